//! `wingman sweep` as a user runs it, on a small study of the seed's Chapter 4 formation (a
//! kinematic follower and perfect measurements: fast and deterministic). Invariants:
//! - the study run whole and as 3 shards merged give the same `results.csv`, but for the
//!   wall-clock columns (`results::is_timing_column`), which are blanked before comparing;
//! - a sweep killed midway and run again runs only the cases not complete (their records are
//!   left byte for byte) and ends with the `results.csv` of an uninterrupted sweep;
//! - a bad value of an axis is reported as a bad study file, naming the file, the axis and
//!   the value, with exit code 2, before anything runs (no output folder).
//!
//! Cases that could not run: tests/study_case_statuses.rs; `--out`: tests/study_out_folder.rs.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn wingman() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_wingman"));
    command.env("NODEVICE_SELECT", "1");
    command
}

/// Writes a study of `scenarios/seed_ch4_formation.toml` into `dir` and returns its path.
fn write_study(dir: &Path, name: &str, body: &str) -> PathBuf {
    common::write_study(dir, name, "seed_ch4_formation", body)
}

/// 3 x 2 gains, 2 replicates: 12 cases of 20 s.
const SMALL: &str = "replicates = 2
set = [\"run.duration_s=20\", \"output.plots=false\"]

[[axis]]
key = \"guidance.k\"
values = [2.0, 3.5, 5.0]

[[axis]]
key = \"guidance.gamma_d\"
range = { from = 8, to = 12, step = 4 }
";

fn sweep(study: &Path, out: &Path, extra: &[&str]) -> Output {
    let output = wingman()
        .arg("sweep")
        .arg(study)
        .arg("--out")
        .arg(out)
        .args(["--quiet", "--jobs", "2"])
        .args(extra)
        .output()
        .expect("wingman runs");
    assert!(
        output.status.success(),
        "{}: {}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

#[test]
fn three_shards_merged_equal_the_whole_sweep() {
    let dir = tempfile::tempdir().expect("temp dir");
    let study = write_study(dir.path(), "small.toml", SMALL);
    let whole = dir.path().join("whole");
    sweep(&study, &whole, &[]);
    let shards: Vec<PathBuf> = (0..3)
        .map(|i| {
            let out = dir.path().join(format!("shard{i}"));
            sweep(&study, &out, &["--shard", &format!("{i}/3")]);
            out
        })
        .collect();
    for (i, shard) in shards.iter().enumerate() {
        // Cases are dealt out in turn: shard i holds cases i, i + 3, i + 6, i + 9.
        let rows = common::results_without_timing(shard);
        let cases: Vec<&str> = rows[1..].iter().map(|r| r[0].as_str()).collect();
        let expected: Vec<String> = (0..4).map(|k| (i + 3 * k).to_string()).collect();
        assert_eq!(cases, expected);
    }
    let merged = dir.path().join("merged");
    let output = wingman()
        .args(["sweep", "merge"])
        .args(&shards)
        .arg("--out")
        .arg(&merged)
        .output()
        .expect("merge runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );

    let expected = common::results_without_timing(&whole);
    assert_eq!(expected.len(), 13, "a header and 12 cases");
    assert!(expected[0].iter().any(|c| c == "guidance.k"));
    assert!(expected[0].iter().any(|c| c == "run.seed"));
    assert!(
        expected[1..]
            .iter()
            .all(|row| row[expected[0].iter().position(|c| c == "status").unwrap()] == "completed")
    );
    assert_eq!(common::results_without_timing(&merged), expected);
    assert_eq!(
        common::file_names(&merged.join("cases")),
        common::file_names(&whole.join("cases"))
    );
    assert_eq!(
        common::file_names(&merged.join("plots")),
        common::file_names(&whole.join("plots"))
    );
    assert!(
        common::file_names(&whole.join("plots"))
            .contains(&"heatmap_b_hat_final_ft.png".to_string())
    );
}

/// Counts the cases with a record in a sweep folder.
fn complete_cases(out: &Path) -> Vec<String> {
    common::file_names(&out.join("cases"))
        .into_iter()
        .filter(|case| out.join("cases").join(case).join("case.json").exists())
        .collect()
}

#[test]
fn a_killed_sweep_resumes_with_the_missing_cases_only() {
    let dir = tempfile::tempdir().expect("temp dir");
    // 140 s runs (about 0.15-0.4 s each), one at a time: the kill lands midway.
    let body = SMALL.replace("run.duration_s=20", "run.duration_s=140");
    let study = write_study(dir.path(), "resume.toml", &body);
    let out = dir.path().join("killed");
    let mut child = wingman()
        .arg("sweep")
        .arg(&study)
        .arg("--out")
        .arg(&out)
        .args(["--quiet", "--jobs", "1"])
        .stderr(Stdio::null())
        .spawn()
        .expect("wingman starts");
    let started = Instant::now();
    while complete_cases(&out).len() < 3 && started.elapsed() < Duration::from_secs(120) {
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().expect("killed");
    child.wait().expect("reaped");
    let before = complete_cases(&out);
    assert!(
        (3..12).contains(&before.len()),
        "the kill should land midway: {} cases complete",
        before.len()
    );
    assert!(!out.join("results.csv").exists());
    let records_before: Vec<Vec<u8>> = before
        .iter()
        .map(|case| std::fs::read(out.join("cases").join(case).join("case.json")).unwrap())
        .collect();

    let output = wingman()
        .arg("sweep")
        .arg(&study)
        .arg("--out")
        .arg(&out)
        .args(["--jobs", "2"])
        .output()
        .expect("wingman runs");
    assert!(output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains(&format!("{} of 12 cases already complete", before.len())),
        "{stderr}"
    );
    // The complete cases were not run again: their records (wall times included) are as
    // they were.
    for (case, record) in before.iter().zip(&records_before) {
        let after = std::fs::read(out.join("cases").join(case).join("case.json")).unwrap();
        assert_eq!(&after, record, "case {case} ran again");
    }
    assert_eq!(complete_cases(&out).len(), 12);

    let uninterrupted = dir.path().join("uninterrupted");
    sweep(&study, &uninterrupted, &[]);
    assert_eq!(
        common::results_without_timing(&out),
        common::results_without_timing(&uninterrupted)
    );
}

#[test]
fn a_bad_axis_value_is_a_bad_study_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let body = "[[axis]]\nkey = \"guidance.k\"\nvalues = [2.0, -1.0]\n";
    let study = write_study(dir.path(), "bad.toml", body);
    let out = dir.path().join("never");
    let output = wingman()
        .arg("sweep")
        .arg(&study)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("wingman runs");
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("bad.toml"), "{stderr}");
    assert!(stderr.contains("axis `guidance.k`, value -1.0"), "{stderr}");
    assert!(!out.exists(), "nothing runs before the study is checked");

    let unknown = write_study(
        dir.path(),
        "unknown.toml",
        "[[axis]]\nname = \"typo\"\nkey = \"guidance.kk\"\nvalues = [1]\n",
    );
    let output = wingman()
        .arg("sweep")
        .arg(&unknown)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("axis `typo`") && stderr.contains("kk"),
        "{stderr}"
    );

    // A shard index out of range is refused on a valid study, before it runs.
    let valid = write_study(
        dir.path(),
        "valid.toml",
        "[[axis]]\nkey = \"guidance.k\"\nvalues = [2.0, 3.0]\n",
    );
    let shard = wingman()
        .arg("sweep")
        .arg(&valid)
        .args(["--shard", "3/3", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(shard.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&shard.stderr);
    assert!(stderr.contains("--shard 3/3"), "{stderr}");
    assert!(!out.exists(), "nothing runs with a bad shard");
}

/// Every study in `studies/` passes the checks a sweep makes before it runs, with the number
/// of cases docs/studies.md gives (the Monte Carlo study over at least 50 streams).
#[test]
fn shipped_studies_are_valid() {
    let expected = [
        ("field_of_view", 42),
        ("resolution", 15),
        ("rate_latency", 16),
        ("monte_carlo", 50),
        ("apparent_size", 13 * 13 * 4 * 5),
        ("formation_streams", 10),
        ("vision_ch4_filter", 9),
        ("background", 6 * 3 * 3),
        ("formation_moderate_air_mass", 30),
    ];
    for (name, cases) in expected {
        let path = common::repo_root().join(format!("studies/{name}.toml"));
        let plan = wingman::study::Plan::load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(plan.cases.len(), cases, "{name}");
    }
}

/// A study of a group scenario runs the group in every case: one column per follower's
/// number, named after it, and the group's status (it ran the pair alone, silently, before).
#[test]
fn a_group_study_runs_every_follower() {
    let dir = tempfile::tempdir().expect("temp dir");
    let study = common::write_study(
        dir.path(),
        "platoon.toml",
        "platoon",
        "replicates = 2\nset = [\"run.duration_s=2\", \"output.plots=false\", \"output.frames_every=0\"]\n",
    );
    let out = dir.path().join("out");
    sweep(&study, &out, &[]);
    let rows = common::results_without_timing(&out);
    let column = |name: &str| {
        rows[0]
            .iter()
            .position(|c| c == name)
            .unwrap_or_else(|| panic!("no column {name}"))
    };
    assert_eq!(rows.len(), 3, "a header and two cases");
    for row in &rows[1..] {
        assert_eq!(row[column("status")], "completed");
        for follower in ["f1", "f2", "f3"] {
            let b_hat: f64 = row[column(&format!("{follower}.b_hat_final_ft"))]
                .parse()
                .expect("a number");
            assert!(b_hat > 0.0, "{follower}: {b_hat}");
            assert!(
                out.join("cases/000000")
                    .join(follower)
                    .join("summary.json")
                    .is_file()
            );
        }
        assert_eq!(row[column("f1.wall_s")], "", "a timing column");
    }
}
