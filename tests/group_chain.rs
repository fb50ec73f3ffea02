//! A chain of followers, each tracking the aircraft ahead by its own camera
//! (`scenarios/platoon.toml`: target → f1 → f2 → f3), run end to end for its first seconds.
//!
//! Invariants: (1) the aircraft each follower tracks is, in its telemetry, where the leader's
//! own simulation put it at every logged instant, within a thousandth of a foot (the relay of
//! the leader's truth, carried over one tick with its velocity and acceleration);
//! (2) every frame any follower measured was of the aircraft it tracks, by the truth (no
//! teammate captured a track) and none went unmeasured; (3) the outputs: one folder per
//! follower with today's files, and `group.json` with the followers leaders first.

mod common;

use common::repo_root;
use wingman::output::group::{load_checked, run_group_to_directory};

#[test]
fn platoon_links_track_their_leaders() {
    let path = repo_root().join("scenarios/platoon.toml");
    let sets = [
        "run.seed=1",
        "run.duration_s=6",
        "output.plots=false",
        "output.frames_every=0",
    ]
    .map(String::from);
    let group = load_checked(&path, &sets).expect("valid").expect("a group");
    let dir = tempfile::tempdir().expect("temp dir");
    let summary = run_group_to_directory(&group, "platoon", dir.path(), None, |_| {}).expect("run");
    assert_eq!(summary.stopped_by, None);
    let names: Vec<&str> = summary.followers.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["f1", "f2", "f3"]);
    for f in &summary.followers {
        assert_eq!(
            f.false_lock_frames, 0,
            "{} measured another aircraft",
            f.name
        );
        assert_eq!(f.lost_frames, 0, "{} lost its leader", f.name);
        for file in ["telemetry.csv", "summary.json", "scenario.toml"] {
            assert!(
                dir.path().join(&f.name).join(file).is_file(),
                "{}/{file}",
                f.name
            );
        }
    }
    assert!(dir.path().join("group.json").is_file());
    // The leader's truth as each follower's telemetry has it.
    for (leader, follower) in [("f1", "f2"), ("f2", "f3")] {
        let ahead = positions(&dir.path().join(leader).join("telemetry.csv"), "fol");
        let seen = positions(&dir.path().join(follower).join("telemetry.csv"), "tgt");
        assert_eq!(ahead.len(), seen.len());
        for (a, s) in ahead.iter().zip(&seen) {
            let off: f64 = (0..3).map(|i| (a[i] - s[i]).abs()).sum();
            assert!(off < 1e-3, "{follower} sees {leader} {off} ft off");
        }
    }
}

/// With `output.plots`, a group's folder has the formation seen from above and, in each
/// follower's folder, the figures a single run of it would have.
#[test]
fn group_plots_the_formation_and_each_follower() {
    let path = repo_root().join("scenarios/platoon.toml");
    let sets = [
        "run.duration_s=2",
        "output.plots=true",
        "output.frames_every=0",
    ]
    .map(String::from);
    let group = load_checked(&path, &sets).expect("valid").expect("a group");
    let dir = tempfile::tempdir().expect("temp dir");
    run_group_to_directory(&group, "platoon", dir.path(), None, |_| {}).expect("run");
    assert!(dir.path().join("formation.png").is_file());
    for name in ["f1", "f2", "f3"] {
        for figure in ["relative_position.png", "size_estimate.png"] {
            let file = dir.path().join(name).join("plots").join(figure);
            assert!(file.is_file(), "{}", file.display());
        }
    }
}

/// Per row: the follower's position (`fol`) or the tracked aircraft's (`tgt`: rel + fol),
/// NED, ft.
fn positions(path: &std::path::Path, which: &str) -> Vec<[f64; 3]> {
    let mut reader = csv::Reader::from_path(path).expect("telemetry");
    let header = reader.headers().expect("header").clone();
    let col = |name: &str| header.iter().position(|h| h == name).expect(name);
    let fol = ["fol_n_ft", "fol_e_ft", "fol_d_ft"].map(&col);
    let rel = ["rel_n_ft", "rel_e_ft", "rel_d_ft"].map(&col);
    reader
        .records()
        .map(|r| {
            let r = r.expect("row");
            let v = |i: usize| r[i].parse::<f64>().expect("number");
            std::array::from_fn(|k| match which {
                "fol" => v(fol[k]),
                _ => v(fol[k]) + v(rel[k]),
            })
        })
        .collect()
}
