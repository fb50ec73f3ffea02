//! The plant's equations of motion are right where an exact answer exists:
//! - with no air (density 0: no aerodynamic or thrust loads) the centre of gravity falls freely,
//!   v_NED(t) = v_NED(0) + g t e_down, whatever the body does;
//! - torque-free rotation keeps the inertial angular momentum R(q) J ω and the rotational
//!   energy ½ ωᵀ J ω (with a nonzero Jxz: the inertia coupling of (7.16)), matches Euler's
//!   closed-form solution for an axisymmetric body, and keeps the quaternion's norm at 1;
//! - the body-axis derivative agrees with the seed's wind-axis form (7.15) for V̇ and α̇.
//!
//! Tolerances: RK4's global error over these runs is ~(ω dt)⁴ ≈ 1e-10 relative or less, so
//! 1e-8 relative leaves two decades for round-off while still catching any wrong sign or
//! missing term (those show up at the 1e-2 level).

use wingman::frames::{EulerAngles, GRAVITY_FPS2, Mat3, Vec3};
use wingman::integrate::Rk4;
use wingman::world::aircraft::{Aircraft, AircraftParams, AircraftState, Controls, STATE_LEN};
use wingman::world::atmosphere::AtmosphereSample;

fn aircraft_with_inertia(jxx: f64, jyy: f64, jzz: f64, jxz: f64) -> Aircraft {
    let mut params = AircraftParams::seed_follower().expect("built-in data is valid");
    params.mass.jxx_slug_ft2 = jxx;
    params.mass.jyy_slug_ft2 = jyy;
    params.mass.jzz_slug_ft2 = jzz;
    params.mass.jxz_slug_ft2 = jxz;
    Aircraft::new(params).expect("valid aircraft")
}

fn vacuum() -> AtmosphereSample {
    AtmosphereSample::calm(0.0)
}

/// Integrates `seconds` at `dt_s` without air; `normalize` chooses whether the quaternion is
/// renormalised.
fn fly_in_vacuum(
    aircraft: &Aircraft,
    x: &mut [f64],
    controls: &Controls,
    seconds: f64,
    dt_s: f64,
    normalize: bool,
    mut each: impl FnMut(&[f64]),
) {
    let air = vacuum();
    let mut rk = Rk4::new(STATE_LEN);
    let steps = (seconds / dt_s).round() as usize;
    for tick in 0..steps {
        rk.step(tick as f64 * dt_s, dt_s, x, |_, x, dx| {
            aircraft.derivative(x, controls, &air, dx)
        });
        if normalize {
            aircraft.normalize(x);
        }
        each(x);
    }
}

/// Free fall: tumbling, moving, full throttle and deflected surfaces, but no air, so the only
/// force is gravity. After 5 s the NED velocity is v0 + g t e_down and the position the
/// parabola, to 1e-8 relative.
#[test]
fn free_fall_without_air_follows_gravity_alone() {
    let aircraft = aircraft_with_inertia(0.1230, 0.1747, 0.2553, 0.0);
    let controls = Controls {
        throttle: 1.0,
        elevator_rad: 0.2,
        aileron_rad: -0.2,
        rudder_rad: 0.1,
    };
    let start = AircraftState::from_euler(
        Vec3::new(10.0, -5.0, -300.0),
        &EulerAngles::new(0.4, -0.3, 2.0),
        Vec3::new(30.0, 4.0, -2.0),
        Vec3::new(1.5, -0.7, 0.9),
        controls,
    );
    let v0 = start.velocity_ned_fps();
    let mut x = start.pack().to_vec();
    let t = 5.0;
    fly_in_vacuum(&aircraft, &mut x, &controls, t, 0.002, true, |_| {});
    let end = AircraftState::unpack(&x).expect("valid");
    let g = Vec3::new(0.0, 0.0, GRAVITY_FPS2);
    let v_expected = v0 + g * t;
    let p_expected = start.position_ned_ft + v0 * t + 0.5 * g * t * t;
    assert!(
        (end.velocity_ned_fps() - v_expected).norm() < 1e-8 * v_expected.norm(),
        "{:?} vs {v_expected:?}",
        end.velocity_ned_fps()
    );
    assert!((end.position_ned_ft - p_expected).norm() < 1e-8 * p_expected.norm());
}

