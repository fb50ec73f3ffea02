//! The product's main scenario: `scenarios/formation.toml`, the camera on
//! its gimbal in the loop on the 6-DOF follower over the seed's 140 s target manoeuvres, the
//! Kalman estimator, the seed's slot in the target's velocity frame, light Dryden turbulence.
//!
//! Shown, on three turbulence streams and three other camera settings: no frame is lost; b̂
//! ends within 5% of the true 8 ft span with the truth inside b̂ ± 3σ_b; the position is
//! within 3 ft RMS of the slot per axis over the last 20 s; the gimbal never reaches a limit.
//! In moderate turbulence, the streams 1 to 5 lose no frame and stay within 5 ft RMS;
//! at 1920x1080 the target, binned beyond 160 px, is identified and the slot held as at
//! 640x480. And a 2 s occlusion in the middle of the run: the target is found again within 1 s of its
//! end, and the follower is back within 3 ft of the slot within 15 s.

use crate::common;

use wingman::output::RunReport;
use wingman::output::summary::{RunStatus, Summary};

/// The criteria for one run of the main scenario.
fn assert_identified_and_on_the_slot(s: &Summary) {
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    assert_eq!(s.lost_frames, 0, "episodes {:?}", s.loss_episodes);
    let sigma = s.b_sigma_final_ft.expect("Kalman run");
    let error = s.b_hat_final_ft - s.b_true_ft;
    assert!(error.abs() < 0.05 * s.b_true_ft, "b̂ {}", s.b_hat_final_ft);
    assert!(
        error.abs() <= 3.0 * sigma,
        "b̂ {} ± 3 × {sigma}",
        s.b_hat_final_ft
    );
    for (axis, rms) in s.rms_error_last20s_ft.iter().enumerate() {
        assert!(*rms < 3.0, "axis {axis}: RMS {rms} ft");
    }
    let gimbal = s.gimbal.expect("gimballed camera");
    assert_eq!(gimbal.rows_at_limit, 0, "{gimbal:?}");
}

/// One stream of the main scenario, with the costs and saved frames checked on the first.
fn run_stream(seed: u32) -> RunReport {
    let seed_key = format!("run.seed={seed}");
    let report = common::run("formation", &[&seed_key, "output.frames_every=0"]);
    let s = &report.summary;
    println!(
        "seed {seed}: b̂ {:.3} ± {:.3} ft, RMS {:.2?} ft, {:.1}x real time",
        s.b_hat_final_ft,
        s.b_sigma_final_ft.unwrap_or(f64::NAN),
        s.rms_error_last20s_ft,
        s.realtime_factor
    );
    assert_identified_and_on_the_slot(s);
    report
}

#[test]
fn stream_1_identifies_the_target_and_holds_the_slot() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scenario = common::load("formation", &["output.frames_every=600"]);
    let report = common::run_in(&scenario, "formation", dir.path());
    let s = &report.summary;
    assert_identified_and_on_the_slot(s);
    assert_eq!(s.frames, 4200, "30 Hz for 140 s");
    let cost = s.per_frame_ms.expect("camera run");
    for (stage, ms) in [
        ("render", cost.render),
        ("readback", cost.readback),
        ("vision", cost.vision),
        ("estimator", cost.estimator),
        ("guidance", cost.guidance),
        ("control", cost.control),
        ("plant", cost.plant),
    ] {
        assert!(ms > 0.0 && ms.is_finite(), "{stage}: {ms} ms");
    }
    let a = s.aircraft.as_ref().expect("6-DOF run");
    assert_eq!((a.limit_ticks.elevator, a.limit_ticks.rudder), (0, 0));
    // One frame in 600 saved: frames 0, 600, ..., 3600.
    let saved = std::fs::read_dir(dir.path().join("frames"))
        .expect("frames")
        .count();
    assert_eq!(saved, 7);
}

#[test]
fn stream_4_identifies_the_target_and_holds_the_slot() {
    run_stream(4);
}

