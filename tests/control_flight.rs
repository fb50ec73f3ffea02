//! The Chapter 7 flight controller flies the 6-DOF follower (seed 7.4, Fig 7.1-7.13): plant
//! plus autopilot integrated together by the simulation's RK4 at dt = 5 ms, starting from the
//! 50 ft/s trim heading north.
//!
//! Invariants: a constant command holds speed and height; the seed's target velocity profile
//! is followed with every surface inside its limits, small sideslip, α below stall and the
//! airspeed inside 30-70 ft/s, in calm air and in light Dryden turbulence; an unreachable
//! speed command saturates the throttle without the RBF weights winding up, and the aircraft
//! recovers when the command comes back.

use crate::common;

use wingman::control::{Autopilot, AutopilotInput, AutopilotOutput, AutopilotState, weave_side};
use wingman::frames::{SEA_LEVEL_DENSITY_SLUG_FT3, Vec3};
use wingman::integrate::Rk4;
use wingman::scenario::{AutopilotSection, TargetSection};
use wingman::world::aircraft::{
    Aircraft, AircraftParams, AircraftState, STATE_LEN, TrimRequest, trim_level_flight,
};
use wingman::world::atmosphere::{
    Atmosphere, AtmosphereConfig, AtmosphereSample, DisturbanceConfig, TurbulenceLevel,
};
use wingman::world::target::TargetMotionModel;

/// Integration step, s (the brief's ≤ 5 ms; the roll mode's ≈ 17 ms time constant and the
/// 25 ms servos are well resolved).
const DT_S: f64 = 0.005;

/// One logged instant.
#[derive(Debug, Clone, Copy)]
struct Sample {
    t_s: f64,
    velocity_ned_fps: Vec3,
    command_ned_fps: Vec3,
    airspeed_fps: f64,
    alpha_rad: f64,
    beta_rad: f64,
    altitude_ft: f64,
    out: AutopilotOutput,
    /// Actuator positions (what the surfaces actually do).
    surfaces_rad: Vec3,
    drag_weight_norm: f64,
    moment_weight_norm_max: f64,
}

struct Flight {
    samples: Vec<Sample>,
    drag_bound: f64,
    moment_bound: f64,
}

