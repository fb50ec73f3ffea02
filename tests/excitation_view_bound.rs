//! The excitation's field-of-view bound in the loop: formation.toml with a 20 ft target
//! (34° of the 60° view at the slot). Set in scaled units, the unbounded excitation swings it
//! ±8 ft and loses it before 60 s on stream 5 (at 45 s, measured); bounded at the estimated
//! size (`excitation.fov_fraction = 0.7`, the scenario's), the same stream keeps every frame.

mod common;

use wingman::output::summary::RunStatus;

fn run_20ft(fov_fraction: &str) -> wingman::output::summary::Summary {
    let fraction = format!("excitation.fov_fraction={fov_fraction}");
    let sets = [
        "target.size_ft=20.0",
        "run.seed=5",
        "run.duration_s=60.0",
        "output.frames_every=0",
        fraction.as_str(),
    ];
    common::run("formation", &sets).summary
}

#[test]
fn a_large_target_is_kept_in_view_by_the_bound() {
    let bounded = run_20ft("0.7");
    assert_eq!(
        bounded.status,
        RunStatus::Completed,
        "{:?}",
        bounded.message
    );
    assert_eq!(bounded.lost_frames, 0, "{:?}", bounded.loss_episodes);
    let unbounded = run_20ft("0.0");
    assert!(
        unbounded.lost_frames > 0,
        "without the bound the 20 ft target leaves the view"
    );
}
