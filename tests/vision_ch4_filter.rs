//! The Kalman estimator identifies the target's size on pixels whatever the camera's rate and
//! latency: `vision_ch4_formation.toml` with `estimator.kind = "kalman"` and the
//! bearing read at the maximal length's midpoint (as `formation.toml`), at three of the nine
//! rate/latency settings docs/formation.md tabulates (measured over all nine: b̂ 7.75-7.82 ft).
//! The adaptive law of the same scenario identifies b only thanks to its 33 ms delay; the
//! filter fuses each frame at its capture time, so the delay does not matter.

use crate::common;

use wingman::output::summary::RunStatus;

fn assert_identifies_b(rate_hz: u32, latency_frames: u32) {
    let rate = format!("camera.rate_hz={rate_hz}");
    let latency = format!("camera.latency_frames={latency_frames}");
    let report = common::run(
        "vision_ch4_formation",
        &[
            "estimator.kind=kalman",
            "camera.bearing_point=length_midpoint",
            "output.frames_every=0",
            &rate,
            &latency,
        ],
    );
    let s = &report.summary;
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    assert_eq!(s.lost_frames, 0);
    let b_true_ft = s.b_true_ft;
    assert!(
        (s.b_hat_final_ft - b_true_ft).abs() < 0.05 * b_true_ft,
        "{rate_hz} Hz, {latency_frames} frames late: b̂ {} ft",
        s.b_hat_final_ft
    );
}

#[test]
fn fifteen_hz_without_latency_identifies_b() {
    assert_identifies_b(15, 0);
}

#[test]
fn thirty_hz_one_frame_late_identifies_b() {
    assert_identifies_b(30, 1);
}

#[test]
fn sixty_hz_two_frames_late_identifies_b() {
    assert_identifies_b(60, 2);
}
