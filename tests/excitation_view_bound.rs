//! The excitation's size in the loop: formation.toml with a 20 ft target (34° of the 60° view
//! at the slot).
//! - The field of view's bound (stream 3): under the seed's scaled law (a = k_σ σ_b in units
//!   of b̂, so the swing in feet grows as b̂²) the unbounded excitation swings the target ±8 ft
//!   and loses it before 60 s (at 45 s, measured; streams 2 and 5 at 60 and 123 s); bounded at
//!   the estimated size (`excitation.fov_fraction = 0.7`, the scenario's) it keeps every
//!   frame (streams 3 and 5, 140 s).
//! - The relative law formation.toml flies (a = k_σ σ_b / b̂ in feet; stream 5): the swing follows the
//!   relative uncertainty alone, about 0.9 ft for this target, and the slot is held under 3 ft
//!   on every axis; the scaled law, bounded, swings it ±2.1 ft along the track on the seed's
//!   western leg, which the throttle cannot fly, and ends 3.7 and 4.9 ft off the slot across
//!   and below it (measured: docs/findings.md, The excitation and the field of view).

mod common;

use wingman::output::summary::{RunStatus, Summary};

/// The seed's law as formation.toml flew it before: scaled units, k_σ σ_b, k1 = 0.4.
const SCALED_LAW: [&str; 4] = [
    "excitation.mode=\"uncertainty\"",
    "excitation.units=\"scaled\"",
    "excitation.k_sigma=1.0",
    "excitation.k1=0.4",
];

fn run_20ft(seed: u64, duration_s: f64, extra: &[&str]) -> Summary {
    let duration = format!("run.duration_s={duration_s}");
    let stream = format!("run.seed={seed}");
    let mut sets = vec![
        "target.size_ft=20.0",
        stream.as_str(),
        "output.frames_every=0",
        duration.as_str(),
    ];
    sets.extend_from_slice(extra);
    common::run("formation", &sets).summary
}

#[test]
fn a_large_target_is_kept_in_view_by_the_bound() {
    let bounded = run_20ft(3, 60.0, &SCALED_LAW);
    assert_eq!(
        bounded.status,
        RunStatus::Completed,
        "{:?}",
        bounded.message
    );
    assert_eq!(bounded.lost_frames, 0, "{:?}", bounded.loss_episodes);
    let unbounded = run_20ft(
        3,
        60.0,
        &[&SCALED_LAW[..], &["excitation.fov_fraction=0.0"]].concat(),
    );
    assert!(
        unbounded.lost_frames > 0,
        "without the bound the 20 ft target leaves the view"
    );
}

#[test]
fn the_relative_excitation_holds_a_large_target_on_the_slot() {
    common::assert_held_on_the_slot(&run_20ft(5, 140.0, &[]));
    let scaled = run_20ft(5, 140.0, &SCALED_LAW);
    assert!(
        common::worst_axis_ft(&scaled) > 3.0,
        "the scaled law's swing along the track: {:?}",
        scaled.rms_error_last20s_ft
    );
}