fn norm(w: &[f64]) -> f64 {
    w.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// Flies `duration_s` from the 50 ft/s trim heading north at 500 ft, commanded with
/// `command(t)`.
fn fly(
    section: &AutopilotSection,
    turbulence: TurbulenceLevel,
    duration_s: f64,
    command: impl Fn(f64) -> Vec3,
) -> Flight {
    let config = AtmosphereConfig {
        turbulence,
        ..AtmosphereConfig::default()
    };
    fly_in(section, &config, 7, duration_s, command)
}

/// As [`fly`], in the air `config` describes (turbulence seeded with `seed`); the trim is
/// solved in the steady air without the Δ perturbations (the controller does not know them).
fn fly_in(
    section: &AutopilotSection,
    config: &AtmosphereConfig,
    seed: u64,
    duration_s: f64,
    command: impl Fn(f64) -> Vec3,
) -> Flight {
    let params = AircraftParams::seed_follower().expect("built-in aircraft");
    let aircraft = Aircraft::new(params.clone()).expect("valid aircraft");
    let autopilot = Autopilot::new(&params, section).expect("valid autopilot");
    let mut atmosphere = Atmosphere::new(config, seed).expect("valid atmosphere");
    let start = Vec3::zeros();
    let trim_air = AtmosphereSample {
        drag_factor: 1.0,
        moment_bias_body_lbf_ft: Vec3::zeros(),
        ..atmosphere.steady_sample(&start)
    };
    let trim = trim_level_flight(
        &aircraft,
        &TrimRequest {
            airspeed_fps: 50.0,
            position_ned_ft: start,
            heading_rad: 0.0,
            air: trim_air,
        },
    )
    .expect("trims at 50 ft/s");
    let mut x = trim.state.pack().to_vec();
    let air0 = atmosphere.steady_sample(&start);
    let data0 = aircraft.air_data(&x, &air0).expect("valid state");
    x.extend(autopilot.initial_state(&data0));
    let n = x.len();
    let mut rk = Rk4::new(n);
    let ticks = (duration_s / DT_S).round() as usize;
    let mut samples = Vec::with_capacity(ticks / 10 + 1);
    for tick in 0..ticks {
        let t_s = tick as f64 * DT_S;
        let state = AircraftState::unpack(&x).expect("valid state");
        let airspeed = aircraft
            .air_data(&x, &atmosphere.steady_sample(&state.position_ned_ft))
            .expect("valid")
            .airspeed_fps;
        let air = atmosphere.sample(DT_S, &state.position_ned_ft, airspeed);
        let mut scratch = vec![0.0; autopilot.state_len()];
        // Log the instant at the start of the step.
        if tick % 10 == 0 {
            let data = aircraft.air_data(&x, &air).expect("valid state");
            let input = AutopilotInput {
                velocity_cmd_ned_fps: command(t_s),
                air_data: data,
                sensed_air_data: data,
                actuators: state.actuators,
                weave_side: weave_side(t_s, section.weave_period_s),
                slot_line: None,
            };
            let out = autopilot.derivative(&x[STATE_LEN..], &input, &mut scratch);
            let weights = AutopilotState::unpack(&x[STATE_LEN..]);
            let [wl, wm, wn] = weights.moment_weights();
            samples.push(Sample {
                t_s,
                velocity_ned_fps: data.velocity_ned_fps,
                command_ned_fps: command(t_s),
                airspeed_fps: data.airspeed_fps,
                alpha_rad: data.alpha_rad,
                beta_rad: data.beta_rad,
                altitude_ft: -state.position_ned_ft.z,
                out,
                surfaces_rad: Vec3::new(
                    state.actuators.elevator_rad,
                    state.actuators.aileron_rad,
                    state.actuators.rudder_rad,
                ),
                drag_weight_norm: norm(weights.drag_weights()),
                moment_weight_norm_max: norm(wl).max(norm(wm)).max(norm(wn)),
            });
        }
        rk.step(t_s, DT_S, &mut x, |t, x, dx| {
            let (plant, ctrl) = x.split_at(STATE_LEN);
            let (dplant, dctrl) = dx.split_at_mut(STATE_LEN);
            let Some(data) = aircraft.air_data(plant, &air) else {
                dx.fill(0.0);
                return;
            };
            let Some(state) = AircraftState::unpack(plant) else {
                dx.fill(0.0);
                return;
            };
            let input = AutopilotInput {
                velocity_cmd_ned_fps: command(t),
                air_data: data,
                sensed_air_data: data,
                actuators: state.actuators,
                weave_side: weave_side(t_s, section.weave_period_s),
                slot_line: None,
            };
            let out = autopilot.derivative(ctrl, &input, dctrl);
            aircraft.derivative(plant, &out.controls, &air, dplant);
        });
        aircraft.normalize(&mut x);
        autopilot.enforce_bounds(&mut x[STATE_LEN..]);
        assert!(x.iter().all(|v| v.is_finite()), "state diverged at {t_s} s");
    }
    Flight {
        samples,
        drag_bound: autopilot.drag_weight_outer_bound(),
        moment_bound: autopilot.moment_weight_outer_bound(),
    }
}

/// Summary numbers of a flight over samples with t ≥ `from_s`.
#[derive(Debug)]
struct Stats {
    rms_velocity_error_fps: Vec3,
    max_abs_alpha_deg: f64,
    max_abs_beta_deg: f64,
    max_abs_surfaces_deg: Vec3,
    airspeed_range_fps: (f64, f64),
    altitude_range_ft: (f64, f64),
    any_saturation: bool,
    throttle_saturated_fraction: f64,
}

fn stats(flight: &Flight, from_s: f64) -> Stats {
    let s: Vec<&Sample> = flight.samples.iter().filter(|s| s.t_s >= from_s).collect();
    let n = s.len().max(1) as f64;
    let mut sq = Vec3::zeros();
    let mut st = Stats {
        rms_velocity_error_fps: Vec3::zeros(),
        max_abs_alpha_deg: 0.0,
        max_abs_beta_deg: 0.0,
        max_abs_surfaces_deg: Vec3::zeros(),
        airspeed_range_fps: (f64::INFINITY, f64::NEG_INFINITY),
        altitude_range_ft: (f64::INFINITY, f64::NEG_INFINITY),
        any_saturation: false,
        throttle_saturated_fraction: 0.0,
    };
    let mut throttle_sat = 0usize;
    for x in &s {
        let e = x.velocity_ned_fps - x.command_ned_fps;
        sq += e.component_mul(&e);
        st.max_abs_alpha_deg = st.max_abs_alpha_deg.max(x.alpha_rad.to_degrees().abs());
        st.max_abs_beta_deg = st.max_abs_beta_deg.max(x.beta_rad.to_degrees().abs());
        for i in 0..3 {
            st.max_abs_surfaces_deg[i] =
                st.max_abs_surfaces_deg[i].max(x.surfaces_rad[i].to_degrees().abs());
        }
        st.airspeed_range_fps.0 = st.airspeed_range_fps.0.min(x.airspeed_fps);
        st.airspeed_range_fps.1 = st.airspeed_range_fps.1.max(x.airspeed_fps);
        st.altitude_range_ft.0 = st.altitude_range_ft.0.min(x.altitude_ft);
        st.altitude_range_ft.1 = st.altitude_range_ft.1.max(x.altitude_ft);
        let sat = x.out.saturation;
        st.any_saturation |= sat.elevator || sat.aileron || sat.rudder;
        if sat.throttle {
            throttle_sat += 1;
        }
    }
    st.rms_velocity_error_fps = (sq / n).map(f64::sqrt);
    st.throttle_saturated_fraction = throttle_sat as f64 / n;
    st
}

fn seed_target() -> TargetMotionModel {
    TargetMotionModel::from_section(&TargetSection::default()).expect("closed form")
}

/// RMS of the vertical velocity error over the samples (t ≥ `from_s`) where no flight-path
/// limit changed γ_c: what is left once the thrust-limited stretches are set aside.
fn vertical_rms_unlimited(flight: &Flight, from_s: f64) -> f64 {
    let errors: Vec<f64> = flight
        .samples
        .iter()
        .filter(|s| s.t_s >= from_s && !s.out.flight_path_limited)
        .map(|s| s.velocity_ned_fps.z - s.command_ned_fps.z)
        .collect();
    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len().max(1) as f64).sqrt()
}

