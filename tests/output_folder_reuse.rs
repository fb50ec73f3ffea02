//! An output folder never mixes runs: a second run into the folder of a first
//! clears the first's files (frames and plots it does not write again are gone), and a folder
//! with other files in it is refused with exit code 2, naming it, and left as it was.

use crate::common;

use crate::common::wingman_cli as wingman;

/// `wingman run scenarios/seed_ch4_formation.toml --out OUT --quiet`.
fn run_seed_ch4_into(out: &std::path::Path) -> (i32, String) {
    wingman(&[
        "run",
        "scenarios/seed_ch4_formation.toml",
        "--out",
        out.to_str().expect("utf-8"),
        "--quiet",
    ])
}

#[test]
fn a_second_run_clears_the_first_and_other_folders_are_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("run");
    let out_s = out.to_str().expect("utf-8");
    let first = [
        "run",
        "scenarios/vision_ch4_formation.toml",
        "--out",
        out_s,
        "--quiet",
        "--set",
        "run.duration_s=0.5",
        "--set",
        "output.frames_every=5",
    ];
    let (code, stderr) = wingman(&first);
    assert_eq!(code, 0, "{stderr}");
    assert!(out.join("frames").is_dir() && out.join("plots").is_dir());
    let (code, stderr) = wingman(&[
        "run",
        "scenarios/seed_ch4_formation.toml",
        "--out",
        out_s,
        "--quiet",
        "--set",
        "run.duration_s=0.5",
        "--set",
        "output.plots=false",
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        !out.join("frames").exists(),
        "the first run's frames stayed"
    );
    assert!(!out.join("plots").exists(), "the first run's plots stayed");
    let summary = std::fs::read_to_string(out.join("summary.json")).expect("summary");
    assert!(summary.contains("seed_ch4_formation"));

    let other = dir.path().join("thesis");
    std::fs::create_dir_all(&other).expect("folder");
    std::fs::write(other.join("chapter1.tex"), "text").expect("file");
    let (code, stderr) = run_seed_ch4_into(&other);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("thesis") && stderr.contains("not empty"),
        "{stderr}"
    );
    let left: Vec<_> = std::fs::read_dir(&other).expect("read").collect();
    assert_eq!(left.len(), 1, "the refused folder was written to");

    let file = other.join("chapter1.tex");
    let (code, stderr) = run_seed_ch4_into(&file);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("is a file, not a folder"), "{stderr}");
}

/// A run killed before it wrote its summary (SIGKILL: nothing of it runs any more) leaves a
/// folder that the next run into the same `--out` recognises by its marker and replaces, as a
/// scheduler's resubmission does.
#[test]
fn the_folder_of_a_killed_run_is_reused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("run");
    let mut child = common::spawn_long_run_logging(&out);
    child.kill().expect("SIGKILL");
    child.wait().expect("child ends");
    assert!(
        !out.join("summary.json").exists(),
        "killed before its summary"
    );
    let (code, stderr) = run_seed_ch4_into(&out);
    assert_eq!(code, 0, "{stderr}");
    assert!(out.join("summary.json").is_file() && out.join(".wingman-run").is_file());
}
