//! The bank limit on the reference (`autopilot.bank_limit = "reference"`; docs/equations.md,
//! The bank limit on the reference). formation.toml's follower behind the target aircraft
//! flying the seed's profile (studies/formation_aircraft_target.toml's world), stream 17: in
//! the target's slowest turn (32-34 ft/s at 100-105 s) the follower at its 35 ft/s floor flew
//! its clock's S-turns with the seed's 30° clamp on the raw command, which the roll
//! prefilter's reversals overshot to 46°; at 34 ft/s that turn needs more lift than α_max
//! gives, the follower sank 80-85 ft below its slot and was back on it only inside the last
//! 20 s (RMS [5.6, 16.9, 24.6] ft with the 0.06 speed brake formation.toml had then, [2.6,
//! 7.3, 10.8] ft with its 0.18 now).
//! With the reference held inside 30° the run holds every axis under 3 ft. Measured over
//! run.seed 1-20 and 1-40, runs with every axis under 3 ft, the reference held against the
//! command clamp: with the 0.06 brake 19 against 17 and 33 against 28; with 0.18, 20 against
//! 15 and 35 against 27, but seed 28 then leaves the slot by 106 ft with the reference held
//! (docs/findings.md, The speed brake's size, and the bank reference, in moderate air).
//! The run flies the Chapter 7 loop formation.toml flew then
//! (`common::formation_chapter7_overrides`): on its energy loop, whose S-turns by geometry
//! reverse at a half width, not on a clock, stream 17 holds every axis under 2.1 ft with
//! either limit (measured), so it would test nothing there.

use crate::common::{formation_chapter7_overrides, run, worst_axis_ft};
use wingman::output::RunReport;
use wingman::output::summary::RunStatus;

/// formation.toml on the Chapter 7 loop with the target aircraft on the seed's profile and
/// the study's estimator, stream 17, with the bank limit acting where `limit` says.
fn slowest_turn(limit: &str) -> RunReport {
    let bank_limit = format!("autopilot.bank_limit=\"{limit}\"");
    let overrides = formation_chapter7_overrides(&[
        "output.frames_every=0",
        "run.seed=17",
        "target.model=\"aircraft\"",
        "estimator.target_gust_sigma_fps=0.8",
        "estimator.target_gust_time_s=1.5",
        "estimator.target_bank=\"measured\"",
        "estimator.jerk_psd=0.1",
        &bank_limit,
    ]);
    run("formation", &overrides)
}

/// The largest |φ_c| of the bank reference over the run, deg.
fn largest_bank_cmd_deg(report: &RunReport) -> f64 {
    report
        .logged
        .iter()
        .filter_map(|s| s.aircraft.as_ref())
        .map(|a| a.autopilot.euler_cmd.phi_rad.abs().to_degrees())
        .fold(0.0, f64::max)
}

#[test]
fn the_limit_on_the_reference_keeps_the_follower_on_its_slot_through_the_slowest_turn() {
    let held = slowest_turn("reference");
    let unheld = slowest_turn("command");
    let (bank_held, bank_unheld) = (largest_bank_cmd_deg(&held), largest_bank_cmd_deg(&unheld));
    println!(
        "largest bank reference: held {bank_held:.1}°, command only {bank_unheld:.1}°; RMS held {:?}, command only {:?}",
        held.summary.rms_error_last20s_ft, unheld.summary.rms_error_last20s_ft
    );
    assert!(
        bank_held <= 30.0 + 1e-9,
        "the reference reached {bank_held}°"
    );
    assert!(
        bank_unheld > 40.0,
        "the command's clamp: the reference reached only {bank_unheld}°"
    );
    assert_eq!(held.summary.status, RunStatus::Completed);
    assert_eq!(held.summary.lost_frames, 0);
    assert!(worst_axis_ft(&held.summary) < 3.0);
    assert!(worst_axis_ft(&unheld.summary) > 5.0);
}
