//! A Slurm job array, simulated on one machine (docs/studies.md, On a cluster): the script
//! `studies/cluster/slurm_sweep.sh` run once per array task with `SLURM_ARRAY_TASK_ID` set, on a
//! study of 6 camera cases in 3 shards. Shard 0 runs as it should; shard 1 is killed
//! (SIGKILL) in the middle of a case; shard 2 runs on a "node" without a graphics adapter (the
//! Vulkan loader pointed at a driver manifest that does not exist). Invariants:
//! - the task without an adapter exits 1 and records its cases as `failed`; the merge of the
//!   shards as they are then fails;
//! - the two tasks submitted again (as `sbatch --array=1,2` would) run what has no result and
//!   exit 0, and the merge of the three shards gives the `results.csv` of the same study swept
//!   on one machine: the same cases, statuses and numbers (wall-clock columns blanked).

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// 2 fields of view by 3 gains, camera cases of 20 s: at 60° the target is tracked (about a
/// second of wall time per case; with k = 2 it leaves the frame at 8.4 s and the case stops as
/// lost), at 20° it is never in view and the case stops as lost at 1 s: a result like any.
const STUDY: &str =
    "set = [\"run.duration_s=20\", \"run.stop_after_lost_s=1\", \"output.plots=false\"]
[[axis]]
key = \"camera.hfov_deg\"
values = [60.0, 20.0]

[[axis]]
key = \"guidance.k\"
values = [2.0, 3.0, 4.0]
";

const SHARDS: usize = 3;

/// Array task `index` of the Slurm script, in `dir` (its `runs/` receives the shards), on a
/// node without an adapter when `no_adapter`.
fn array_task(dir: &Path, study: &Path, index: usize, no_adapter: bool) -> Command {
    let mut task = Command::new("bash");
    task.arg(common::repo_root().join("studies/cluster/slurm_sweep.sh"))
        .current_dir(dir)
        .env("STUDY", study)
        .env("SHARDS", SHARDS.to_string())
        .env("SLURM_ARRAY_TASK_ID", index.to_string())
        .env("SLURM_CPUS_PER_TASK", "1")
        .env("WINGMAN", env!("CARGO_BIN_EXE_wingman"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    if no_adapter {
        let missing = "/nonexistent/wingman_no_such_icd.json";
        task.env("VK_ICD_FILENAMES", missing)
            .env("VK_DRIVER_FILES", missing);
    }
    task
}

fn shard_dir(dir: &Path, index: usize) -> PathBuf {
    dir.join(format!("runs/array-shard-{index}-of-{SHARDS}"))
}

fn finished(output: Output, expected_code: i32, what: &str) -> String {
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(
        output.status.code(),
        Some(expected_code),
        "{what}: {stderr}"
    );
    stderr
}

/// Starts task 1 and kills it (SIGKILL) once its first case has written telemetry and before
/// that case has a record: in the middle of a run.
fn killed_mid_run(dir: &Path, study: &Path) {
    let mut task: Child = array_task(dir, study, 1, false)
        .spawn()
        .expect("task 1 starts");
    let case = shard_dir(dir, 1).join("cases/000001");
    let started = Instant::now();
    while std::fs::metadata(case.join("telemetry.csv")).map_or(0, |m| m.len()) == 0 {
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "case 1 never started"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    task.kill().expect("killed");
    task.wait().expect("reaped");
    assert!(
        !case.join("case.json").exists(),
        "the kill came after the case"
    );
    assert!(!shard_dir(dir, 1).join("results.csv").exists());
}

fn merge(dir: &Path, out: &str) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wingman"))
        .args(["sweep", "merge"])
        .args((0..SHARDS).map(|i| shard_dir(dir, i)))
        .args(["--out", out])
        .current_dir(dir)
        .env("NODEVICE_SELECT", "1")
        .output()
        .expect("merge runs")
}

#[test]
fn a_killed_and_a_broken_task_resubmitted_merge_to_the_one_machine_sweep() {
    let dir = tempfile::tempdir().expect("temp dir");
    let study = common::write_study(dir.path(), "array.toml", "vision_ch4_formation", STUDY);

    let task = array_task(dir.path(), &study, 0, false).output();
    finished(task.expect("task 0 runs"), 0, "task 0");
    killed_mid_run(dir.path(), &study);
    let task = array_task(dir.path(), &study, 2, true).output();
    let stderr = finished(task.expect("task 2 runs"), 1, "task 2 without an adapter");
    assert!(stderr.contains("2 case(s) could not run"), "{stderr}");
    let rows = common::results_without_timing(&shard_dir(dir.path(), 2));
    assert_eq!(common::column(&rows, "status"), ["failed", "failed"]);
    let stderr = finished(merge(dir.path(), "early"), 1, "merge before resubmission");
    assert!(stderr.contains("have no results"), "{stderr}");

    for index in [1, 2] {
        let task = array_task(dir.path(), &study, index, false).output();
        finished(task.expect("resubmitted"), 0, "a resubmitted task");
    }
    let stderr = finished(merge(dir.path(), "merged"), 0, "merge");
    assert!(stderr.contains("6 cases: 2 completed, 4 lost"), "{stderr}");

    let whole = Command::new(env!("CARGO_BIN_EXE_wingman"))
        .arg("sweep")
        .arg(&study)
        .args(["--out", "whole", "--jobs", "2", "--quiet"])
        .current_dir(dir.path())
        .env("NODEVICE_SELECT", "1")
        .output();
    finished(whole.expect("one-machine sweep"), 0, "one-machine sweep");
    let expected = common::results_without_timing(&dir.path().join("whole"));
    assert_eq!(expected.len(), 7, "a header and 6 cases");
    assert_eq!(
        common::results_without_timing(&dir.path().join("merged")),
        expected
    );
}
