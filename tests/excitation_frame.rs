//! The excitation's frame and window in the loop: formation.toml (a lateral E = [0, 1, 0],
//! the command read in the target's velocity frame), whose target turns to fly east at
//! 30-50 s.
//! - `excitation.frame = "inertial"` (formation.toml's): E stays east, and with the target
//!   flying east the swing lies along its track.
//! - `excitation.frame = "target"`: E turns with the command's frame and the swing stays
//!   across the track.
//! - A window (`excitation.start_s`, `end_s`): no swing outside it, the whole swing inside.

use crate::common;
use wingman::output::RunReport;
use wingman::sim::Snapshot;

/// The excitation's offset R*_c - R_c, ft.
fn offset_ft(s: &Snapshot) -> wingman::frames::Vec3 {
    s.excited_command_ned_ft - s.command_ned_ft
}

/// Over the rows of 36-46 s (the target flying east, its heading 85-95°) where the offset is
/// over 0.05 ft: the largest fraction of it along the target's track.
fn largest_along_track_fraction(report: &RunReport) -> f64 {
    report
        .logged
        .iter()
        .filter(|s| (36.0..46.0).contains(&s.t_s) && offset_ft(s).norm() > 0.05)
        .map(|s| {
            let along = s.target.velocity_ned_fps.normalize();
            offset_ft(s).dot(&along).abs() / offset_ft(s).norm()
        })
        .fold(0.0, f64::max)
}

fn run(extra: &[&str]) -> RunReport {
    let mut sets = vec!["run.duration_s=46", "output.frames_every=0", "run.seed=2"];
    sets.extend_from_slice(extra);
    common::run("formation", &sets)
}

#[test]
fn a_swing_in_the_target_frame_stays_across_the_track() {
    let inertial = largest_along_track_fraction(&run(&[]));
    assert!(
        inertial > 0.95,
        "in NED the swing lies along the track: {inertial}"
    );
    let turned = largest_along_track_fraction(&run(&["excitation.frame=\"target\""]));
    assert!(
        turned < 0.2,
        "in the target frame it stays across: {turned}"
    );
}

#[test]
fn the_window_bounds_the_swing() {
    let report = run(&[
        "excitation.frame=\"target\"",
        "excitation.start_s=10",
        "excitation.end_s=30",
    ]);
    let largest_ft = |from_s: f64, to_s: f64| {
        (report.logged.iter())
            .filter(|s| (from_s..to_s).contains(&s.t_s))
            .map(|s| offset_ft(s).norm())
            .fold(0.0, f64::max)
    };
    assert_eq!(largest_ft(0.0, 10.0), 0.0);
    assert_eq!(largest_ft(30.0, 46.0), 0.0);
    // Inside the window, past its fade in: the swing formation.toml flies there (0.87 ft
    // at its largest, measured), not a remnant of the fades.
    assert!(largest_ft(15.0, 25.0) > 0.5, "{}", largest_ft(15.0, 25.0));
}
