//! The energy outer loop (`autopilot.outer_loop = "energy"`; docs/equations.md, The energy
//! outer loop) flies the 6-DOF follower in calm air, from the 50 ft/s trim heading north,
//! commanded as a guidance law would command it (a velocity from the error).
//!
//! Invariants:
//! - a 30 ft height step at 50 ft/s: overshoot under 3 ft (10%), within ±1.5 ft (5%) after
//!   10 s, the airspeed within ±3.5 ft/s of 50 throughout;
//! - a 10 ft/s speed step at constant height: overshoot under 2.5 ft/s, within ±0.5 ft/s
//!   after 6 s, the height within ±2 ft throughout;
//! - with the thrust saturated (the follower with half its thrust coefficient told to climb
//!   at 10 ft/s at 50 ft/s, beyond full throttle), `energy_speed_weight` decides which is
//!   kept: 2 keeps the speed (within 1.5 ft/s) and gives up climb rate, 0 keeps the climb
//!   rate (within 1 ft/s of the demand) and gives up speed, 1 gives up some of each.

use crate::common::flight::{FlightSample, fly};
use wingman::frames::Vec3;
use wingman::scenario::{AutopilotSection, OuterLoop};
use wingman::world::aircraft::AircraftParams;
use wingman::world::atmosphere::AtmosphereConfig;

/// Integration step, s (as tests/control_flight.rs).
const DT_S: f64 = 0.005;
/// When each step is commanded, s.
const STEP_AT_S: f64 = 5.0;

/// The energy loop with the priority `speed_weight`, every other key its default.
fn energy(speed_weight: f64) -> AutopilotSection {
    AutopilotSection {
        outer_loop: OuterLoop::Energy,
        energy_speed_weight: speed_weight,
        ..AutopilotSection::default()
    }
}

/// The shipped follower with its thrust coefficient scaled by `thrust_scale`.
fn follower(thrust_scale: f64) -> AircraftParams {
    let mut params = AircraftParams::seed_follower().expect("built-in aircraft");
    params.propulsion.c_thrust_throttle *= thrust_scale;
    params
}

/// A guidance-like command: `speed_fps` north at `height_ft`, the height error flown back at
/// 0.5/s (within ±10 ft/s).
fn hold(speed_fps: f64, height_ft: f64, position: &Vec3) -> Vec3 {
    let climb_fps = (0.5 * (height_ft + position.z)).clamp(-10.0, 10.0);
    Vec3::new(speed_fps, 0.0, -climb_fps)
}

/// The step's overshoot past `target` (in the direction from `start`) after [`STEP_AT_S`],
/// and how long after it `value` last was outside `target` ± `band`.
fn step_response(
    flight: &[FlightSample],
    start: f64,
    target: f64,
    band: f64,
    value: impl Fn(&FlightSample) -> f64,
) -> (f64, f64) {
    let sign = (target - start).signum();
    let after: Vec<&FlightSample> = flight.iter().filter(|s| s.t_s >= STEP_AT_S).collect();
    let overshoot = after
        .iter()
        .map(|s| sign * (value(s) - target))
        .fold(0.0, f64::max);
    let settling_s = after
        .iter()
        .rev()
        .find(|s| (value(s) - target).abs() > band)
        .map_or(0.0, |s| s.t_s - STEP_AT_S);
    (overshoot, settling_s)
}

/// The largest |value - reference| over the flight.
fn largest_deviation(
    flight: &[FlightSample],
    reference: f64,
    value: impl Fn(&FlightSample) -> f64,
) -> f64 {
    flight
        .iter()
        .map(|s| (value(s) - reference).abs())
        .fold(0.0, f64::max)
}

/// The mean of `value` over [from_s, to_s).
fn mean(
    flight: &[FlightSample],
    from_s: f64,
    to_s: f64,
    value: impl Fn(&FlightSample) -> f64,
) -> f64 {
    let window: Vec<f64> = flight
        .iter()
        .filter(|s| s.t_s >= from_s && s.t_s < to_s)
        .map(value)
        .collect();
    window.iter().sum::<f64>() / window.len().max(1) as f64
}