#[test]
fn stream_7_identifies_the_target_and_holds_the_slot() {
    run_stream(7);
}

/// The identification does not hang on one camera: a slower frame rate, two frames of
/// latency and a coarser image each keep it.
#[test]
fn other_camera_settings_identify_the_target_and_hold_the_slot() {
    for overrides in [
        ["camera.rate_hz=15", "camera.latency_frames=1"],
        ["camera.rate_hz=30", "camera.latency_frames=2"],
        ["camera.width_px=320", "camera.height_px=240"],
    ] {
        let mut all = overrides.to_vec();
        all.push("output.frames_every=0");
        let report = common::run("formation", &all);
        println!("{overrides:?}: {}", report.summary.to_json());
        assert_identified_and_on_the_slot(&report.summary);
    }
}

/// The moderate-turbulence streams 1 to 5: no frame lost, RMS of R - R_c below 5 ft
/// per axis over the last 20 s. These five are the issue's, not chosen for passing (what the
/// other streams give: docs/findings.md, Measurements behind the code and tests).
#[test]
fn moderate_turbulence_streams_1_to_5_keep_the_target_and_the_slot() {
    for seed in 1..=5 {
        let seed_key = format!("run.seed={seed}");
        let report = common::run(
            "formation",
            &[
                &seed_key,
                "atmosphere.turbulence=moderate",
                "output.frames_every=0",
            ],
        );
        let s = &report.summary;
        println!(
            "moderate, stream {seed}: lost {}, RMS {:.2?} ft",
            s.lost_frames, s.rms_error_last20s_ft
        );
        assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
        assert_eq!(s.lost_frames, 0, "stream {seed}: {:?}", s.loss_episodes);
        for (axis, rms) in s.rms_error_last20s_ft.iter().enumerate() {
            assert!(*rms < 5.0, "stream {seed}, axis {axis}: RMS {rms} ft");
        }
    }
}

/// The main scenario at 1920x1080 bins its target beyond 160 px (`camera.measure_max_length_px`):
/// most frames are binned, and the run keeps the target and the slot as at 640x480.
#[test]
fn full_hd_camera_bins_the_target_and_holds_the_slot() {
    let report = common::run(
        "formation",
        &[
            "camera.width_px=1920",
            "camera.height_px=1080",
            "output.frames_every=0",
        ],
    );
    let s = &report.summary;
    let regions = s.frame_regions.expect("camera run");
    println!(
        "1920x1080: {regions:?}, {:.1}x real time",
        s.realtime_factor
    );
    assert!(regions.binned > 3500, "{regions:?}");
    assert_identified_and_on_the_slot(s);
}

/// ‖R - R_c‖ at each logged row, ft.
fn slot_errors(report: &RunReport) -> Vec<(f64, f64)> {
    report
        .logged
        .iter()
        .map(|s| (s.t_s, (s.relative_ned_ft - s.command_ned_ft).norm()))
        .collect()
}

#[test]
fn a_two_second_occlusion_is_searched_out_and_the_slot_regained() {
    let (hide_s, show_s) = (69.0, 71.0);
    let occlusion = format!("camera.occlusion_s=[{hide_s}, {show_s}]");
    let report = common::run("formation", &[&occlusion, "output.frames_every=0"]);
    let s = &report.summary;
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    let [episode] = s.loss_episodes[..] else {
        panic!("one loss episode expected: {:?}", s.loss_episodes);
    };
    assert!((episode.start_s - hide_s).abs() < 0.05, "{episode:?}");
    assert!(episode.found, "{episode:?}");
    let found_s = episode.start_s + episode.length_s;
    assert!(found_s <= show_s + 1.0, "found at {found_s} s");
    let back_s = slot_errors(&report)
        .into_iter()
        .find(|(t, e)| *t >= show_s && *e < 3.0)
        .map(|(t, _)| t);
    assert!(
        back_s.is_some_and(|t| t <= show_s + 15.0),
        "back within 3 ft at {back_s:?} s"
    );
}
