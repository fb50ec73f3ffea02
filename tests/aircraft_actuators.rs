//! Actuators, integrated as plant states with the simulation's RK4, never leave their position
//! limits (elevator and aileron ±30°, rudder ±20°: seed 7.4; throttle [0, 1]), never move
//! faster than their rate limits, and follow a small command as a first-order lag.
//!
//! The rate bound is exact for RK4: each step's increment is dt times a weighted mean of four
//! derivatives that are each clamped to the rate limit, so |Δδ| ≤ rate_limit · dt (1e-12 slack
//! for round-off).

use wingman::frames::{EulerAngles, Vec3};
use wingman::integrate::Rk4;
use wingman::world::aircraft::state::{AILERON_RAD, ELEVATOR_RAD, RUDDER_RAD, THROTTLE};
use wingman::world::aircraft::{Aircraft, AircraftParams, AircraftState, Controls, STATE_LEN};
use wingman::world::atmosphere::AtmosphereSample;

fn follower() -> Aircraft {
    Aircraft::new(AircraftParams::seed_follower().expect("valid data")).expect("valid aircraft")
}

fn start_state() -> Vec<f64> {
    AircraftState::from_euler(
        Vec3::new(0.0, 0.0, -500.0),
        &EulerAngles::default(),
        Vec3::new(50.0, 0.0, 3.0),
        Vec3::zeros(),
        Controls {
            throttle: 0.4,
            ..Controls::default()
        },
    )
    .pack()
    .to_vec()
}

/// Bang-bang commands far beyond the limits, switching every 1.5 s for 6 s: positions stay in
/// their limits, per-step changes stay within rate · dt, and the limits are reached (so the
/// check is not vacuous; "reached" = within 1e-4 of the range, which the lag's exponential
/// tail gets to well inside 1.5 s: ≥ 9 time constants after the rate-limited ramp).
#[test]
fn limits_and_rate_limits_hold_under_saturating_commands() {
    let aircraft = follower();
    let limits = aircraft.params().actuators;
    let air = AtmosphereSample::default();
    let mut x = start_state();
    let mut rk = Rk4::new(STATE_LEN);
    let dt_s = 0.001;
    let indices = [ELEVATOR_RAD, AILERON_RAD, RUDDER_RAD, THROTTLE];
    let specs = [
        limits.elevator,
        limits.aileron,
        limits.rudder,
        limits.throttle,
    ];
    let mut reached = [false; 4];
    for tick in 0..6000 {
        let sign = if (tick / 1500) % 2 == 0 { 1.0 } else { -1.0 };
        let commands = Controls {
            throttle: 0.5 + sign * 5.0,
            elevator_rad: sign * 2.0,
            aileron_rad: -sign * 2.0,
            rudder_rad: sign * 2.0,
        };
        let before = x.clone();
        rk.step(tick as f64 * dt_s, dt_s, &mut x, |_, x, dx| {
            aircraft.derivative(x, &commands, &air, dx)
        });
        aircraft.normalize(&mut x);
        for (k, (&i, spec)) in indices.iter().zip(&specs).enumerate() {
            assert!(x[i] >= spec.min && x[i] <= spec.max, "index {i}: {}", x[i]);
            let step = (x[i] - before[i]).abs();
            assert!(
                step <= spec.rate_limit_per_s * dt_s + 1e-12,
                "index {i}: moved {step} in one step"
            );
            let near = 1e-4 * (spec.max - spec.min);
            reached[k] |= (x[i] - spec.max).abs() < near || (x[i] - spec.min).abs() < near;
        }
    }
    assert_eq!(reached, [true; 4]);
    // The rudder's limit is ±20°, the elevator's ±30° (seed 7.4).
    assert!((limits.rudder.max.to_degrees() - 20.0).abs() < 1e-12);
    assert!((limits.elevator.min.to_degrees() + 30.0).abs() < 1e-12);
}

/// A 1° elevator step (needs 40 °/s at the start, below the 200 °/s limit) is a pure
/// first-order lag: after one time constant the elevator has covered 1 - e^-1 of the step
/// (RK4 at dt = τ/25 errs by ≈ 25 (dt/τ)⁵/120 ≈ 2e-8 relative; the bound is 1e-7).
#[test]
fn small_step_is_a_first_order_lag() {
    let aircraft = follower();
    let tau = aircraft.params().actuators.elevator.time_constant_s;
    let air = AtmosphereSample::default();
    let mut x = start_state();
    let mut rk = Rk4::new(STATE_LEN);
    let commands = Controls {
        throttle: 0.4,
        elevator_rad: 1f64.to_radians(),
        ..Controls::default()
    };
    let steps = 25;
    let dt_s = tau / steps as f64;
    for tick in 0..steps {
        rk.step(tick as f64 * dt_s, dt_s, &mut x, |_, x, dx| {
            aircraft.derivative(x, &commands, &air, dx)
        });
    }
    let expected = 1f64.to_radians() * (1.0 - (-1.0f64).exp());
    assert!(
        (x[ELEVATOR_RAD] - expected).abs() < 1e-7 * expected,
        "{} vs {expected}",
        x[ELEVATOR_RAD]
    );
}
