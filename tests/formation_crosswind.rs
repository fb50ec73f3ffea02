//! formation.toml in a 15 ft/s wind from the west (`atmosphere.wind_ned_fps = [0, 15, 0]`),
//! stream 3. The seed's profile is fixed over the ground, so on its western leg the target's
//! 50 ft/s over the ground is 65 ft/s through the air: with the airspeed command capped at
//! 65 ft/s (the default) the follower has nothing left to close a gap and drifts 49 ft RMS
//! across the track (measured); with formation.toml's 85 ft/s it holds the slot under 3 ft
//! on every axis (docs/findings.md, A 15 ft/s crosswind).
//!
//! From the east (`[0, -15, 0]`), stream 1, the westward leg asks for 20 ft/s through the air,
//! below the follower's stall: over the ground the slot cannot be held; with the target
//! flying the profile through the air mass (`target.path = "in_air_mass"`) it asks for the
//! profile's own speeds and the slot holds (docs/findings.md, The target in the air mass).
//! The over-ground run flies the Chapter 7 loop formation.toml flew until its energy loop
//! (`common::formation_chapter7_overrides`; over 3 ft on an axis, measured 10.8 ft; over streams
//! 1-5 2 of 5 under 3 ft, worst axis up to 13.8 ft). The energy loop's S-turns by geometry
//! take up most of the surplus over the ground: 4 of streams 1-5 under 3 ft, stream 1 3.49 ft
//! across the westward track, too near the bar to test (over streams 1-20, 9 of 20: those
//! whose last 20 s ask for less than the floor a quarter of the time or more miss). In the
//! air mass, on the energy loop, 5 of 5 are under 3 ft (worst 1.47 ft; 20 of 20 over 1-20);
//! no frame is lost in any of these runs.

use crate::common;

use wingman::output::summary::Summary;

fn run_in_wind(extra: &[&str]) -> Summary {
    let mut sets = vec![
        "atmosphere.wind_ned_fps=[0.0, 15.0, 0.0]",
        "run.seed=3",
        "output.frames_every=0",
    ];
    sets.extend_from_slice(extra);
    common::run("formation", &sets).summary
}

#[test]
fn a_crosswind_from_the_west_is_flown_with_the_airspeed_it_needs() {
    common::assert_held_on_the_slot(&run_in_wind(&[]));
    let capped = run_in_wind(&["autopilot.max_airspeed_cmd_fps=65.0"]);
    assert!(
        common::worst_axis_ft(&capped) > 3.0,
        "at the still-air cap: {:?}",
        capped.rms_error_last20s_ft
    );
}

#[test]
fn a_crosswind_from_the_east_is_held_behind_a_target_in_the_air_mass() {
    let from_the_east = ["atmosphere.wind_ned_fps=[0.0, -15.0, 0.0]", "run.seed=1"];
    let over_ground = run_in_wind(&common::formation_chapter7_overrides(&from_the_east));
    assert!(
        common::worst_axis_ft(&over_ground) > 3.0,
        "over the ground: {:?}",
        over_ground.rms_error_last20s_ft
    );
    let in_air = run_in_wind(&[
        from_the_east[0],
        from_the_east[1],
        "target.path=in_air_mass",
    ]);
    common::assert_held_on_the_slot(&in_air);
}
