//! The tracking window measures what the whole image measures.
//!
//! (1) Over the 60-pose test set, a frame drawn, read back and measured only in the window the
//! tracker predicts from the whole image's measurement has the whole image's centroid and
//! maximal length: to the bit on the noise-free uniform sky of the camera scenarios (the
//! region holds the whole frame's bytes, the background of a uniform border is exact, and the
//! measurement's arithmetic is done in image coordinates), within 0.05 px on a gradient sky
//! (the quadratic sky is fitted on the window's border, not the image's: 8-bit rounding moves
//! the fit by a fraction of a grey level: measured 3e-3 px) and, with σ = 2 grey levels of
//! noise, by less than the noise moves it (the window's border gives another estimate of the
//! noise, so another threshold and coverage debiasing: measured 0.01 px on most poses, 0.26 /
//! 1.8 px on a 250 ft pose whose thin wing the noise breaks up, where another draw of the
//! noise moves it by 1.3 / 7 px).
//! The noise's own effect is larger: two draws of the noise move the measurement by more
//! than twice as much (RMS over the poses) as measuring it in the window does.
//! (2) The closed loop of `formation.toml` flies the same 30 s with either pipeline: every
//! frame record and every relative position equal. (3) A target that jumps out of its window
//! between two frames is measured in the same frame: the frame is drawn and measured again
//! whole, its record is the whole pipeline's, and the next frames are windowed again; a
//! sudden roll of the follower is no such jump, because the tracker carries the window with
//! the camera's rotation. (4) With `camera.measure_max_length_px`, a frame whose target is
//! longer than the limit is the measurement of the binned camera: at 1920x1080 a target
//! 222 px long (limit 160) is measured as the 960x540 camera measures it, to the bit, in the
//! image's coordinates (the binned window equals the binned whole image, as in (1), and the
//! binning's scale by 2 is exact). (5) Saving frames changes no measurement: a frame to be
//! saved is measured in its window, binned when it would be, and only then drawn whole for
//! the saved image.

use crate::common;

use crate::render_support::*;
use wingman::frames::{EulerAngles, Mat3, Vec3};
use wingman::render::camera::CameraIntrinsics;
use wingman::render::{Background, PixelNoise, RenderSettings, Renderer, Sky};
use wingman::sensing::camera::WindowCounts;
use wingman::sensing::{CameraConfig, CameraSensor, CaptureGeometry, FollowerPose};
use wingman::sim::{Simulation, StepOutcome};
use wingman::vision::{BlobMeasurement, BlobSelection, BlobStatus, TrackingWindow, VisionPipeline};

/// Differences of centroid (distance) and maximal length between two measurements of the
/// same poses, px.
#[derive(Debug, Default)]
struct Differences {
    centroid_px: Vec<f64>,
    length_px: Vec<f64>,
}

impl Differences {
    fn push(&mut self, a: &BlobMeasurement, b: &BlobMeasurement) {
        self.centroid_px
            .push((a.centroid_u_px - b.centroid_u_px).hypot(a.centroid_v_px - b.centroid_v_px));
        self.length_px.push(a.max_length_px - b.max_length_px);
    }

    /// Largest centroid and length differences, px.
    fn max(&self) -> (f64, f64) {
        let largest = |v: &[f64]| v.iter().fold(0.0f64, |m, d| m.max(d.abs()));
        (largest(&self.centroid_px), largest(&self.length_px))
    }

    /// RMS centroid and length differences, px.
    fn rms(&self) -> (f64, f64) {
        let rms = |v: &[f64]| (v.iter().map(|d| d * d).sum::<f64>() / v.len() as f64).sqrt();
        (rms(&self.centroid_px), rms(&self.length_px))
    }
}

