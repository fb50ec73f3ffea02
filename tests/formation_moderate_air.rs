//! formation.toml in moderate turbulence, the keys that keep it (docs/findings.md, The
//! speed brake's size, and the bank reference, in moderate air). Streams 29, 21, 37 and 86
//! were found on the Chapter 7 loop formation.toml flew until it took the energy loop, and
//! their tests fly that loop (`common::formation_chapter7_overrides`): on the energy loop none of
//! the four shows its mechanism (measured: stream 29 with the 0.06 brake, 21 with the
//! command clamp and 37 at 120 °/s with the stops lose no frame; 86 with the stops loses 6
//! at 107 s, after the pass the test is about), so they would test nothing there.
//! - stream 29: an updraft of 9-13 ft/s held over 40-57 s while the target descends and
//!   slows. With the speed brake of ΔC_D 0.18 the follower sinks with the target; with 0.06
//!   (twice the clean drag, a glide of 10-12° at 45-50 ft/s) it stays above it and loses it
//!   at 53-64 s.
//! - stream 21: an S-turn's reversal in the target's slowest turn (35.4 ft/s at 96-100 s).
//!   With the bank reference held inside the 30° limit the follower keeps its height; with
//!   the seed's clamp on the raw command alone the reference overshoots to a bank the lift
//!   does not carry at 33-35 ft/s, the follower sinks 70 ft below the target and loses it.
//! - stream 28, formation.toml as shipped (the energy loop): a tailwind gust of 15-22 ft/s
//!   in the slowest turn carries the follower past a target fixed over the ground (4 frames
//!   lost, and 32 ft RMS along the track over the last 20 s; 24 frames with legs that
//!   alternate in the turn, hundreds with the pan's stops); a
//!   target in the same air (`target.path = "in_air_mass"`, `target.gusts = "shared"`, the
//!   filter's gust states set from the air's statistics) is carried too, and none is lost
//!   (docs/findings.md, The target in the air mass). Over streams 1-60 in that world no
//!   frame is lost and the worst RMS axis has a median of 3.1 ft; stream 28's is 5.12 ft,
//!   over the 5 (one of the four of 60 that miss it), so it is held under 6.5 ft.
//! - stream 37: in the slowest turn the target stands 15-22° from the pan's axis, where the
//!   pan turns fastest for the line of sight (the keyhole). At 101 s the pan command jumps
//!   from the pan's 170° stop to -80°, and the pan swings 226° the long way round: 0.75 s
//!   (23 frames) at formation.toml's 300 °/s, 1.9 s (56 frames) at the [camera.gimbal]
//!   default of 120 °/s. The camera loses 6 frames of the fast swing and 46 of the slow one
//!   (docs/findings.md, The gimbal's slew rate). The bars sit near half of each swing: at
//!   most 12 frames at 300 °/s, at least 30 at 120 °/s. formation.toml's pan has no stop
//!   now, so both runs set the stops at ±170° back: the test is of the servos' rate.
//! - stream 86: at 99.4 s, banked 35-40°, the line of sight's bearing in body axes passes
//!   behind the camera (the pan command from -170° through 180° to 143°). The pan held at its
//!   -170° stop leaves the target off the image's centre while the tilt makes up for it, up
//!   to its 90° limit at 101.5 s; the target leaves the image at 102.6 s and 55 frames are
//!   lost. A pan without stops (formation.toml's) turns through 180° and loses none
//!   (docs/findings.md, A pan without stops). Bars: at most 5 frames without stops, at least
//!   25 with them.

use crate::common;

use crate::common::worst_axis_ft;
use std::ops::Range;
use wingman::output::RunReport;
use wingman::output::summary::RunStatus;

/// The [camera.gimbal] default's pan stops, which formation.toml's slip ring does without.
const PAN_STOPS: &str = "camera.gimbal.pan_limits_deg=[-170,170]";

/// formation.toml in moderate turbulence on `seed`, with `overrides`.
fn moderate(seed: u32, overrides: &[&str]) -> RunReport {
    let seed_key = format!("run.seed={seed}");
    let mut all = vec![
        seed_key.as_str(),
        "atmosphere.turbulence=moderate",
        "output.frames_every=0",
    ];
    all.extend_from_slice(overrides);
    common::run("formation", &all)
}

