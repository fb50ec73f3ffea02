//! A run that loses its target does not read as a success: once the target has
//! gone unmeasured longer than `run.stop_after_lost_s` the run stops with status `lost`,
//! keeps its telemetry, summary and plots, names the lost frames on its last line and exits
//! 1. With the limit at 0 the same run goes on to its end.

use crate::common::wingman_cli as wingman;

#[test]
fn a_target_lost_longer_than_the_limit_stops_the_run() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("lost");
    // The inertial command leaves the 60° field of view at about t = 20 s; a first
    // loss of 2.9 s is survived, the second, from t = 22.6 s, stops the run 5 s later.
    let (code, stderr) = wingman(&[
        "run",
        "scenarios/vision_ch4_formation.toml",
        "--out",
        out.to_str().expect("utf-8"),
        "--set",
        "guidance.command_frame=inertial",
        "--quiet",
    ]);
    assert_eq!(code, 1, "{stderr}");
    let last = stderr.trim_end().lines().last().unwrap_or_default();
    assert!(
        last.contains("target lost") && last.contains("lost;"),
        "{last}"
    );
    assert!(last.contains("frames,"), "{last}");
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(out.join("summary.json")).expect("summary kept"),
    )
    .expect("summary is JSON");
    assert_eq!(summary["status"], "lost");
    let duration_s = summary["duration_s"].as_f64().expect("duration");
    assert!(
        (20.0..60.0).contains(&duration_s),
        "stopped at {duration_s} s"
    );
    let last_episode = summary["loss_episodes"]
        .as_array()
        .and_then(|e| e.last())
        .expect("a loss episode");
    assert_eq!(last_episode["found"], false);
    // 5 s at 30 Hz, and not more: the run stopped at the limit.
    let frames = last_episode["frames"].as_u64().expect("frames");
    assert!(
        (149..=152).contains(&frames),
        "{frames} frames in the last loss"
    );
    assert!(summary["lost_frames"].as_u64().expect("lost frames") >= frames);
    let telemetry = std::fs::read_to_string(out.join("telemetry.csv")).expect("telemetry");
    let last_t: f64 = telemetry
        .lines()
        .last()
        .and_then(|l| l.split(',').next())
        .and_then(|t| t.parse().ok())
        .expect("last row's time");
    assert!(
        (last_t - duration_s).abs() < 1e-6,
        "telemetry ends at {last_t} s"
    );
    assert!(
        out.join("plots/relative_position.png").is_file(),
        "plots kept"
    );
}