/// Lowest speed of the seed's target profile, ft/s (x = 25(1 + cos), y = 25(1 - cos) cross
/// at 25√2; docs/equations.md, The relative motion and the seed's scenario: "about 35-60
/// ft/s").
const PROFILE_MIN_SPEED_FPS: f64 = 35.355;

fn report(name: &str, flight: &Flight, from_s: f64) -> Stats {
    let st = stats(flight, from_s);
    println!(
        "{name}: velocity RMS (n, e, d) = ({:.3}, {:.3}, {:.3}) ft/s, d where γ_c is not limited {:.3} ft/s; \
         max |α| = {:.2}°, max |β| = {:.2}°; max |δe|, |δa|, |δr| = {:.2}°, {:.2}°, {:.2}°; \
         V in [{:.2}, {:.2}] ft/s; height in [{:.1}, {:.1}] ft; throttle clamped {:.1} % of the time",
        st.rms_velocity_error_fps.x,
        st.rms_velocity_error_fps.y,
        st.rms_velocity_error_fps.z,
        vertical_rms_unlimited(flight, from_s),
        st.max_abs_alpha_deg,
        st.max_abs_beta_deg,
        st.max_abs_surfaces_deg.x,
        st.max_abs_surfaces_deg.y,
        st.max_abs_surfaces_deg.z,
        st.airspeed_range_fps.0,
        st.airspeed_range_fps.1,
        st.altitude_range_ft.0,
        st.altitude_range_ft.1,
        100.0 * st.throttle_saturated_fraction,
    );
    st
}

/// (a) Commanded to keep flying the trim velocity, the aircraft does: the controller's initial
/// state reproduces the trim (θ_c = γ_c + α_ref with α_ref from the same lift curve the plant
/// uses), so only round-off moves it. 60 s; bands 0.01 ft/s and 0.01 ft are far above the
/// round-off seen (1e-8) and far below anything a sign or offset error would give (the seed's
/// θ_c = γ_c alone would sink at 4 ft/s).
#[test]
fn trim_velocity_command_holds_speed_and_height() {
    let flight = fly(
        &AutopilotSection::default(),
        TurbulenceLevel::Off,
        60.0,
        |_| Vec3::new(50.0, 0.0, 0.0),
    );
    let st = report("hold 50 ft/s north", &flight, 0.0);
    assert!(
        st.airspeed_range_fps.0 > 49.99 && st.airspeed_range_fps.1 < 50.01,
        "{st:?}"
    );
    assert!(
        st.altitude_range_ft.0 > -0.01 && st.altitude_range_ft.1 < 0.01,
        "{st:?}"
    );
    assert!(st.rms_velocity_error_fps.amax() < 0.01, "{st:?}");
}

