//! A run in a world (`[scene] kind = "world"`): the frames saved with `output.frames_every`
//! show the scene (ground below the horizon, sky above it); the summary's `background` counts
//! every frame whose target was in front of the camera once, by what lay behind it; a run
//! without the section has no such counts (its frames are those of `camera.sky`); a scene key
//! out of range is refused with exit code 2, naming it.

use crate::common::*;
use wingman::render::CameraImage;

/// Two seconds of formation_scene.toml, saving every 15th frame.
#[test]
fn saved_frames_show_the_scene_and_the_summary_counts_backgrounds() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scenario = load(
        "formation_scene",
        &[
            "run.duration_s=2",
            "output.frames_every=15",
            "output.overlay=false",
        ],
    );
    let report = run_in(&scenario, "formation_scene", dir.path());
    let counts = report.summary.background.expect("a world's run has counts");
    let counted: u64 = [counts.sky, counts.ground, counts.horizon, counts.cloud]
        .iter()
        .map(|c| c.frames)
        .sum();
    // The target starts 200 ft ahead and 30 ft below: in front of the camera on every frame;
    // each is measured when the next is taken (latency_frames = 1), so all but the last.
    assert_eq!(counted, report.summary.frames - 1, "{counts:?}");
    let lost: u64 = [counts.sky, counts.ground, counts.horizon, counts.cloud]
        .iter()
        .map(|c| c.lost)
        .sum();
    assert_eq!(lost, report.summary.lost_frames);

    // The first frame: the camera looks ahead and down at the target 30 ft below, over the
    // ground 300 ft below: its bottom row is fields (green above blue), its top row is sky
    // or cloud (blue at least green) unless the camera looks down too steeply to see any.
    let frame = CameraImage::read_png(&dir.path().join("frames/000000.png")).expect("frame saved");
    let (w, h) = (frame.width_px, frame.height_px);
    let ground_like = |v: u32| {
        (0..w)
            .filter(|&u| {
                let p = frame.pixel(u, v).expect("inside");
                p[1] > p[2]
            })
            .count() as f64
            / f64::from(w)
    };
    assert!(
        ground_like(h - 1) > 0.9,
        "bottom row {}",
        ground_like(h - 1)
    );
    assert!(ground_like(0) < 0.1, "top row {}", ground_like(0));
}

#[test]
fn without_a_scene_there_are_no_counts() {
    let report = run("vision_ch4_formation", &["run.duration_s=1"]);
    assert!(report.summary.frames > 0);
    assert_eq!(report.summary.background, None);
}

#[test]
fn a_scene_key_out_of_range_is_named() {
    let (code, stderr) = wingman_cli(&[
        "run",
        "scenarios/formation_scene.toml",
        "--set",
        "scene.cloud_coverage=1.5",
        "--out",
        "/nonexistent/never",
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("scene.cloud_coverage = 1.5") && stderr.contains("allowed [0, 1]"),
        "{stderr}"
    );
}