#[test]
fn a_height_step_at_constant_speed() {
    let flight = fly(
        &follower(1.0),
        &energy(1.0),
        &AtmosphereConfig::default(),
        DT_S,
        30.0,
        |t, p| hold(50.0, if t >= STEP_AT_S { 30.0 } else { 0.0 }, p),
    );
    let (overshoot_ft, settling_s) = step_response(&flight, 0.0, 30.0, 1.5, |s| s.height_ft);
    let speed_fps = largest_deviation(&flight, 50.0, |s| s.airspeed_fps);
    println!(
        "height step: overshoot {overshoot_ft:.2} ft, settles in {settling_s:.1} s, airspeed within ±{speed_fps:.2} ft/s"
    );
    assert!(overshoot_ft < 3.0, "overshoot {overshoot_ft:.2} ft");
    assert!(settling_s < 10.0, "settles in {settling_s:.1} s");
    assert!(speed_fps < 3.5, "airspeed off by {speed_fps:.2} ft/s");
}

#[test]
fn a_speed_step_at_constant_height() {
    let flight = fly(
        &follower(1.0),
        &energy(1.0),
        &AtmosphereConfig::default(),
        DT_S,
        25.0,
        |t, p| hold(if t >= STEP_AT_S { 60.0 } else { 50.0 }, 0.0, p),
    );
    let (overshoot_fps, settling_s) = step_response(&flight, 50.0, 60.0, 0.5, |s| s.airspeed_fps);
    let height_ft = largest_deviation(&flight, 0.0, |s| s.height_ft);
    println!(
        "speed step: overshoot {overshoot_fps:.2} ft/s, settles in {settling_s:.1} s, height within ±{height_ft:.2} ft"
    );
    assert!(overshoot_fps < 2.5, "overshoot {overshoot_fps:.2} ft/s");
    assert!(settling_s < 6.0, "settles in {settling_s:.1} s");
    assert!(height_ft < 2.0, "height off by {height_ft:.2} ft");
}

#[test]
fn with_thrust_saturated_the_priority_decides_what_is_kept() {
    let demand_climb_fps = 10.0;
    // Mean climb rate, airspeed and throttle over the 3 s after the climb is established.
    let flown = |speed_weight: f64| {
        let flight = fly(
            &follower(0.5),
            &energy(speed_weight),
            &AtmosphereConfig::default(),
            DT_S,
            11.0,
            |t, _| {
                let climb = if t >= STEP_AT_S {
                    demand_climb_fps
                } else {
                    0.0
                };
                Vec3::new(50.0, 0.0, -climb)
            },
        );
        let (from, to) = (STEP_AT_S + 2.0, STEP_AT_S + 5.0);
        [
            mean(&flight, from, to, |s| -s.velocity_ned_fps.z),
            mean(&flight, from, to, |s| s.airspeed_fps),
            mean(&flight, from, to, |s| s.throttle),
        ]
    };
    let demand_speed_fps = 50f64.hypot(demand_climb_fps);
    let [height_climb, height_speed, height_throttle] = flown(0.0);
    let [even_climb, even_speed, _] = flown(1.0);
    let [speed_climb, speed_speed, speed_throttle] = flown(2.0);
    println!(
        "s = 0: climb {height_climb:.2} ft/s at {height_speed:.2} ft/s; 1: {even_climb:.2} at {even_speed:.2}; 2: {speed_climb:.2} at {speed_speed:.2} (demand {demand_climb_fps} at {demand_speed_fps:.2})"
    );
    assert!(
        height_throttle > 0.99 && speed_throttle > 0.99,
        "thrust not saturated"
    );
    assert!(
        (height_climb - demand_climb_fps).abs() < 1.0,
        "s = 0 climbs at {height_climb:.2} ft/s"
    );
    assert!(
        height_speed < demand_speed_fps - 3.0,
        "s = 0 keeps the speed: {height_speed:.2} ft/s"
    );
    assert!(
        (speed_speed - demand_speed_fps).abs() < 1.5,
        "s = 2 flies {speed_speed:.2} ft/s"
    );
    assert!(
        speed_climb < demand_climb_fps - 1.0,
        "s = 2 keeps the climb: {speed_climb:.2} ft/s"
    );
    assert!(
        even_climb < height_climb && even_climb > speed_climb,
        "s = 1 climbs at {even_climb:.2}"
    );
    assert!(
        even_speed > height_speed && even_speed < speed_speed,
        "s = 1 flies {even_speed:.2}"
    );
}