/// (a) A new constant velocity (50 ft/s on a course of 36.9°, a 37° heading step) is reached
/// and then held: after 20 s the velocity matches to 0.01 ft/s and the height no longer
/// changes. The step is flown as a banked turn: the heading-rate demand is capped at the
/// rate of a coordinated turn at the 30° bank limit, and the bank is commanded for the heading
/// rate demanded (not only the reference's), so no surface reaches its limit and the
/// sideslip stays under 5° (measured 3.5°) and the height loss under 5 ft (measured 4.5 ft:
/// the turn is banked from its start) even for this abrupt command.
#[test]
fn constant_velocity_step_is_reached_and_held() {
    let command = Vec3::new(40.0, 30.0, 0.0);
    let flight = fly(
        &AutopilotSection::default(),
        TurbulenceLevel::Off,
        40.0,
        move |_| command,
    );
    let all = report("step to (40, 30, 0) ft/s", &flight, 0.0);
    assert!(!all.any_saturation, "{all:?}");
    assert!(all.max_abs_beta_deg < 5.0, "{all:?}");
    assert!(all.altitude_range_ft.0 > -5.0, "{all:?}");
    let late = stats(&flight, 20.0);
    assert!(late.rms_velocity_error_fps.amax() < 0.01, "{late:?}");
    assert!(
        late.altitude_range_ft.1 - late.altitude_range_ft.0 < 0.05,
        "{late:?}"
    );
}

/// (b) The seed's target velocity profile (docs/equations.md, The relative motion and the
/// seed's scenario; Fig 7.2) commanded for 140 s from the
/// 50 ft/s trim heading north: the aircraft's velocity follows it, every surface stays inside
/// its limits, the sideslip stays small and the airspeed inside 30-70 ft/s (Fig 7.5-7.6).
///
/// Bands (measured values in the test output):
/// - north and east RMS < 0.6 ft/s (measured 0.33, 0.43): the attitude prefilters follow
///   ramps without lag; what is left is their response to the profile's curvature.
/// - down RMS < 2.5 ft/s (measured 0.53): the profile climbs at 6 ft/s while slowing to
///   40 ft/s, which needs m g sin γ + D ≈ 4.9 lbf against 6.6 lbf of full thrust at that speed
///   (T ∝ V²). Where the flight-path limit still holds the climb (thrust margin), the
///   follower climbs less; with those stretches set aside the down RMS is < 0.6 ft/s
///   (measured 0.17).
/// - |β| < 5° and no surface clamped (the criteria; measured 0.5°, 13°, 1.9°, 2.9°).
/// - airspeed in [30, 70] ft/s (the band; measured 35.1-60.4).
/// - |α| after 5 s: the issue asks for < 5°, which this airframe cannot meet: level flight at
///   the profile's lowest speed, 35.4 ft/s, needs α ≈ 12° (Aerosonde lift curve with the
///   seed's mass and wing). The test bounds α by that trim α + 2° (the turn's 1/cos φ and the
///   transients), well short of the stall blend at 27°.
#[test]
fn seed_target_profile_is_followed() {
    let target = seed_target();
    let started = std::time::Instant::now();
    let flight = fly(
        &AutopilotSection::default(),
        TurbulenceLevel::Off,
        140.0,
        |t| target.velocity_ned_fps(t),
    );
    println!("140 s at dt = 5 ms: wall time {:?}", started.elapsed());
    let st = report("seed profile, calm air", &flight, 5.0);
    let alpha_bound = common::trim_alpha_deg(PROFILE_MIN_SPEED_FPS) + 2.0;
    println!("α bound: trim α at {PROFILE_MIN_SPEED_FPS} ft/s + 2° = {alpha_bound:.2}°");
    assert!(st.rms_velocity_error_fps.x < 0.6, "{st:?}");
    assert!(st.rms_velocity_error_fps.y < 0.6, "{st:?}");
    assert!(st.rms_velocity_error_fps.z < 2.5, "{st:?}");
    assert!(vertical_rms_unlimited(&flight, 5.0) < 0.6);
    assert!(!st.any_saturation, "{st:?}");
    assert!(st.max_abs_beta_deg < 5.0, "{st:?}");
    assert!(st.max_abs_alpha_deg < alpha_bound, "{st:?}");
    assert!(
        st.airspeed_range_fps.0 > 30.0 && st.airspeed_range_fps.1 < 70.0,
        "{st:?}"
    );
}

