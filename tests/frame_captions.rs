//! Invariant: a saved frame's overlay says when the frame was exposed (`FRAME N T t S`) and
//! shows the gimbal's angles and command of that same instant, not of the later tick at
//! which the frame was measured and saved (with one frame of latency, measuring a frame
//! overlaps the exposure of the next, a frame period later).

use crate::common;

use wingman::output::frame_images::{frame_caption, gimbal_captions};
use wingman::render::CameraImage;
use wingman::vision::overlay::draw_caption;

#[test]
fn saved_frame_captions_show_its_exposure() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scenario = common::load(
        "formation",
        &[
            "run.duration_s=1.5",
            "run.log_every=1",
            "output.frames_every=30",
            "output.overlay=true",
        ],
    );
    let report = common::run_in(&scenario, "formation", dir.path());
    let dt_s = scenario.run.dt_s;
    let frame = report
        .logged
        .iter()
        .filter_map(|s| s.frame)
        .find(|f| f.index == 30)
        .expect("frame 30 reached the guidance");
    let row_at = |t_s: f64| {
        report
            .logged
            .iter()
            .find(|s| (s.t_s - t_s).abs() < 0.5 * dt_s)
            .expect("a telemetry row at every tick")
    };
    let exposure = row_at(frame.t_s);
    let saved = row_at(frame.t_s + 1.0 / scenario.camera.rate_hz);
    let expected: Vec<String> = [frame_caption(30, frame.t_s)]
        .into_iter()
        .chain(gimbal_captions(exposure.gimbal))
        .collect();
    assert_eq!(expected[0], "FRAME 30 T 1.000 S");
    assert_ne!(
        gimbal_captions(exposure.gimbal),
        gimbal_captions(saved.gimbal),
        "the gimbal moves between exposure and saving, so the test can tell them apart"
    );
    let png = CameraImage::read_png(&dir.path().join("frames/000030.png")).expect("frame 30 saved");
    let (w, h) = (png.width_px, png.height_px);
    let mut redrawn = png.rgba.clone();
    for (k, line) in expected.iter().enumerate() {
        draw_caption(&mut redrawn, w, h, k + 1, line).expect("caption fits");
    }
    assert!(
        redrawn == png.rgba,
        "the saved frame's captions are not {expected:?}"
    );
}
