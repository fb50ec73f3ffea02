//! A camera mount turned by 1° in yaw from its nominal orientation, which the sensing
//! transform does not know (`navigation.camera.mount_misalignment_deg`), makes the measured
//! bearing off by 1°: the renderer draws with the true mount, the sensing transform turns the
//! pixels with the nominal one. The first frame (the same geometry in both runs) is measured
//! with and without the misalignment: the bearings differ by -1° (the camera turned right sees
//! the target 1° further left) and r* turns by 1°, to 0.02° (the target 61 ft ahead, 70 px
//! long, so that the centroid is measured to a tenth of a pixel).

use wingman::frames::Vec3;
use wingman::scenario::Scenario;
use wingman::sensing::FrameRecord;
use wingman::sim::Simulation;

const SCENARIO: &str = r#"
[run]
dt_s = 0.002
[camera]
rate_hz = 25.0
latency_frames = 0
msaa_samples = 4
[target]
initial_position_ft = [60.0, 10.0, 0.0]
[sensor]
mode = "camera"
[navigation.camera]
gimbal_encoder_noise_deg = 0.0
gimbal_encoder_bias_deg = [0.0, 0.0]
exposure_jitter_ms = 0.0
mount_misalignment_deg = [0.0, 0.0, 1.0]
"#;

/// The first frame's record and the camera's focal length, px, with the camera's errors on or
/// off.
fn first_frame(errors: bool) -> (FrameRecord, f64) {
    let mode = format!(
        "navigation.camera.mode={}",
        if errors { "errors" } else { "perfect" }
    );
    let scenario = Scenario::from_toml_str(SCENARIO, std::path::Path::new("m.toml"), &[mode])
        .unwrap_or_else(|e| panic!("{e}"));
    let sim = Simulation::new(&scenario).unwrap_or_else(|e| panic!("{e}"));
    let record = sim
        .camera()
        .and_then(|c| c.last_record())
        .expect("a frame at t = 0");
    assert_eq!(record.t_s, 0.0);
    (record, scenario.camera.focal_length_px())
}

fn bearing_deg(record: &FrameRecord, focal_px: f64) -> f64 {
    let m = record.measured.expect("the target is measured");
    (m.y_i_px / focal_px).atan().to_degrees()
}

#[test]
fn a_one_degree_misalignment_moves_the_bearing_by_one_degree() {
    let (perfect, focal_px) = first_frame(false);
    let (misaligned, _) = first_frame(true);
    let shift_deg = bearing_deg(&misaligned, focal_px) - bearing_deg(&perfect, focal_px);
    assert!(
        (shift_deg + 1.0).abs() < 0.02,
        "bearing moved by {shift_deg:.4}°"
    );
    let r: [Vec3; 2] = [perfect, misaligned].map(|f| f.r_measured.expect("r*"));
    let turn_deg = r[0].angle(&r[1]).to_degrees();
    eprintln!("bearing moved by {shift_deg:.4}°, r* turned by {turn_deg:.4}°");
    assert!((turn_deg - 1.0).abs() < 0.02, "r* turned by {turn_deg:.4}°");
}