/// (c) The same run in light Dryden turbulence (MIL-F-8785C, W20 = 15 kt; at 500 ft
/// σ_u = σ_v ≈ 3.1 ft/s, σ_w ≈ 2.5 ft/s), three random streams: no surface clamped, |β| < 5°,
/// airspeed in [30, 70] ft/s. α: the vertical gusts alone move it by σ_w/V ≈ 4° at the
/// profile's slowest, so the bound is 22°, 5° short of the stall blend's centre (27°).
/// Velocity RMS: north and east < 1.5 ft/s (half a gust σ; measured 0.77-1.10: the wind
/// estimate takes out the slow part of the gusts, L_u/V ≈ 20 s); down < 4 ft/s (measured
/// 1.08-1.44): a downdraft during the slow, thrust-limited climbs costs the whole climb, so
/// outside the limited stretches the bound is 2 ft/s (measured 1.03-1.15). Every RBF weight
/// vector stays inside its projection bound Ω_1.
#[test]
fn seed_target_profile_in_light_turbulence() {
    let target = seed_target();
    let config = AtmosphereConfig {
        turbulence: TurbulenceLevel::Light,
        ..AtmosphereConfig::default()
    };
    for seed in [7, 8, 9] {
        let flight = fly_in(&AutopilotSection::default(), &config, seed, 140.0, |t| {
            target.velocity_ned_fps(t)
        });
        let st = report(
            &format!("seed profile, light turbulence {seed}"),
            &flight,
            5.0,
        );
        assert!(st.rms_velocity_error_fps.x < 1.5, "{st:?}");
        assert!(st.rms_velocity_error_fps.y < 1.5, "{st:?}");
        assert!(st.rms_velocity_error_fps.z < 4.0, "{st:?}");
        assert!(vertical_rms_unlimited(&flight, 5.0) < 2.0);
        assert!(!st.any_saturation, "{st:?}");
        assert!(st.max_abs_beta_deg < 5.0, "{st:?}");
        assert!(st.max_abs_alpha_deg < 22.0, "{st:?}");
        assert!(
            st.airspeed_range_fps.0 > 30.0 && st.airspeed_range_fps.1 < 70.0,
            "{st:?}"
        );
        let worst_weight = flight
            .samples
            .iter()
            .map(|s| s.drag_weight_norm.max(s.moment_weight_norm_max))
            .fold(0.0, f64::max);
        assert!(worst_weight <= flight.drag_bound.max(flight.moment_bound) + 1e-9);
    }
}

