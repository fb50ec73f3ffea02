//! S-turns by geometry (`autopilot.weave_half_width_ft`; docs/findings.md, An energy outer
//! loop): formation.toml (the energy outer loop, S-turns by geometry) behind a target flying
//! straight north at 30 ft/s, below the follower's slowest airspeed command (35 ft/s), in
//! light turbulence.
//!
//! Invariant: with the S-turns placed about the slot's line and reversing 10 ft off it, the
//! follower never overtakes the target (the target at least 5 ft ahead of it along the track
//! at every logged instant after 20 s) and the along-track error stays within ±30 ft;
//! without them the same follower overtakes. (Measured over streams 1-10 with
//! formation.toml's S-turns, 2 ft/s accepted within 5 ft of lead: the target at least
//! 0.5-31.7 ft ahead, median 15.9 (stream 1: 14.3), the along-track error within 20.6-31.6
//! ft. Stream 2 is the exception to both bars: a leg's swing brings the follower level with
//! the target's position along the track, 0.5 ft behind it, and it loses 18 frames; with
//! every deficit stretched it comes as near, 0.4 ft, and loses 5. A 30 ft/s target asks for
//! 5 ft/s below the floor, more than twice the profile's slowest turn does; docs/findings.md,
//! An energy outer loop. The window opens at 20 s, before the approach has settled: on
//! streams 1, 3 and 4 the largest error behind the slot, 23-26 ft, comes before 30 s; from
//! 30 s on the along-track RMS is 3.5-16.5 ft over streams 1-10, median 6.3.)

use crate::common;

use wingman::output::RunReport;

/// formation.toml behind the 30 ft/s target for 60 s, with `overrides`.
fn behind_a_slow_target(overrides: &[&str]) -> RunReport {
    let mut all = vec![
        "output.frames_every=0",
        "run.duration_s=60",
        "target.motion=straight",
        "target.straight_velocity_fps=[30.0, 0.0, 0.0]",
    ];
    all.extend_from_slice(overrides);
    common::run("formation", &all)
}

/// The largest |along-track error| (R - R_c, north) after 20 s, ft.
fn along_track_error_ft(report: &RunReport) -> f64 {
    let late = report.logged.iter().filter(|s| s.t_s >= 20.0);
    late.map(|s| (s.relative_ned_ft[0] - s.command_ned_ft[0]).abs())
        .fold(0.0, f64::max)
}

#[test]
fn s_turns_by_geometry_hold_the_slot_behind_a_slower_target() {
    let stretched = behind_a_slow_target(&[]);
    let (ahead_ft, error_ft) = (
        common::least_ahead_ft(&stretched, 20.0),
        along_track_error_ft(&stretched),
    );
    println!(
        "with S-turns: target at least {ahead_ft:.1} ft ahead, along-track error within ±{error_ft:.1} ft"
    );
    assert!(ahead_ft > 5.0, "the follower came within {ahead_ft:.1} ft");
    assert!(error_ft < 30.0, "along-track error {error_ft:.1} ft");

    let straight = behind_a_slow_target(&[
        "autopilot.weave_half_width_ft=0",
        "autopilot.weave_deficit_fps=0",
    ]);
    let ahead_ft = common::least_ahead_ft(&straight, 20.0);
    println!("without: the target at least {ahead_ft:.1} ft ahead");
    assert!(
        ahead_ft < 0.0,
        "the follower without S-turns did not overtake"
    );
}

/// formation.toml with the airframe size model (the span model wanders side on) and the slot
/// 30 ft beside the target ([0, 30, 0] ft in its frame), through the target's slowest turn
/// (35.4 ft/s at t ≈ 97 s, the follower on its inside), stream `seed`.
fn beside_the_target(seed: u64) -> RunReport {
    common::run(
        "formation",
        &[
            "output.frames_every=0",
            "run.duration_s=110",
            &format!("run.seed={seed}"),
            "guidance.command_ft=[0.0, 30.0, 0.0]",
            "estimator.size_model=\"airframe\"",
        ],
    )
}

/// Invariant: a follower whose slot lies beside the target flies no S-turns (a leg across
/// the slot's line carries it under the target: the clock's S-turns brought it within
/// 9-14 ft of the target on streams 3-5 and lost the target on stream 2; docs/findings.md,
/// S-turns only behind the target), so in the slowest turn it stays at least 20 ft from the
/// target and measures every frame.
#[test]
fn a_follower_beside_its_target_keeps_clear_of_it() {
    let report = beside_the_target(3);
    let nearest_ft = common::nearest_approach_ft(&report, 30.0);
    println!(
        "nearest {nearest_ft:.1} ft after 30 s, {} frames lost",
        report.summary.lost_frames
    );
    assert!(
        nearest_ft > 20.0,
        "came within {nearest_ft:.1} ft of the target"
    );
    assert_eq!(report.summary.lost_frames, 0);
}

