//! A sweep's case statuses (docs/studies.md, Case statuses). Invariants:
//! - a case that could not run (here: no graphics adapter, the Vulkan loader pointed at a
//!   driver manifest that does not exist, as tests/render_no_adapter_hint.rs does; or an
//!   asset that is missing) is a row with status `failed`, the sweep goes on with the other
//!   cases and exits 1 naming it; run again where an adapter exists, it is run, not skipped;
//! - a case that ran and lost its target is a result: the sweep exits 0 and a rerun skips it;
//! - the progress lines and `results.csv` use the same status names, those of
//!   `results::case_statuses` (a run's `summary.json` names, then `failed`), and
//!   docs/studies.md and docs/outputs.md name every one.

use crate::common;

use std::path::Path;
use std::process::Command;
use wingman::output::summary::RunStatus;
use wingman::study::results::case_statuses;

/// `wingman sweep STUDY --out OUT --jobs 1`, without a Vulkan driver when `no_adapter`: the
/// exit code and standard error.
fn sweep(study: &Path, out: &Path, no_adapter: bool) -> (Option<i32>, String) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_wingman"));
    command
        .arg("sweep")
        .arg(study)
        .arg("--out")
        .arg(out)
        .args(["--jobs", "1"])
        .env("NODEVICE_SELECT", "1");
    if no_adapter {
        let missing = "/nonexistent/wingman_no_such_icd.json";
        command
            .env("VK_ICD_FILENAMES", missing)
            .env("VK_DRIVER_FILES", missing);
    }
    let output = command.output().expect("wingman runs");
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// Two camera cases of 3 s: at 60° the target is tracked, at 20° it is never in view and the
/// run stops as lost after 1 s.
const TWO_FIELDS: &str =
    "set = [\"run.duration_s=3\", \"run.stop_after_lost_s=1\", \"output.plots=false\"]
[[axis]]
key = \"camera.hfov_deg\"
values = [60.0, 20.0]
";

#[test]
fn a_case_without_an_adapter_fails_the_sweep_and_is_retried() {
    let dir = tempfile::tempdir().expect("temp dir");
    let study = common::write_study(dir.path(), "fov.toml", "vision_ch4_formation", TWO_FIELDS);
    let out = dir.path().join("out");

    let (code, stderr) = sweep(&study, &out, true);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("2 case(s) could not run") && stderr.contains("no GPU adapter"),
        "{stderr}"
    );
    let rows = common::results_without_timing(&out);
    assert_eq!(common::column(&rows, "status"), ["failed", "failed"]);

    // Resubmitted on a machine with an adapter: both run (none is skipped), and the lost
    // case is a result.
    let (code, stderr) = sweep(&study, &out, false);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(!stderr.contains("already complete"), "{stderr}");
    let rows = common::results_without_timing(&out);
    assert_eq!(common::column(&rows, "status"), ["completed", "lost"]);

    let (code, stderr) = sweep(&study, &out, false);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("2 of 2 cases already complete"), "{stderr}");
}

#[test]
fn a_missing_asset_fails_its_case_only() {
    let dir = tempfile::tempdir().expect("temp dir");
    let body = "set = [\"run.duration_s=2\", \"output.plots=false\", \"camera.mesh=no_such_mesh.obj\", \"camera.rate_hz=25\"]\n\
                [[axis]]\nkey = \"sensor.mode\"\nvalues = [\"perfect\", \"camera\"]\n";
    let study = common::write_study(dir.path(), "mesh.toml", "seed_ch4_formation", body);
    let out = dir.path().join("out");
    let (code, stderr) = sweep(&study, &out, false);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("first: case 1"), "{stderr}");
    let rows = common::results_without_timing(&out);
    assert_eq!(common::column(&rows, "status"), ["completed", "failed"]);
    assert!(common::column(&rows, "message")[1].contains("no_such_mesh.obj"));
}

#[test]
fn progress_lines_and_results_use_one_set_of_names() {
    let dir = tempfile::tempdir().expect("temp dir");
    let study = common::write_study(dir.path(), "fov.toml", "vision_ch4_formation", TWO_FIELDS);
    let out = dir.path().join("out");
    let (code, stderr) = sweep(&study, &out, false);
    assert_eq!(code, Some(0), "{stderr}");
    let names = case_statuses();
    let rows = common::results_without_timing(&out);
    let statuses = common::column(&rows, "status");
    // "case 1 lost: 2/2 done (1 completed, 1 lost), about 0 s left"
    let mut seen = 0;
    for line in stderr.lines().filter(|l| l.starts_with("case ")) {
        let words: Vec<&str> = line.split_whitespace().collect();
        let case: usize = words[1].parse().expect("case index");
        let status = words[2].trim_end_matches(':');
        assert_eq!(status, statuses[case], "{line}");
        let counts = line[line.find('(').unwrap() + 1..line.find(')').unwrap()].to_string();
        for count in counts.split(", ") {
            let name = count.split_once(' ').expect("count name").1;
            assert!(names.contains(&name), "{name} in {line}");
        }
        seen += 1;
    }
    assert_eq!(seen, 2, "{stderr}");
    let summary = stderr.lines().last().expect("a last line");
    assert!(summary.contains("1 completed, 1 lost"), "{summary}");
    assert!(!summary.contains("failed"), "{summary}");
}

#[test]
fn status_names_are_the_summarys_and_documented() {
    for status in RunStatus::ALL {
        assert_eq!(
            serde_json::to_value(status).expect("serialises"),
            status.name()
        );
    }
    for doc in ["docs/studies.md", "docs/outputs.md"] {
        let text = std::fs::read_to_string(common::repo_root().join(doc)).expect("doc");
        for name in case_statuses() {
            assert!(
                text.contains(&format!("`{name}`")),
                "{doc} does not name `{name}`"
            );
        }
    }
}