/// (e) No wind-up: 120 ft/s commanded for 10 s (the throttle stays clamped at full while the
/// aircraft accelerates, then at idle when the command drops back) and then 50 ft/s again.
/// With the freeze rule the drag network does not move while the throttle is clamped
/// (‖Ŵ_D‖ < 0.05) and the aircraft is back within 0.1 ft/s of 50 ft/s after 35 s, having
/// held its height within 5 ft; without it, ‖Ŵ_D‖ runs to the projection bound within the
/// first second (the rule matters), and the projection still keeps it inside Ω_1.
#[test]
fn unreachable_speed_saturates_throttle_without_wind_up() {
    let command = |t: f64| {
        if (2.0..12.0).contains(&t) {
            Vec3::new(120.0, 0.0, 0.0)
        } else {
            Vec3::new(50.0, 0.0, 0.0)
        }
    };
    for freeze in [true, false] {
        let section = AutopilotSection {
            freeze_adaptation_on_saturation: freeze,
            // The default top speed (65 ft/s) would make the command reachable.
            max_airspeed_cmd_fps: 200.0,
            ..AutopilotSection::default()
        };
        let flight = fly(&section, TurbulenceLevel::Off, 60.0, command);
        let st = report(&format!("120 ft/s for 10 s, freeze {freeze}"), &flight, 0.0);
        let clamped_s = flight
            .samples
            .iter()
            .filter(|s| s.out.saturation.throttle)
            .count() as f64
            * 10.0
            * DT_S;
        let max_drag_weight = flight
            .samples
            .iter()
            .map(|s| s.drag_weight_norm)
            .fold(0.0, f64::max);
        let max_moment_weight = flight
            .samples
            .iter()
            .map(|s| s.moment_weight_norm_max)
            .fold(0.0, f64::max);
        println!(
            "  throttle clamped {clamped_s:.1} s, max ‖Ŵ_D‖ = {max_drag_weight:.3} (Ω_1: {:.3}), max ‖Ŵ_moment‖ = {max_moment_weight:.3}",
            flight.drag_bound
        );
        assert!(clamped_s > 3.0, "the command must saturate the throttle");
        assert!(max_drag_weight <= flight.drag_bound + 1e-9);
        assert!(max_moment_weight <= flight.moment_bound + 1e-9);
        assert!(!st.any_saturation || !freeze, "{st:?}");
        if freeze {
            let during = flight
                .samples
                .iter()
                .filter(|s| s.t_s < 12.0)
                .map(|s| s.drag_weight_norm)
                .fold(0.0, f64::max);
            assert!(during < 0.05, "‖Ŵ_D‖ = {during} while clamped");
            let late = stats(&flight, 35.0);
            assert!(
                late.airspeed_range_fps.0 > 49.9 && late.airspeed_range_fps.1 < 50.1,
                "{late:?}"
            );
            assert!(st.altitude_range_ft.0 > -5.0 && st.altitude_range_ft.1 < 5.0);
        } else {
            assert!(max_drag_weight > 0.9 * flight.drag_bound);
        }
    }
}

/// The course is unwrapped: a command circling at 0.1 rad/s passes χ = ±180° twice in 80 s;
/// the heading reference must go on turning (no 360° turn back, no jump in ψ̇_c: it stays
/// near 0.1 rad/s, below 0.15), and the velocity follows the circle (RMS < 0.5 ft/s per
/// horizontal axis after the entry, measured ≈ 0.3).
#[test]
fn course_through_south_is_unwrapped() {
    let rate = 0.1;
    let flight = fly(
        &AutopilotSection::default(),
        TurbulenceLevel::Off,
        80.0,
        move |t| {
            let a = rate * (t - 2.0).max(0.0);
            50.0 * Vec3::new(a.cos(), a.sin(), 0.0)
        },
    );
    let st = report("circle at 0.1 rad/s", &flight, 20.0);
    let last = flight.samples.last().expect("samples");
    // ψ_c continuous: 78 s of turning at 0.1 rad/s is 7.8 rad (447°).
    assert!(
        (last.out.euler_cmd.psi_rad - 7.8).abs() < 0.1,
        "{}",
        last.out.euler_cmd.psi_rad
    );
    let max_rate = flight
        .samples
        .iter()
        .map(|s| s.out.euler_rate_cmd_rps.z.abs())
        .fold(0.0, f64::max);
    assert!(max_rate < 0.15, "ψ̇_c up to {max_rate}");
    assert!(
        st.rms_velocity_error_fps.x < 0.5 && st.rms_velocity_error_fps.y < 0.5,
        "{st:?}"
    );
    assert!(!st.any_saturation);
}

