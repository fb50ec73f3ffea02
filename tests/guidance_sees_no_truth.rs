//! What the guidance and the telemetry are given comes from measurements, not from the truth:
//! a camera run's guidance state before its first frame does not depend on where the target
//! really is, and with two or more frames of latency the telemetry's frame columns show the
//! frame the guidance holds, not the newest one measured.

use crate::common;

use wingman::sim::{Simulation, StepOutcome};

/// The guidance's output at t = 0 of `vision_ch4_formation` with the target moved by `shift`.
fn first_command(shift_ft: [f64; 3]) -> wingman::guidance::signals::GuidanceOutput {
    let start = [200.0 + shift_ft[0], 50.0 + shift_ft[1], 30.0 + shift_ft[2]];
    let position = format!(
        "target.initial_position_ft=[{}, {}, {}]",
        start[0], start[1], start[2]
    );
    let scenario = common::load("vision_ch4_formation", &[&position]);
    Simulation::new(&scenario)
        .expect("set-up")
        .snapshot()
        .guidance
}

#[test]
fn guidance_before_the_first_frame_is_independent_of_the_target() {
    let here = first_command([0.0; 3]);
    let elsewhere = first_command([40.0, -25.0, 10.0]);
    assert_eq!(here.r_command, elsewhere.r_command);
    assert_eq!(here.command, elsewhere.command);
}

#[test]
fn telemetry_shows_the_frame_the_guidance_holds() {
    let rate_hz = 30.0;
    let latency_frames = 2.0;
    let scenario = common::load(
        "vision_ch4_formation",
        &[
            "run.duration_s=3",
            "camera.latency_frames=2",
            "camera.rate_hz=30",
        ],
    );
    let mut sim = Simulation::new(&scenario).expect("set-up");
    let mut checked = 0;
    while sim.step().expect("runs") == StepOutcome::Running {
        let snapshot = sim.snapshot();
        let Some(frame) = snapshot.frame else {
            continue;
        };
        let age_frames = (snapshot.t_s - frame.t_s) * rate_hz;
        assert!(
            (latency_frames - 1e-6..latency_frames + 1.0 - 1e-6).contains(&age_frames),
            "at t = {} s the logged frame is {age_frames} frames old",
            snapshot.t_s
        );
        checked += 1;
    }
    assert!(checked > 1000, "too few rows with a frame: {checked}");
}
