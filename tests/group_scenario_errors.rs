//! A group scenario the run cannot take is refused before anything runs: exit code 2 and one
//! line naming the file, the member, the key and the value (an unknown aircraft in `tracks`,
//! a cycle of followers, a member's key out of its range, a member's run key, a name given
//! twice, an air mass that is neither shared nor independent).

use crate::common::wingman_cli;

/// A follower on the target and `extra` after it.
fn group_file(dir: &std::path::Path, extra: &str) -> std::path::PathBuf {
    let text = format!(
        "[sensor]\nmode = \"perfect\"\n\n[[group.follower]]\nname = \"f1\"\ntracks = \"target\"\n\n{extra}"
    );
    let path = dir.join("group.toml");
    std::fs::write(&path, text).expect("write scenario");
    path
}

fn refused(extra: &str, expected: &[&str]) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = group_file(dir.path(), extra);
    let out = dir.path().join("out");
    let (code, stderr) = wingman_cli(&[
        "run",
        path.to_str().expect("utf-8"),
        "--out",
        out.to_str().expect("utf-8"),
        "--quiet",
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("group.toml"), "names the file: {stderr}");
    for part in expected {
        assert!(stderr.contains(part), "names {part}: {stderr}");
    }
    assert_eq!(stderr.trim().lines().count(), 1, "one line: {stderr}");
    assert!(!out.exists(), "nothing written");
}

#[test]
fn unknown_aircraft_is_named_with_the_known_ones() {
    refused(
        "[[group.follower]]\nname = \"f2\"\ntracks = \"f9\"\n",
        &["f2", "tracks = \"f9\"", "target, f1"],
    );
}

#[test]
fn cycle_is_refused() {
    refused(
        "[[group.follower]]\nname = \"f2\"\ntracks = \"f3\"\n\n[[group.follower]]\nname = \"f3\"\ntracks = \"f2\"\n",
        &["cycle", "f2 tracks f3", "f3 tracks f2"],
    );
}

#[test]
fn member_key_out_of_range_is_named() {
    refused(
        "[[group.follower]]\nname = \"f2\"\ntracks = \"f1\"\ncamera.hfov_deg = 500.0\n",
        &["\"f2\"", "camera.hfov_deg", "500"],
    );
    refused(
        "[[group.target]]\nname = \"other\"\nsize_ft = -3.0\n",
        &["\"other\"", "target.size_ft", "-3"],
    );
}

#[test]
fn run_keys_and_names_are_the_groups() {
    refused(
        "[[group.follower]]\nname = \"f2\"\ntracks = \"f1\"\nrun.dt_s = 0.01\n",
        &["group.follower.f2.run.dt_s", "run section is the group's"],
    );
    refused(
        "[[group.follower]]\nname = \"f1\"\ntracks = \"target\"\n",
        &["name = \"f1\" is taken"],
    );
}

#[test]
fn gusts_are_shared_or_independent() {
    refused(
        "[group]\ngusts = \"calm\"\n",
        &["group.gusts = \"calm\"", "\"independent\" or \"shared\""],
    );
}