/// The RBF networks learn unmodelled drag and moments (Δ of (7.17)-(7.18): drag × 1.5 and
/// moment biases of 0.2, 0.5, 0.1 lbf ft, applied to the plant only). With adaptation the
/// speed and attitude errors vanish (< 1e-3 after 60 s) and the corrections match the
/// perturbations (Ŵ_DᵀΦ ≈ ΔD/m within 3 %, ŴᵀΦ ≈ J⁻¹Δ within 2 %); without it the same
/// perturbations leave steady errors of degrees (backstepping without adaptation has no
/// integral action: e_θ = J⁻¹ΔM / (k_q k_θ + 1) ≈ 7.8° here). This is the check on the sign of (7.23) (module
/// docs of `control::adaptation`): with the seed's printed sign the drag estimate would run
/// away from the drag instead.
#[test]
fn unmodelled_drag_and_moments_are_learned() {
    let disturbances = DisturbanceConfig {
        drag_factor: 1.5,
        moment_bias_lbf_ft: [0.2, 0.5, 0.1],
    };
    let config = AtmosphereConfig {
        disturbances: disturbances.clone(),
        ..AtmosphereConfig::default()
    };
    let params = AircraftParams::seed_follower().expect("built-in aircraft");
    let inertia = params.mass.inertia_slug_ft2();
    let expected_moment =
        inertia.try_inverse().expect("invertible") * Vec3::from(disturbances.moment_bias_lbf_ft);
    // ΔD/m = 0.5 D/m with the drag of the undisturbed 50 ft/s trim (D = T cos α there).
    let trim = trim_level_flight(
        &Aircraft::new(params.clone()).expect("valid aircraft"),
        &TrimRequest {
            airspeed_fps: 50.0,
            position_ned_ft: Vec3::zeros(),
            heading_rad: 0.0,
            air: AtmosphereSample::default(),
        },
    )
    .expect("trims");
    let trim_drag_lbf = trim.controls.throttle
        * params
            .control_effectiveness(0.5 * SEA_LEVEL_DENSITY_SLUG_FT3 * 2500.0)
            .thrust_per_throttle_lbf
        * trim.alpha_rad.cos();
    let expected_drag_per_mass = 0.5 * trim_drag_lbf / params.mass.mass_slug;
    for rbf in [true, false] {
        let section = AutopilotSection {
            rbf_enabled: rbf,
            ..AutopilotSection::default()
        };
        let flight = fly_in(&section, &config, 1, 90.0, |_| Vec3::new(50.0, 0.0, 0.0));
        report(&format!("Δ drag and moments, RBF {rbf}"), &flight, 60.0);
        let late: Vec<&Sample> = flight.samples.iter().filter(|s| s.t_s > 60.0).collect();
        let speed_error = late
            .iter()
            .map(|s| s.out.airspeed_error_fps.abs())
            .fold(0.0, f64::max);
        let attitude_error = late
            .iter()
            .map(|s| s.out.euler_error_rad.norm())
            .fold(0.0, f64::max);
        println!("  max |e_V| = {speed_error:.2e} ft/s, max ‖e_E‖ = {attitude_error:.2e} rad");
        if rbf {
            assert!(speed_error < 1e-3 && attitude_error < 1e-3);
            let last = late.last().expect("samples");
            assert!(
                (last.out.drag_correction_fps2 - expected_drag_per_mass).abs()
                    < 0.03 * expected_drag_per_mass,
                "{} vs {expected_drag_per_mass}",
                last.out.drag_correction_fps2
            );
            let correction = last.out.moment_correction_rps2;
            assert!(
                (correction - expected_moment).norm() < 0.02 * expected_moment.norm(),
                "{correction:?} vs {expected_moment:?}"
            );
        } else {
            assert!(speed_error > 1.0 || attitude_error > 0.02);
        }
    }
}

