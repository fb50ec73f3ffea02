//! The 6-DOF follower flown by its flight controller alone, without guidance: plant plus
//! autopilot integrated together by the simulation's RK4 from the 50 ft/s trim heading north
//! at the origin, in the air an [`AtmosphereConfig`] describes.

use wingman::control::{Autopilot, AutopilotInput, AutopilotOutput, weave_side};
use wingman::frames::Vec3;
use wingman::integrate::Rk4;
use wingman::scenario::AutopilotSection;
use wingman::world::aircraft::{
    Aircraft, AircraftParams, AircraftState, STATE_LEN, TrimRequest, trim_level_flight,
};
use wingman::world::atmosphere::{Atmosphere, AtmosphereConfig, AtmosphereSample};

/// One logged instant of a flight.
#[derive(Debug, Clone, Copy)]
pub struct FlightSample {
    /// Time, s.
    pub t_s: f64,
    /// Airspeed, ft/s.
    pub airspeed_fps: f64,
    /// Height above the start, ft.
    pub height_ft: f64,
    /// Inertial velocity, NED, ft/s.
    pub velocity_ned_fps: Vec3,
    /// The throttle channel's position (negative: speed brake).
    pub throttle: f64,
    /// The controller's output at the instant.
    pub out: AutopilotOutput,
}

/// Flies the aircraft `params` for `duration_s` at step `dt_s` from the 50 ft/s trim heading north, commanded with
/// `command(t, R_F)` (R_F the aircraft's NED position, ft), and logs every tenth step.
pub fn fly(
    params: &AircraftParams,
    section: &AutopilotSection,
    config: &AtmosphereConfig,
    dt_s: f64,
    duration_s: f64,
    command: impl Fn(f64, &Vec3) -> Vec3,
) -> Vec<FlightSample> {
    let aircraft = Aircraft::new(params.clone()).expect("valid aircraft");
    let autopilot = Autopilot::new(params, section).expect("valid autopilot");
    let mut atmosphere = Atmosphere::new(config, 7).expect("valid atmosphere");
    let start = Vec3::zeros();
    let trim_air = AtmosphereSample {
        drag_factor: 1.0,
        moment_bias_body_lbf_ft: Vec3::zeros(),
        ..atmosphere.steady_sample(&start)
    };
    let request = TrimRequest {
        airspeed_fps: 50.0,
        position_ned_ft: start,
        heading_rad: 0.0,
        air: trim_air,
    };
    let trim = trim_level_flight(&aircraft, &request).expect("trims at 50 ft/s");
    let mut x = trim.state.pack().to_vec();
    let data0 = aircraft
        .air_data(&x, &atmosphere.steady_sample(&start))
        .expect("valid state");
    x.extend(autopilot.initial_state(&data0));
    let mut rk = Rk4::new(x.len());
    let mut scratch = vec![0.0; autopilot.state_len()];
    let mut samples = Vec::new();
    let ticks = (duration_s / dt_s).round() as usize;
    for tick in 0..ticks {
        let t_s = tick as f64 * dt_s;
        let state = AircraftState::unpack(&x).expect("valid state");
        let position = state.position_ned_ft;
        let airspeed = aircraft
            .air_data(&x, &atmosphere.steady_sample(&position))
            .expect("valid")
            .airspeed_fps;
        let air = atmosphere.sample(dt_s, &position, airspeed);
        let input_at = |t: f64, plant: &[f64]| {
            let data = aircraft.air_data(plant, &air)?;
            let state = AircraftState::unpack(plant)?;
            Some(AutopilotInput {
                velocity_cmd_ned_fps: command(t, &state.position_ned_ft),
                air_data: data,
                sensed_air_data: data,
                actuators: state.actuators,
                weave_side: weave_side(t_s, section.weave_period_s),
                slot_line: None,
            })
        };
        if tick % 10 == 0 {
            let input = input_at(t_s, &x).expect("valid state");
            samples.push(FlightSample {
                t_s,
                airspeed_fps: input.air_data.airspeed_fps,
                height_ft: -position.z,
                velocity_ned_fps: input.air_data.velocity_ned_fps,
                throttle: state.actuators.throttle,
                out: autopilot.derivative(&x[STATE_LEN..], &input, &mut scratch),
            });
        }
        rk.step(t_s, dt_s, &mut x, |t, x, dx| {
            let (plant, ctrl) = x.split_at(STATE_LEN);
            let (dplant, dctrl) = dx.split_at_mut(STATE_LEN);
            let Some(input) = input_at(t, plant) else {
                dx.fill(0.0);
                return;
            };
            let out = autopilot.derivative(ctrl, &input, dctrl);
            aircraft.derivative(plant, &out.controls, &air, dplant);
        });
        aircraft.normalize(&mut x);
        autopilot.enforce_bounds(&mut x[STATE_LEN..]);
        assert!(x.iter().all(|v| v.is_finite()), "state diverged at {t_s} s");
    }
    samples
}

/// The aircraft's answer G(T) to a sinusoid in its velocity command, as (re, im): flown in
/// calm air at 45 ft/s north at the platoon's 1/300 s step, the command's component along the
/// unit vector `axis` 4 ft/s sin(2πt/T); the Fourier component of the velocity along `axis`
/// over four periods after 30 s (the transient over), against the command's sin.
pub fn sinusoid_answer(section: &AutopilotSection, period_s: f64, axis: Vec3) -> (f64, f64) {
    const SPEED_FPS: f64 = 45.0;
    const SWING_FPS: f64 = 4.0;
    const SETTLED_S: f64 = 30.0;
    let params = AircraftParams::seed_follower().expect("built-in aircraft");
    let omega = 2.0 * std::f64::consts::PI / period_s;
    let flight = fly(
        &params,
        section,
        &AtmosphereConfig::default(),
        1.0 / 300.0,
        SETTLED_S + 4.0 * period_s,
        |t, _| Vec3::new(SPEED_FPS, 0.0, 0.0) + axis * (SWING_FPS * (omega * t).sin()),
    );
    let read: Vec<_> = flight.iter().filter(|s| s.t_s >= SETTLED_S).collect();
    let (sin_part, cos_part) = read.iter().fold((0.0, 0.0), |(a, b), s| {
        let v = s.velocity_ned_fps.dot(&axis);
        (a + v * (omega * s.t_s).sin(), b + v * (omega * s.t_s).cos())
    });
    let scale = 2.0 / read.len() as f64 / SWING_FPS;
    (sin_part * scale, cos_part * scale)
}