/// Over the 60 poses on `background`: windowed against whole-image measurements, and (the
/// measurement's own noise) the whole image's measurements of two noise draws; fails when a
/// window's measurement reaches its edge or a pose is not measured `Ok`.
fn window_against_whole(background: Background) -> (Differences, Differences) {
    let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
    let mut settings = RenderSettings::new(cam);
    settings.msaa_samples = 4;
    settings.background = background;
    let mesh = aircraft();
    let mut renderer = Renderer::new(gpu(), settings, &mesh).unwrap_or_else(|e| panic!("{e}"));
    let mut vision =
        VisionPipeline::new(scenario_vision_config()).unwrap_or_else(|e| panic!("{e}"));
    let mut tracker = TrackingWindow::new(cam, 1.0 / 30.0, vision.region_clearance_px());
    let (mut window, mut noise) = (Differences::default(), Differences::default());
    for (k, case) in sixty_poses().iter().enumerate() {
        let k = k as u64;
        let frame = renderer
            .render(&case.pose, k)
            .unwrap_or_else(|e| panic!("{e}"));
        let whole = measure_largest(&mut vision, frame);
        assert_eq!(whole.status, BlobStatus::Ok, "{case:?}");
        // The tracker's window one frame later, the camera not turning.
        tracker.observe(k, &whole, &Mat3::identity());
        let region = tracker
            .predict(k + 1, &Mat3::identity())
            .unwrap_or_else(|| panic!("{case:?}: no window"));
        let part = renderer
            .render_region(&case.pose, &region, k)
            .unwrap_or_else(|e| panic!("{e}"));
        let m = vision
            .measure_region(&part.rgba, &region, &cam, BlobSelection::Largest)
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(!m.reaches_inner_edge, "{case:?}: {region:?}");
        assert_eq!(m.blob.status, BlobStatus::Ok, "{case:?}");
        window.push(&m.blob, &whole);
        if background.noise.is_some() {
            let other_draw = renderer
                .render(&case.pose, k + 1000)
                .unwrap_or_else(|e| panic!("{e}"));
            noise.push(&measure_largest(&mut vision, other_draw), &whole);
        }
    }
    eprintln!(
        "{background:?}: window - whole: max {:.2e} / {:.2e} px, rms {:.2e} / {:.2e} px (centroid / length)",
        window.max().0,
        window.max().1,
        window.rms().0,
        window.rms().1
    );
    (window, noise)
}

#[test]
fn windowed_measurements_equal_whole_image_measurements_over_60_poses() {
    let (window, _) = window_against_whole(Background::default());
    assert_eq!(window.max(), (0.0, 0.0));
    let gradient = Sky::VerticalGradient {
        top_rgb: [150, 180, 225],
        bottom_rgb: [215, 225, 235],
    };
    let (window, _) = window_against_whole(Background {
        sky: gradient,
        noise: None,
    });
    let (centroid, length) = window.max();
    assert!(centroid <= 0.05 && length <= 0.05, "{centroid} {length}");
    let (window, noise) = window_against_whole(Background {
        sky: gradient,
        noise: Some(PixelNoise {
            std_grey_levels: 2.0,
            seed: 1,
        }),
    });
    let ((wc, wl), (nc, nl)) = (window.rms(), noise.rms());
    eprintln!("two noise draws: rms {nc:.2e} / {nl:.2e} px");
    assert!(wc <= 0.5 * nc && wl <= 0.5 * nl, "{wc} {wl} vs {nc} {nl}");
}

/// Runs `formation.toml` for 30 s with `pipeline`: every logged snapshot, and how its frames
/// were drawn.
fn formation_30_s(pipeline: &str) -> (Vec<wingman::sim::Snapshot>, WindowCounts) {
    let pipeline = format!("camera.pipeline={pipeline}");
    let scenario = common::load(
        "formation",
        &["run.duration_s=30", "output.frames_every=0", &pipeline],
    );
    let mut sim = Simulation::new(&scenario).unwrap_or_else(|e| panic!("{e}"));
    let mut logged = vec![sim.snapshot()];
    while let Ok(StepOutcome::Running) = sim.step() {
        logged.push(sim.snapshot());
    }
    let counts = sim.camera().expect("camera run").window_counts();
    (logged, counts)
}