/// Torque-free tumbling with inertia coupling (Jxz = 0.03 slug ft²): the inertial angular
/// momentum and the rotational energy stay constant over 10 s at dt = 2 ms, and the quaternion's
/// norm stays 1 to 1e-10 even without renormalisation (RK4 drifts it only at order dt⁴).
#[test]
fn torque_free_rotation_conserves_momentum_energy_and_norm() {
    let aircraft = aircraft_with_inertia(0.1230, 0.1747, 0.2553, 0.03);
    let j: Mat3 = *aircraft.inertia_slug_ft2();
    let start = AircraftState::from_euler(
        Vec3::zeros(),
        &EulerAngles::new(0.1, 0.2, 0.3),
        Vec3::zeros(),
        Vec3::new(2.0, 0.5, -1.0),
        Controls::default(),
    );
    let momentum = |s: &AircraftState| s.attitude * (j * s.body_rates_rps);
    let energy = |s: &AircraftState| 0.5 * s.body_rates_rps.dot(&(j * s.body_rates_rps));
    let (h0, e0) = (momentum(&start), energy(&start));
    let mut x = start.pack().to_vec();
    let (mut worst_h, mut worst_e, mut worst_norm) = (0.0f64, 0.0f64, 0.0f64);
    fly_in_vacuum(
        &aircraft,
        &mut x,
        &Controls::default(),
        10.0,
        0.002,
        false,
        |x| {
            let norm = x[6..10].iter().map(|c| c * c).sum::<f64>().sqrt();
            worst_norm = worst_norm.max((norm - 1.0).abs());
            let s = AircraftState::unpack(x).expect("valid");
            worst_h = worst_h.max((momentum(&s) - h0).norm() / h0.norm());
            worst_e = worst_e.max((energy(&s) - e0).abs() / e0);
        },
    );
    assert!(worst_h < 1e-8, "angular momentum drift {worst_h:e}");
    assert!(worst_e < 1e-8, "energy drift {worst_e:e}");
    assert!(worst_norm < 1e-10, "quaternion norm drift {worst_norm:e}");
}

/// Axisymmetric body (Jxx = Jyy): Euler's equations give ω_z constant and the transverse rate
/// turning at λ = (Jzz - Jxx) ω_z / Jxx: ω_x = w0 cos λt, ω_y = w0 sin λt.
#[test]
fn axisymmetric_body_precesses_at_eulers_rate() {
    let (j1, j3) = (0.15, 0.25);
    let aircraft = aircraft_with_inertia(j1, j1, j3, 0.0);
    let (w0, wz) = (1.0, 3.0);
    let start = AircraftState::from_euler(
        Vec3::zeros(),
        &EulerAngles::default(),
        Vec3::zeros(),
        Vec3::new(w0, 0.0, wz),
        Controls::default(),
    );
    let mut x = start.pack().to_vec();
    let t = 4.0;
    fly_in_vacuum(
        &aircraft,
        &mut x,
        &Controls::default(),
        t,
        0.002,
        true,
        |_| {},
    );
    let lambda = (j3 - j1) * wz / j1;
    let expected = Vec3::new(w0 * (lambda * t).cos(), w0 * (lambda * t).sin(), wz);
    let rates = AircraftState::unpack(&x).expect("valid").body_rates_rps;
    assert!(
        (rates - expected).norm() < 1e-8,
        "{rates:?} vs {expected:?}"
    );
}

