//! `wingman sweep --out` and `wingman sweep merge --out` write only into a new or empty folder
//! or the study's own (known by its `plan.json`), as `wingman run` writes only into a run's
//! folder (docs/studies.md, Running a study). Invariant: a folder with other files in it is
//! refused with exit code 2 before anything is written, its files left as they were; the
//! study's own folder is taken again.

use crate::common;

use std::path::Path;

/// One case of 2 s of the seed's Chapter 4 formation.
const ONE_CASE: &str = "set = [\"run.duration_s=2\", \"output.plots=false\"]\n";

fn run_in(dir: &Path, args: &[&str]) -> (i32, String) {
    common::wingman_cli_in(dir, args)
}

#[test]
fn a_folder_of_other_files_is_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    common::write_study(dir.path(), "one.toml", "seed_ch4_formation", ONE_CASE);
    let foreign = dir.path().join("thesis");
    std::fs::create_dir_all(&foreign).expect("folder");
    std::fs::write(foreign.join("chapter1.tex"), "mine").expect("file");

    let (code, stderr) = run_in(dir.path(), &["sweep", "one.toml", "--out", "thesis"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("--out thesis") && stderr.contains("not empty"),
        "{stderr}"
    );
    assert_eq!(common::file_names(&foreign), ["chapter1.tex"]);

    let (code, stderr) = run_in(dir.path(), &["sweep", "one.toml", "--out", "whole"]);
    assert_eq!(code, 0, "{stderr}");
    let (code, stderr) = run_in(dir.path(), &["sweep", "merge", "whole", "--out", "thesis"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("--out thesis"), "{stderr}");
    assert_eq!(common::file_names(&foreign), ["chapter1.tex"]);

    // A file where the folder should be is refused too.
    std::fs::write(dir.path().join("plain"), "x").expect("file");
    let (code, stderr) = run_in(dir.path(), &["sweep", "one.toml", "--out", "plain"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("not a folder"), "{stderr}");
}

#[test]
fn the_studys_own_and_empty_folders_are_taken() {
    let dir = tempfile::tempdir().expect("temp dir");
    common::write_study(dir.path(), "one.toml", "seed_ch4_formation", ONE_CASE);
    std::fs::create_dir_all(dir.path().join("empty")).expect("folder");
    for _ in 0..2 {
        let (code, stderr) = run_in(dir.path(), &["sweep", "one.toml", "--out", "empty"]);
        assert_eq!(code, 0, "{stderr}");
    }
    let (code, stderr) = run_in(dir.path(), &["sweep", "merge", "empty", "--out", "merged"]);
    assert_eq!(code, 0, "{stderr}");
    let (code, stderr) = run_in(dir.path(), &["sweep", "merge", "empty", "--out", "merged"]);
    assert_eq!(code, 0, "a merge into its own earlier merge: {stderr}");
    assert_eq!(
        common::results_without_timing(&dir.path().join("merged")),
        common::results_without_timing(&dir.path().join("empty"))
    );
}