#[test]
fn formation_flies_the_same_with_the_window_as_with_the_whole_image() {
    let (windowed, counts) = formation_30_s("window");
    let (whole, whole_counts) = formation_30_s("whole");
    eprintln!("window: {counts:?}; whole: {whole_counts:?}");
    assert_eq!(windowed.len(), whole.len());
    // 900 frames: the first two drawn whole (acquisition: the second is drawn before the
    // first is measured, one frame of latency), the rest in the window.
    assert_eq!(counts.whole_untracked, 2);
    assert!(counts.windowed >= 895, "{counts:?}");
    assert_eq!(whole_counts.windowed, 0);
    for (a, b) in windowed.iter().zip(&whole) {
        assert_eq!(a.frame, b.frame, "t = {} s", a.t_s);
        assert_eq!(a.relative_ned_ft, b.relative_ned_ft, "t = {} s", a.t_s);
    }
}

/// A camera on `formation.toml`'s settings with `pipeline`, latency `latency_frames`.
fn camera(pipeline: &str, latency_frames: u32) -> CameraSensor {
    camera_with(&[
        &format!("camera.pipeline={pipeline}"),
        &format!("camera.latency_frames={latency_frames}"),
    ])
}

/// A camera on `formation.toml`'s settings with `overrides`, saving no frames.
fn camera_with(overrides: &[&str]) -> CameraSensor {
    camera_saving(overrides, 0)
}

/// A camera on `formation.toml`'s settings with `overrides`, saving every `every`th frame
/// (0: none).
fn camera_saving(overrides: &[&str], every: u32) -> CameraSensor {
    let saving = format!("output.frames_every={every}");
    let mut keys = overrides.to_vec();
    keys.push(&saving);
    let scenario = common::load("formation", &keys);
    CameraSensor::new(&CameraConfig::of(&scenario)).unwrap_or_else(|e| panic!("{e}"))
}

/// Frame `k` of a sequence: the target 60 ft ahead, 12° right, drifting; a 35° roll of the
/// follower from frame 6 on; the target 25° further left (a jump no tracker predicts) from
/// frame 12 on.
fn geometry(k: u64) -> CaptureGeometry {
    let drift = 0.1 * k as f64;
    let (bearing, roll): (f64, f64) = match k {
        0..6 => (0.21, 0.0),
        6..12 => (0.21, 0.6),
        _ => (0.21 - 0.45, 0.6),
    };
    CaptureGeometry::exact(
        Vec3::new(60.0 * bearing.cos(), 60.0 * bearing.sin() + drift, -4.0),
        EulerAngles::new(0.3, 0.05, 0.4),
        FollowerPose::at_origin(EulerAngles::new(roll, 0.02, 0.0)),
    )
}

/// Takes frame `k` of [`geometry`] with both cameras and asserts that they deliver the same
/// record and measured the same last frame.
fn capture_alike(a: &mut CameraSensor, b: &mut CameraSensor, k: u64) {
    let t_s = k as f64 / 30.0;
    let [delivered_a, delivered_b] = [&mut *a, &mut *b].map(|camera| {
        camera
            .capture(t_s, &geometry(k))
            .unwrap_or_else(|e| panic!("{e}"))
    });
    assert_eq!(delivered_a, delivered_b, "frame {k}");
    assert_eq!(a.last_record(), b.last_record(), "frame {k}");
}