/// formation.toml (the energy loop, 10 ft S-turns by geometry) in light air, stream 27, the
/// speed deficit a leg leaves to the along-track error `deficit_fps` (lead budget 5 ft): its
/// largest |R - R_c| after 30 s, ft.
fn largest_slot_error_ft(deficit_fps: &str) -> f64 {
    let report = common::run(
        "formation",
        &[
            "output.frames_every=0",
            "run.seed=27",
            &format!("autopilot.weave_deficit_fps={deficit_fps}"),
        ],
    );
    assert_eq!(report.summary.lost_frames, 0);
    let late = report.logged.iter().filter(|s| s.t_s >= 30.0);
    late.map(|s| (s.relative_ned_ft - s.command_ned_ft).norm())
        .fold(0.0, f64::max)
}

/// Invariant: a command that a gust lowers under the follower's floor for a few seconds is
/// taken as along-track error while the follower is behind its slot, not as a leg and a
/// reversal at full bank. Stream 27's largest slot error after 30 s: 6.6 ft with 2 ft/s
/// accepted within 5 ft of lead, 21.0 ft without (measured; over light streams 1-50, before
/// the legs kept outside the turn, the median 8.1 against 13.8 ft, docs/findings.md, Path
/// stretching with a lead budget).
#[test]
fn a_lead_budget_keeps_a_short_deficit_off_the_legs() {
    let budgeted = largest_slot_error_ft("2.0");
    let stretched = largest_slot_error_ft("0.0");
    println!(
        "largest slot error after 30 s: {budgeted:.1} ft with the budget, {stretched:.1} without"
    );
    assert!(budgeted < 10.0, "with the budget: {budgeted:.1} ft");
    assert!(stretched > 15.0, "without: {stretched:.1} ft");
}

/// formation.toml (the energy loop, S-turns by geometry of half width 10 ft, 2 ft/s accepted
/// within 5 ft of lead) in a 15 ft/s wind to the west, stream 4, to 108 s, the
/// legs kept outside the target's turn from `outside_turn_dps` (0: never): the nearest
/// approach to the target after 90 s, ft, and the frames lost.
fn through_the_slowest_turn_in_a_tailwind(outside_turn_dps: &str) -> (f64, u64) {
    let report = common::run(
        "formation",
        &[
            "output.frames_every=0",
            "run.duration_s=108",
            "run.seed=4",
            "atmosphere.wind_ned_fps=[0.0, -15.0, 0.0]",
            &format!("autopilot.weave_outside_turn_dps={outside_turn_dps}"),
        ],
    );
    (
        common::nearest_approach_ft(&report, 90.0),
        report.summary.lost_frames,
    )
}

/// Invariant: in the target's turn the legs keep to its outside, where the turn lengthens
/// the follower's path, and the follower keeps clear of the target. Stream 4
/// in the wind to the west (the target at its slowest, 35 ft/s over the ground, turning
/// left at 6 °/s, the follower at its 35 ft/s floor with 15 ft/s behind it): alternating
/// legs swing 65 ft to the inside, come 18 ft ahead of the target and pass 7.6 ft from it,
/// losing 24 frames; outside the turn the follower keeps 28.9 ft off and loses none
/// (measured). Over streams 1-10 the nearest approach in the same 90-108 s has a median of
/// 27.8 ft and a least of 24.5 ft outside the turn, 13.8 and 7.3 ft alternating: the 14 ft
/// bar is below every stream's nearest approach outside the turn and above half of them
/// alternating (docs/findings.md, Legs outside the turn).
#[test]
fn in_a_tailwind_turn_the_legs_keep_outside_it() {
    let (outside_ft, outside_lost) = through_the_slowest_turn_in_a_tailwind("1.72");
    let (alternating_ft, alternating_lost) = through_the_slowest_turn_in_a_tailwind("0.0");
    println!(
        "nearest after 90 s: {outside_ft:.1} ft outside the turn ({outside_lost} frames lost), \
         {alternating_ft:.1} ft alternating ({alternating_lost} lost)"
    );
    assert!(outside_ft > 14.0, "outside the turn: {outside_ft:.1} ft");
    assert_eq!(outside_lost, 0);
    assert!(alternating_ft < 10.0, "alternating: {alternating_ft:.1} ft");
    assert!(
        alternating_lost >= 10,
        "alternating: {alternating_lost} frames lost"
    );
}
