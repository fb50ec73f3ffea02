//! The excitation's size in the loop: formation.toml with a 20 ft target (34° of the 60° view
//! at the slot).
//! - The field of view's bound (stream 3, 60 s): under the seed's scaled law (a = k_σ σ_b in
//!   units of b̂, so the swing in feet grows as b̂²) the unbounded excitation swings the target
//!   ±8 ft. With formation.toml's former speed brake (ΔC_D 0.06) that lost it at 45 s (streams
//!   2 and 5 at 60 and 123 s); with its 0.18 the follower keeps it in view but flies the
//!   swing, 4.9 ft RMS across the track over 40-60 s. Bounded at the estimated size
//!   (`excitation.fov_fraction = 0.7`, the scenario's) every axis stays under 2.3 ft. Over
//!   streams 1-10 (60 s) the worst axis reads a median 2.5 ft bounded (at most 4.1, stream 2)
//!   against 5.7 unbounded (at least 4.5), no frame lost either way (docs/findings.md, The
//!   excitation and the field of view). These runs fly the Chapter 7 loop formation.toml
//!   flew then (`common::formation_chapter7_overrides`): its energy loop flies less of the
//!   unbounded swing (stream 3: 3.6 ft on the worst axis, measured), short of a clear bar.
//! - The relative law formation.toml flies (a = k_σ σ_b / b̂ in feet; stream 5, the energy
//!   loop): the swing follows the relative uncertainty alone: the largest |R*_c - R_c| after
//!   30 s is 1.3 ft for this target where the scaled law, bounded, reaches 2.8 ft, and the
//!   slot is held under 3 ft on every axis. Over streams 1-5 the relative law's swing is
//!   0.39-0.45 of the scaled law's, every axis under 1.6 ft; the scaled law's under 2.1 ft
//!   (measured. On the Chapter 7 loop with the 0.06 brake the scaled law's swing along the
//!   track, which the throttle could not fly, left it 3.7 and 4.9 ft off the slot; with 0.18
//!   under 2.6 ft on streams 1-5.)

use crate::common;

use wingman::output::RunReport;
use wingman::output::summary::RunStatus;

/// The seed's law as formation.toml flew it before: scaled units, k_σ σ_b, k1 = 0.4.
const SCALED_LAW: [&str; 4] = [
    "excitation.mode=\"uncertainty\"",
    "excitation.units=\"scaled\"",
    "excitation.k_sigma=1.0",
    "excitation.k1=0.4",
];

fn run_20ft(seed: u64, duration_s: f64, extra: &[&str]) -> RunReport {
    let duration = format!("run.duration_s={duration_s}");
    let stream = format!("run.seed={seed}");
    let mut sets = vec![
        "target.size_ft=20.0",
        stream.as_str(),
        "output.frames_every=0",
        duration.as_str(),
    ];
    sets.extend_from_slice(extra);
    common::run("formation", &sets)
}

#[test]
fn a_large_target_is_kept_in_view_by_the_bound() {
    let scaled_on_chapter7 = common::formation_chapter7_overrides(&SCALED_LAW);
    let bounded = run_20ft(3, 60.0, &scaled_on_chapter7).summary;
    assert_eq!(
        bounded.status,
        RunStatus::Completed,
        "{:?}",
        bounded.message
    );
    assert_eq!(bounded.lost_frames, 0, "{:?}", bounded.loss_episodes);
    assert!(
        common::worst_axis_ft(&bounded) < 3.0,
        "{:?}",
        bounded.rms_error_last20s_ft
    );
    let unbounded = run_20ft(
        3,
        60.0,
        &[&scaled_on_chapter7[..], &["excitation.fov_fraction=0.0"]].concat(),
    )
    .summary;
    assert!(
        common::worst_axis_ft(&unbounded) > 4.0,
        "without the bound the 20 ft target's swing is flown: {:?}",
        unbounded.rms_error_last20s_ft
    );
}

#[test]
fn the_relative_excitation_holds_a_large_target_on_the_slot() {
    let relative = run_20ft(5, 140.0, &[]);
    common::assert_held_on_the_slot(&relative.summary);
    let scaled = run_20ft(5, 140.0, &SCALED_LAW);
    let (swing_relative_ft, swing_scaled_ft) =
        (largest_swing_ft(&relative), largest_swing_ft(&scaled));
    println!(
        "largest swing after 30 s: relative {swing_relative_ft:.2} ft, scaled {swing_scaled_ft:.2} ft"
    );
    assert!(
        swing_relative_ft < 0.5 * swing_scaled_ft,
        "relative {swing_relative_ft} ft, scaled {swing_scaled_ft} ft"
    );
}

/// The largest |R*_c - R_c| after 30 s (the excitation's swing once b is known), ft.
fn largest_swing_ft(report: &RunReport) -> f64 {
    report
        .logged
        .iter()
        .filter(|s| s.t_s >= 30.0)
        .map(|s| (s.excited_command_ned_ft - s.command_ned_ft).norm())
        .fold(0.0, f64::max)
}
