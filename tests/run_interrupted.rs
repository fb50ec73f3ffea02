//! A signal stops a run cleanly: SIGINT (Ctrl-C) or SIGTERM (a batch scheduler's
//! pre-emption) stops it at the next tick, the telemetry is flushed in whole rows, the summary
//! says `interrupted`, the plots are drawn, and the exit code is 128 + the signal (130, 143).
//! A group run (the platoon) stopped by Ctrl-C writes its `group.json` and exits 130 too.

use crate::common;

#[test]
fn sigint_writes_summary_and_plots_and_exits_130() {
    stops_cleanly(libc::SIGINT, 130);
}

#[test]
fn sigterm_writes_summary_and_plots_and_exits_143() {
    stops_cleanly(libc::SIGTERM, 143);
}

/// Sends `signal` to a long run once it logs, and checks what it left and its exit code.
fn stops_cleanly(signal: libc::c_int, exit_code: i32) {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("run");
    let mut child = common::spawn_long_run_logging(&out);
    let telemetry = out.join("telemetry.csv");
    let pid = libc::pid_t::try_from(child.id()).expect("pid");
    // SAFETY: sends the signal to the child this test started.
    assert_eq!(unsafe { libc::kill(pid, signal) }, 0);
    let status = child.wait().expect("child ends");
    assert_eq!(status.code(), Some(exit_code));
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(out.join("summary.json")).expect("summary written"),
    )
    .expect("summary is JSON");
    assert_eq!(summary["status"], "interrupted");
    assert!(summary["duration_s"].as_f64().expect("duration") < 10_000.0);
    let text = std::fs::read_to_string(&telemetry).expect("telemetry");
    let columns = text.lines().next().expect("header").split(',').count();
    assert!(text.ends_with('\n') && text.lines().count() > 2);
    assert!(
        text.lines().all(|l| l.split(',').count() == columns),
        "a cut-off row"
    );
    assert!(
        out.join("plots/relative_position.png").is_file(),
        "plots drawn"
    );
}

#[test]
fn sigint_stops_a_group_run_with_130() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("platoon");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_wingman"))
        .args(["run", "scenarios/platoon.toml", "--quiet", "--out"])
        .arg(&out)
        .args(["--set", "output.plots=false"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("NODEVICE_SELECT", "1")
        .spawn()
        .expect("binary starts");
    // The folder is marked once the group is built and about to step.
    let started = std::time::Instant::now();
    while !out.join(".wingman-run").is_file() {
        assert!(started.elapsed().as_secs() < 60, "the group never started");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    let pid = libc::pid_t::try_from(child.id()).expect("pid");
    // SAFETY: sends the signal to the child this test started.
    assert_eq!(unsafe { libc::kill(pid, libc::SIGINT) }, 0);
    let status = child.wait().expect("child ends");
    assert_eq!(status.code(), Some(130));
    let group: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(out.join("group.json")).expect("group.json written"),
    )
    .expect("group.json is JSON");
    let stopped_by = group["stopped_by"].as_str().expect("stopped");
    assert!(stopped_by.contains("Interrupted"), "{stopped_by}");
    assert!(group["duration_s"].as_f64().expect("duration") < 140.0);
}
