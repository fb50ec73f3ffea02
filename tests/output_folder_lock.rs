//! A run holds its output folder's lock for its whole life: a second run into the folder
//! while the first runs is refused with exit code 2 and one line naming the folder, and
//! touches none of the first's files; the lock goes with the process however it ends
//! (SIGKILL too), so the folder is then reusable. Two runs started together into one folder:
//! while both are alive exactly one runs, and the folder holds its files only (on a loaded
//! machine the second may start after the first ended: both then succeed, and the folder
//! holds the second's files only).

use crate::common;

use std::path::Path;
use std::process::{Command, Stdio};

/// A second run into the folder of a run in progress is refused and changes nothing of it;
/// after the first is killed the folder takes a run again.
#[test]
fn a_second_run_is_refused_while_the_first_holds_the_folder() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("run");
    let mut first = common::spawn_long_run_logging(&out);
    let scenario_before = std::fs::read(out.join("scenario.toml")).expect("first's scenario");
    let out_s = out.to_str().expect("utf-8");
    let (code, stderr) = common::wingman_cli(&[
        "run",
        "scenarios/formation.toml",
        "--out",
        out_s,
        "--quiet",
        "--set",
        "run.duration_s=1",
    ]);
    let still_running = first.try_wait().expect("wait").is_none();
    first.kill().expect("SIGKILL");
    first.wait().expect("reaped");
    assert!(still_running, "the first run ended before the check");
    assert_eq!(code, 2, "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains(out_s) && stderr.contains("another wingman run"),
        "{stderr}"
    );
    let scenario_after = std::fs::read(out.join("scenario.toml")).expect("still there");
    assert_eq!(
        scenario_before, scenario_after,
        "the first run's files changed"
    );
    assert!(!out.join("summary.json").exists(), "a summary was written");

    let args = ["run", "scenarios/formation.toml", "--out", out_s, "--quiet"];
    let (code, stderr) = common::wingman_cli(&[&args[..], &["--set", "run.duration_s=1"]].concat());
    assert_eq!(code, 0, "the killed run's lock stayed: {stderr}");
}

/// Starts `wingman run formation.toml` of `duration_s` into `out`, without plots.
fn start(out: &Path, duration_s: u32) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_wingman"))
        .args(["run", "scenarios/formation.toml", "--quiet", "--out"])
        .arg(out)
        .args(["--set", &format!("run.duration_s={duration_s}")])
        .args(["--set", "output.plots=false"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("NODEVICE_SELECT", "1")
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary starts")
}

/// The simulated duration a run's folder says, in its summary, its resolved scenario and
/// its telemetry's last row.
fn durations_in(out: &Path) -> [f64; 3] {
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("summary"))
            .expect("summary is JSON");
    let scenario: toml::Table = std::fs::read_to_string(out.join("scenario.toml"))
        .expect("scenario")
        .parse()
        .expect("scenario is TOML");
    let telemetry = std::fs::read_to_string(out.join("telemetry.csv")).expect("telemetry");
    let last_t = telemetry
        .lines()
        .last()
        .and_then(|l| l.split(',').next())
        .and_then(|t| t.parse::<f64>().ok())
        .expect("a last row");
    [
        summary["duration_s"].as_f64().expect("duration_s"),
        scenario["run"]["duration_s"]
            .as_float()
            .expect("run.duration_s"),
        last_t,
    ]
}

#[test]
fn concurrent_runs_into_one_folder_never_mix() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut sequential = 0;
    for trial in 0..20 {
        let out = dir.path().join(format!("run{trial}"));
        let runs = [start(&out, 20), start(&out, 21)];
        let ended: Vec<(i32, String)> = runs
            .into_iter()
            .map(|child| {
                let output = child.wait_with_output().expect("run ends");
                let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
                (output.status.code().unwrap_or(-1), stderr)
            })
            .collect();
        let winners: Vec<usize> = (0..2).filter(|&i| ended[i].0 == 0).collect();
        let said = durations_in(&out);
        let consistent = said.iter().all(|d| (d - said[0]).abs() < 1e-6);
        assert!(consistent, "trial {trial}: mixed, {said:?}");
        if winners.len() == 2 {
            sequential += 1;
            continue;
        }
        assert_eq!(winners.len(), 1, "trial {trial}: {ended:?}");
        let loser = &ended[1 - winners[0]];
        assert_eq!(loser.0, 2, "trial {trial}: {ended:?}");
        assert!(loser.1.contains("another wingman run"), "{}", loser.1);
        assert_eq!(loser.1.trim_end().lines().count(), 1, "{}", loser.1);
        let duration_s = f64::from(20 + winners[0] as u32);
        assert!(
            (said[0] - duration_s).abs() < 1e-6,
            "trial {trial}: {said:?}"
        );
    }
    assert!(
        sequential <= 10,
        "only {} of 20 trials overlapped",
        20 - sequential
    );
}