#[test]
fn target_jumping_out_of_its_window_is_recovered_in_the_same_frame() {
    for latency_frames in [0, 1] {
        let mut windowed = camera("window", latency_frames);
        let mut whole = camera("whole", latency_frames);
        let mut before_jump = WindowCounts::default();
        for k in 0..18 {
            capture_alike(&mut windowed, &mut whole, k);
            if let Some(record) = windowed.last_record() {
                assert_eq!(record.status, BlobStatus::Ok, "frame {}", record.index);
            }
            if k == 11 {
                before_jump = windowed.window_counts();
            }
        }
        let counts = windowed.window_counts();
        eprintln!("latency {latency_frames}: {counts:?}");
        // The roll (frame 6) is carried by the tracker: no frame redrawn before the jump.
        assert_eq!(before_jump.redrawn_whole, 0, "{before_jump:?}");
        // Frames drawn before the first measurement are drawn whole.
        let untracked = 1 + u64::from(latency_frames);
        assert_eq!(before_jump.whole_untracked, untracked, "{before_jump:?}");
        // The jump (frame 12) is redrawn whole, as is, with a frame in flight, the frame whose
        // window was placed before the jump was measured; then windows again.
        assert!((1..=2).contains(&counts.redrawn_whole), "{counts:?}");
        assert_eq!(counts.whole_untracked, untracked, "{counts:?}");
        assert_eq!(counts.windowed, 18 - untracked, "{counts:?}");
    }
}

#[test]
fn binned_frames_are_measured_as_the_binned_camera_measures_them() {
    let mut binned = camera_with(&[
        "camera.width_px=1920",
        "camera.height_px=1080",
        "camera.measure_max_length_px=160",
    ]);
    let mut coarse = camera_with(&[
        "camera.width_px=960",
        "camera.height_px=540",
        "camera.pipeline=whole",
    ]);
    let mut compared = 0;
    for k in 0..12 {
        let t_s = k as f64 / 30.0;
        binned
            .capture(t_s, &geometry(k))
            .unwrap_or_else(|e| panic!("{e}"));
        coarse
            .capture(t_s, &geometry(k))
            .unwrap_or_else(|e| panic!("{e}"));
        // One frame of latency: frame k - 1 is the last measured.
        let (Some(a), Some(b)) = (binned.last_record(), coarse.last_record()) else {
            continue;
        };
        assert_eq!(a.status, BlobStatus::Ok, "frame {}", a.index);
        let (a_m, b_m) = (a.measured.expect("measured"), b.measured.expect("measured"));
        // The first two frames are drawn whole at full resolution (no track yet).
        if a.index >= 2 {
            assert!(a_m.b_i_px > 160.0, "frame {}: {} px", a.index, a_m.b_i_px);
            assert_eq!(
                [a_m.y_i_px, a_m.z_i_px, a_m.b_i_px],
                [2.0 * b_m.y_i_px, 2.0 * b_m.z_i_px, 2.0 * b_m.b_i_px],
                "frame {}",
                a.index
            );
            assert_eq!(a.r_measured, b.r_measured, "frame {}", a.index);
            compared += 1;
        }
    }
    assert_eq!(compared, 9);
    let counts = binned.window_counts();
    eprintln!("{counts:?}");
    assert_eq!(counts.binned, 10, "{counts:?}");
    assert_eq!(counts.redrawn_whole, 0, "{counts:?}");
}

#[test]
fn saving_frames_changes_no_measurement() {
    let binned = [
        "camera.width_px=1920",
        "camera.height_px=1080",
        "camera.measure_max_length_px=160",
    ];
    let mut saving = camera_saving(&binned, 1);
    let mut not_saving = camera_with(&binned);
    for k in 0..12 {
        capture_alike(&mut saving, &mut not_saving, k);
        // The frame to save is the whole image, at the image's resolution.
        if saving.last_record().is_some() {
            let (image, _, _) = saving.last_frame().expect("a saved frame is whole");
            assert_eq!((image.width_px, image.height_px), (1920, 1080));
        }
    }
    let (counts, reference) = (saving.window_counts(), not_saving.window_counts());
    eprintln!("saving: {counts:?}; not saving: {reference:?}");
    assert_eq!(counts.binned, reference.binned, "{counts:?}");
    assert_eq!(counts.binned, 10, "{counts:?}");
    // Every windowed frame measured is drawn again whole to be saved: all but the last, one
    // frame of latency.
    assert_eq!(counts.whole_saved, counts.windowed - 1, "{counts:?}");
}
