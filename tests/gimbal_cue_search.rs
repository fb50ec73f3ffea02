//! A narrow camera finds a target it has never seen, and a cued one starts on it:
//! formation.toml with `camera.hfov_deg = 30` starts with the target 12.8° below the camera's
//! axis, outside its 11.3° half field of view. Without a cue the gimbal searches about ahead
//! from `search_after_s` after the start and acquires the target within a few seconds (until
//! this search existed, the run stopped as lost at 5 s on every stream); with
//! `camera.gimbal.cue = "target"` (or the same line of sight as a stated bearing) the first
//! frame measures it. Either way the run then tracks as formation.toml does.

use crate::common::run;
use wingman::output::summary::RunStatus;

const NARROW: [&str; 3] = [
    "camera.hfov_deg=30",
    "run.duration_s=20",
    "output.frames_every=0",
];

fn narrow_with(extra: &[&str]) -> wingman::output::RunReport {
    let overrides: Vec<&str> = NARROW.iter().chain(extra).copied().collect();
    run("formation", &overrides)
}

#[test]
fn an_uncued_narrow_camera_searches_and_acquires() {
    let report = narrow_with(&[]);
    let s = &report.summary;
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    let first = s
        .loss_episodes
        .first()
        .expect("the target starts out of view");
    assert_eq!(first.start_s, 0.0);
    assert!(first.found && first.length_s < 4.0, "{first:?}");
    assert_eq!(s.loss_episodes.len(), 1, "{:?}", s.loss_episodes);
}

#[test]
fn a_cued_narrow_camera_measures_the_first_frame() {
    for cue in [
        vec!["camera.gimbal.cue=\"target\""],
        // R(0) = [200, 50, 30] ft: azimuth atan2(50, 200), elevation -atan(30 / 206.2).
        vec![
            "camera.gimbal.cue=\"bearing\"",
            "camera.gimbal.cue_deg=[14.036, -8.278]",
        ],
    ] {
        let report = narrow_with(&cue);
        let s = &report.summary;
        assert_eq!(s.status, RunStatus::Completed, "{cue:?}: {:?}", s.message);
        assert_eq!(s.lost_frames, 0, "{cue:?}: {:?}", s.loss_episodes);
    }
}