/// formation.toml on the Chapter 7 loop in moderate turbulence on `seed`, with `overrides`.
fn moderate_chapter7(seed: u32, overrides: &[&str]) -> RunReport {
    moderate(seed, &common::formation_chapter7_overrides(overrides))
}

/// The first lost frame's time, s (`None`: no frame lost).
fn first_loss_s(report: &RunReport) -> Option<f64> {
    report.summary.loss_episodes.first().map(|e| e.start_s)
}

/// The run keeps the target and the slot (every axis under 5 ft RMS, no frame lost).
fn assert_kept(report: &RunReport) {
    let s = &report.summary;
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    assert_eq!(s.lost_frames, 0, "{:?}", s.loss_episodes);
    assert!(worst_axis_ft(s) < 5.0, "{:?}", s.rms_error_last20s_ft);
}

/// On `seed`, the scenario on the Chapter 7 loop keeps the target and the slot, and with
/// `without` (the key set back) the target is first lost within `lost_within_s`.
fn assert_the_key_keeps_the_target(seed: u32, without: &str, lost_within_s: Range<f64>) {
    let with_key = moderate_chapter7(seed, &[]);
    let reverted = moderate_chapter7(seed, &[without]);
    println!(
        "stream {seed}: lost {} with the key, {} with {without} (first at {:?} s)",
        with_key.summary.lost_frames,
        reverted.summary.lost_frames,
        first_loss_s(&reverted)
    );
    assert_kept(&with_key);
    let lost_at_s = first_loss_s(&reverted).expect("the target is lost without the key");
    assert!(lost_within_s.contains(&lost_at_s), "lost at {lost_at_s} s");
}

#[test]
fn the_brake_follows_the_target_down_through_a_sustained_updraft() {
    assert_the_key_keeps_the_target(29, "follower.speed_brake_c_drag=0.06", 40.0..70.0);
}

#[test]
fn the_bank_reference_held_keeps_the_height_in_the_slowest_turn() {
    assert_the_key_keeps_the_target(21, "autopilot.bank_limit=\"command\"", 94.0..104.0);
}

#[test]
fn a_target_in_the_same_air_is_not_overtaken_in_a_tailwind_gust() {
    let over_ground = moderate(28, &[]);
    let s = &over_ground.summary;
    assert!(
        s.lost_frames >= 2,
        "over the ground: {} lost",
        s.lost_frames
    );
    assert!(worst_axis_ft(s) > 15.0, "{:?}", s.rms_error_last20s_ft);
    let in_air = moderate(
        28,
        &[
            "target.path=in_air_mass",
            "target.gusts=shared",
            "estimator.target_gust_sigma_fps=6",
            "estimator.target_gust_time_s=19",
        ],
    );
    let s = &in_air.summary;
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    assert_eq!(s.lost_frames, 0, "{:?}", s.loss_episodes);
    assert!(worst_axis_ft(s) < 6.5, "{:?}", s.rms_error_last20s_ft);
}

#[test]
fn servos_at_300_dps_follow_the_pan_near_its_axis() {
    let through_the_turn = ["run.duration_s=104", PAN_STOPS];
    let fast = moderate_chapter7(37, &through_the_turn);
    let mut slow = through_the_turn.to_vec();
    slow.push("camera.gimbal.rate_limit_dps=120");
    let slow = moderate_chapter7(37, &slow);
    let (fast_lost, slow_lost) = (fast.summary.lost_frames, slow.summary.lost_frames);
    println!("stream 37 to 104 s: {fast_lost} frames lost at 300 °/s, {slow_lost} at 120 °/s");
    assert!(fast_lost <= 12, "{:?}", fast.summary.loss_episodes);
    assert!(slow_lost >= 30, "{:?}", slow.summary.loss_episodes);
}

#[test]
fn a_pan_without_stops_turns_through_the_back() {
    let through_the_turn = "run.duration_s=108";
    let slip_ring = moderate_chapter7(86, &[through_the_turn]);
    let stopped = moderate_chapter7(86, &[through_the_turn, PAN_STOPS]);
    let (slip_ring_lost, stops_lost) = (slip_ring.summary.lost_frames, stopped.summary.lost_frames);
    println!("stream 86 to 108 s: {slip_ring_lost} frames lost without stops, {stops_lost} with");
    assert!(slip_ring_lost <= 5, "{:?}", slip_ring.summary.loss_episodes);
    assert!(stops_lost >= 25, "{:?}", stopped.summary.loss_episodes);
}