/// The body-axis derivative reproduces the seed's (7.15) in still air:
/// V̇ = (1/m)(-D - m g sinγ + T cosβ cosα) for a general state, and, wings level with β = 0
/// and p = r = 0 (μ = 0), α̇ = q - q_w with q_w = (L - m g cosγ + T sinα)/(m V).
/// Both sides are algebraic identities, so they agree to round-off (1e-9 relative).
#[test]
fn body_axis_form_matches_seed_wind_axis_form() {
    let aircraft = aircraft_with_inertia(0.1230, 0.1747, 0.2553, 0.0);
    let air = AtmosphereSample::default();
    let m = aircraft.params().mass.mass_slug;
    let g = GRAVITY_FPS2;
    let controls = Controls {
        throttle: 0.6,
        elevator_rad: -0.05,
        aileron_rad: 0.03,
        rudder_rad: -0.02,
    };
    let general = AircraftState::from_euler(
        Vec3::new(0.0, 0.0, -200.0),
        &EulerAngles::new(0.3, 0.1, -0.5),
        Vec3::new(48.0, 3.0, 5.0),
        Vec3::new(0.2, -0.1, 0.15),
        controls,
    );
    let level = AircraftState::from_euler(
        Vec3::new(0.0, 0.0, -200.0),
        &EulerAngles::new(0.0, 0.02, 1.0),
        Vec3::new(49.0, 0.0, 4.0),
        Vec3::new(0.0, 0.3, 0.0),
        controls,
    );
    for (state, check_alpha) in [(general, false), (level, true)] {
        let x = state.pack();
        let mut dx = [0.0; STATE_LEN];
        aircraft.derivative(&x, &controls, &air, &mut dx);
        let d = aircraft.air_data(&x, &air).expect("valid");
        let (u, v, w) = (x[3], x[4], x[5]);
        let (ud, vd, wd) = (dx[3], dx[4], dx[5]);
        let v_dot = (u * ud + v * vd + w * wd) / d.airspeed_fps;
        let seed_v_dot = (-d.drag_lbf - m * g * d.flight_path_rad.sin()
            + d.thrust_lbf * d.beta_rad.cos() * d.alpha_rad.cos())
            / m;
        assert!((v_dot - seed_v_dot).abs() < 1e-9 * seed_v_dot.abs().max(1.0));
        if check_alpha {
            let alpha_dot = (u * wd - w * ud) / (u * u + w * w);
            let q_w = (d.lift_lbf - m * g * d.flight_path_rad.cos()
                + d.thrust_lbf * d.alpha_rad.sin())
                / (m * d.airspeed_fps);
            let seed_alpha_dot = d.body_rates_rps.y - q_w;
            assert!((alpha_dot - seed_alpha_dot).abs() < 1e-9 * seed_alpha_dot.abs().max(1.0));
        }
    }
}

/// Renormalisation: after `normalize` the quaternion has norm 1 to round-off and an actuator
/// position pushed outside its limit is put back on it.
#[test]
fn normalize_restores_unit_quaternion_and_actuator_limits() {
    let aircraft = aircraft_with_inertia(0.1230, 0.1747, 0.2553, 0.0);
    let mut x = AircraftState::from_euler(
        Vec3::zeros(),
        &EulerAngles::new(0.1, 0.2, 0.3),
        Vec3::new(50.0, 0.0, 0.0),
        Vec3::zeros(),
        Controls::default(),
    )
    .pack();
    x[6..10].iter_mut().for_each(|c| *c *= 1.01);
    x[13] = 1.0; // elevator beyond +30°
    x[16] = -0.2; // throttle below 0
    aircraft.normalize(&mut x);
    let norm = x[6..10].iter().map(|c| c * c).sum::<f64>().sqrt();
    assert!((norm - 1.0).abs() < 1e-15);
    assert!((x[13] - 30f64.to_radians()).abs() < 1e-15);
    assert_eq!(x[16], 0.0);
}
