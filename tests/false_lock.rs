//! A run that tracks something other than the target says so: formation.toml with a 90° field
//! of view and heavy pixel noise locks onto noise blobs (measured: b̂ at its 30 ft bound, the
//! follower hundreds of feet off its slot). The truth check ends it as `false_lock` after
//! `run.stop_after_lost_s`, with the off-target frames and the follower's own evidence (b̂ at
//! a bound) in the summary's `track_check`, and the CLI exits 1. The same scenario without the
//! noise has no off-target frame and no warning, and its telemetry's `kf_nis`, once per fused
//! frame, averages to the summary's normalised innovation.

use crate::common::{repo_root, run, wingman_cli_in};
use wingman::output::summary::RunStatus;

const NOISE_LOCK: [&str; 4] = [
    "camera.hfov_deg=90",
    "camera.noise_std_grey=20",
    "run.duration_s=30",
    "output.frames_every=0",
];

#[test]
fn a_noise_lock_ends_the_run_as_false_lock() {
    let report = run("formation", &NOISE_LOCK);
    let s = &report.summary;
    assert_eq!(s.status, RunStatus::FalseLock, "{:?}", s.message);
    assert!(s.duration_s < 30.0, "stopped at {} s", s.duration_s);
    assert!(s.message.as_deref().unwrap().starts_with("false lock"));
    let check = &s.track_check;
    assert!(check.off_target_frames > 30, "{check:?}");
    assert!(
        check
            .warnings
            .iter()
            .any(|w| w.contains("other than the target")),
        "{check:?}"
    );
}

#[test]
fn a_clean_run_is_on_target_throughout() {
    let report = run("formation", &["run.duration_s=15", "output.frames_every=0"]);
    let check = &report.summary.track_check;
    assert_eq!(report.summary.status, RunStatus::Completed);
    assert_eq!(check.off_target_frames, 0, "{check:?}");
    assert!(check.warnings.is_empty(), "{check:?}");
    let nis = check.nis_mean_last20s.expect("the filter fused frames");
    assert!(nis > 0.0 && nis < 3.0, "mean NIS {nis}");
    // The telemetry's `kf_nis` holds each fused frame's νᵀ S⁻¹ ν while the frame is held:
    // once per frame, they average to the summary's figure (the run is under 20 s long).
    let mut per_frame: Vec<(u64, f64)> = Vec::new();
    for s in &report.logged {
        let (Some(frame), Some(true), Some(nis)) = (s.frame, s.frame_trusted, s.filter_nis) else {
            continue;
        };
        if per_frame
            .last()
            .is_none_or(|(index, _)| *index != frame.index)
        {
            per_frame.push((frame.index, nis));
        }
    }
    let mean = per_frame.iter().map(|(_, n)| n).sum::<f64>() / per_frame.len() as f64;
    assert!(per_frame.len() > 300, "{} frames", per_frame.len());
    assert!(
        (mean - nis).abs() < 1e-9 * nis,
        "telemetry {mean} against summary {nis}"
    );
}

#[test]
fn the_cli_exits_1_on_a_false_lock() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = repo_root().join("scenarios/formation.toml");
    let scenario = scenario.to_str().unwrap();
    let mut args = vec!["run", scenario, "--out", "out", "--quiet"];
    for set in NOISE_LOCK.iter().chain(&["output.plots=false"]) {
        args.extend(["--set", set]);
    }
    let (code, stderr) = wingman_cli_in(dir.path(), &args);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("false lock"), "{stderr}");
}