/// Mean of `f` over the samples in [from_s, to_s).
fn mean_over(flight: &Flight, from_s: f64, to_s: f64, f: impl Fn(&Sample) -> f64) -> f64 {
    let values: Vec<f64> = flight
        .samples
        .iter()
        .filter(|s| (from_s..to_s).contains(&s.t_s))
        .map(f)
        .collect();
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

/// A descent steeper than the idle glide (40 ft/s north while sinking 25 ft/s): the descent
/// limit holds γ_c near -9°. With the seed's V_c = ‖V_F‖ (47 ft/s) the aircraft turns the
/// vertical speed it cannot fly into horizontal speed (measured 47.05 ft/s north); with
/// `limited_descent_keeps_horizontal_speed` it flies the commanded 40 ft/s over the ground
/// (measured 40.15), so a follower held high does not overtake its target. Means over 10-30 s;
/// bands of 1.5 ft/s lie between the two by far.
#[test]
fn a_limited_descent_keeps_the_horizontal_speed() {
    let command = Vec3::new(40.0, 0.0, 25.0);
    for keeps in [false, true] {
        let section = AutopilotSection {
            limited_descent_keeps_horizontal_speed: keeps,
            descent_waits_for_speed: keeps,
            ..AutopilotSection::default()
        };
        let flight = fly(&section, TurbulenceLevel::Off, 30.0, move |_| command);
        report(
            &format!("descent beyond the limit, keeps {keeps}"),
            &flight,
            10.0,
        );
        let north = mean_over(&flight, 10.0, 30.0, |s| s.velocity_ned_fps.x);
        let limited = mean_over(&flight, 10.0, 30.0, |s| {
            f64::from(u8::from(s.out.flight_path_limited))
        });
        println!(
            "  mean north speed {north:.2} ft/s, limited {:.0} % of the time",
            100.0 * limited
        );
        assert!(limited > 0.9, "the descent must be limited");
        if keeps {
            assert!((north - 40.0).abs() < 1.5, "north {north}");
        } else {
            assert!(north > 40.0 + 1.5 + 1.5, "north {north}");
        }
    }
}

/// A command slower than the aircraft can fly (25 ft/s north, below the 35 ft/s floor): flown
/// straight the aircraft covers 35 ft/s of ground; with 8 s S-turns it flies legs either side
/// of north and covers less: the turns between legs, at the bank limit, take part of each leg
/// (what a run gives, and what the S-turns cost in height: docs/findings.md, Measurements
/// behind the code and tests). Bands: north below 31 ft/s with S-turns and above 34
/// straight; east within 3 ft/s.
#[test]
fn a_command_slower_than_the_aircraft_is_flown_as_s_turns() {
    let command = Vec3::new(25.0, 0.0, 0.0);
    for period_s in [0.0, 8.0] {
        let section = AutopilotSection {
            weave_period_s: period_s,
            ..AutopilotSection::default()
        };
        let flight = fly(&section, TurbulenceLevel::Off, 60.0, move |_| command);
        report(
            &format!("25 ft/s north, S-turns of {period_s} s"),
            &flight,
            10.0,
        );
        let north = mean_over(&flight, 10.0, 60.0, |s| s.velocity_ned_fps.x);
        let east = mean_over(&flight, 10.0, 60.0, |s| s.velocity_ned_fps.y);
        let down = mean_over(&flight, 10.0, 60.0, |s| s.velocity_ned_fps.z);
        println!("  mean velocity [{north:.2}, {east:.2}, {down:.2}] ft/s");
        assert!(east.abs() < 3.0, "east {east}");
        if period_s > 0.0 {
            assert!(north < 31.0, "north {north}");
        } else {
            assert!(north > 34.0, "north {north}");
        }
    }
}

/// The same descent from the 50 ft/s trim, the horizontal speed kept (V_c ≈ 40 ft/s): with
/// `descent_waits_for_speed` the steepest descent keeps the deceleration the airspeed law asks
/// for, so the 10 ft/s of excess speed go sooner (measured at 8 s: 43.1 against 44.2 ft/s;
/// both reach 40.1 by 20 s). The limit's deceleration demand is the one of the command's
/// norm (its prefilter rate), not of the horizontal speed flown, so the effect is this small.
/// Band: at least 0.5 ft/s slower at 8 s, and the same speed (within 0.2 ft/s) at 20 s.
#[test]
fn a_descent_waits_to_shed_speed() {
    let command = Vec3::new(40.0, 0.0, 25.0);
    let airspeed_at = |waits: bool, t_s: f64| {
        let section = AutopilotSection {
            limited_descent_keeps_horizontal_speed: true,
            descent_waits_for_speed: waits,
            ..AutopilotSection::default()
        };
        let flight = fly(&section, TurbulenceLevel::Off, 20.0, move |_| command);
        mean_over(&flight, t_s - 0.05, t_s + 0.05, |s| s.airspeed_fps)
    };
    let (steady_8, waiting_8) = (airspeed_at(false, 8.0), airspeed_at(true, 8.0));
    let (steady_20, waiting_20) = (airspeed_at(false, 19.9), airspeed_at(true, 19.9));
    println!(
        "airspeed at 8 s: {steady_8:.2} steady, {waiting_8:.2} waiting; at 20 s: {steady_20:.2}, {waiting_20:.2}"
    );
    assert!(waiting_8 < steady_8 - 0.5, "{waiting_8} against {steady_8}");
    assert!(
        (waiting_20 - steady_20).abs() < 0.2,
        "{waiting_20} against {steady_20}"
    );
}
