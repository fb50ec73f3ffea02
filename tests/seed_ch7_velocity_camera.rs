//! The seed's Chapter 7 formation through pixels:
//! `scenarios/seed_ch7_velocity_camera.toml`, the seed's inertial R_c = [32, 8, 0] ft and
//! Chapter 7 geometry flown by the 6-DOF follower with its camera on a pan/tilt gimbal, the
//! Kalman estimator and light turbulence.
//!
//! Shown on three turbulence streams: no frame lost; the gimbal never at a limit; the
//! position within 3 ft RMS of R_c per axis over the last 20 s; b̂ within 5% of the size the
//! camera sees (the summary's apparent size: seen from the side, the 6 ft fuselage, not the
//! 8 ft span; the scenario file says why b̂ cannot approach 8 ft here). Without the gimbal the
//! same run loses the target. With the airframe size model b̂ reads the 8 ft size itself.

use crate::common;

use wingman::output::summary::{RunStatus, Summary};

fn assert_flies_the_seed_formation(s: &Summary) {
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    assert_eq!(s.lost_frames, 0, "episodes {:?}", s.loss_episodes);
    let gimbal = s.gimbal.expect("gimballed camera");
    assert_eq!(gimbal.rows_at_limit, 0, "{gimbal:?}");
    for (axis, rms) in s.rms_error_last20s_ft.iter().enumerate() {
        assert!(*rms < 3.0, "axis {axis}: RMS {rms} ft");
    }
    let apparent = s.apparent_size_last20s_ft.expect("camera run").measured;
    assert!(
        (s.b_hat_final_ft - apparent).abs() < 0.05 * apparent,
        "b̂ {} against the apparent {apparent} ft",
        s.b_hat_final_ft
    );
}

/// Runs stream `seed` of the scenario with `overrides` besides, without saved frames.
fn run_stream_with(seed: u32, overrides: &[&str]) -> Summary {
    let seed_key = format!("run.seed={seed}");
    let keys: Vec<&str> = [seed_key.as_str(), "output.frames_every=0"]
        .into_iter()
        .chain(overrides.iter().copied())
        .collect();
    let report = common::run("seed_ch7_velocity_camera", &keys);
    println!("seed {seed}: {}", report.summary.to_json());
    report.summary
}

fn run_stream(seed: u32) -> Summary {
    run_stream_with(seed, &[])
}

#[test]
fn stream_1_flies_the_seed_formation_through_pixels() {
    assert_flies_the_seed_formation(&run_stream(1));
}

#[test]
fn stream_3_flies_the_seed_formation_through_pixels() {
    assert_flies_the_seed_formation(&run_stream(3));
}

#[test]
fn stream_5_flies_the_seed_formation_through_pixels() {
    assert_flies_the_seed_formation(&run_stream(5));
}

/// The same run with the camera fixed on the nose: the target leaves the field of view in
/// its first turn (a short run shows it).
#[test]
fn a_fixed_camera_loses_the_target() {
    let report = common::run(
        "seed_ch7_velocity_camera",
        &[
            "camera.gimbal.kind=none",
            "run.duration_s=40",
            "output.frames_every=0",
        ],
    );
    let s = &report.summary;
    assert!(s.lost_frames > 0, "{s:?}");
    // Lost for good: the run stops as `lost` (run.stop_after_lost_s) rather than completing.
    assert_eq!(s.status, RunStatus::Lost, "{:?}", s.message);
}

/// With `estimator.size_model = "airframe"` b̂ reads the target's 8 ft size side-on, within
/// 5% and the truth inside ±3σ_b, and the model puts the bearing point (the maximal length's
/// midpoint) where the vision measures it, within 1.5 px of its mean offset (13 px along the
/// fuselage), and the slot within 3 ft RMS per axis. On this stream, without the bearing
/// point's offset, b̂ ended 7.0% low (z -2.9): the offset's change with the view read as the
/// target's motion.
#[test]
fn the_airframe_model_reads_the_targets_size_side_on() {
    let s = &run_stream_with(10, &["estimator.size_model=\"airframe\""]);
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    assert_eq!(s.lost_frames, 0, "episodes {:?}", s.loss_episodes);
    for (axis, rms) in s.rms_error_last20s_ft.iter().enumerate() {
        assert!(*rms < 3.0, "axis {axis}: RMS {rms} ft");
    }
    let (b_hat, sigma) = (s.b_hat_final_ft, s.b_sigma_final_ft.expect("Kalman σ_b"));
    assert!((b_hat / 8.0 - 1.0).abs() < 0.05, "b̂ {b_hat} ft");
    assert!((b_hat - 8.0).abs() < 3.0 * sigma, "b̂ {b_hat} ± {sigma} ft");
    let view = s.airframe_view_last20s.expect("airframe model");
    for k in 0..2 {
        let (predicted, measured) = (
            view.predicted_bearing_offset_px[k],
            view.measured_bearing_offset_px[k],
        );
        assert!((predicted - measured).abs() < 1.5, "{view:?}");
    }
    assert!(view.measured_bearing_offset_px[0].abs() > 5.0, "{view:?}");
}
