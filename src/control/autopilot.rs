//! The follower's flight controller (seed 7.3, (7.20)-(7.33); docs/equations.md, The 6-DOF
//! follower (Chapter 7)): airspeed law with an RBF drag correction, block backstepping from
//! Euler angles to body rates to moments with RBF moment corrections, inversion of (7.19) for
//! the surfaces, saturation and anti-wind-up.
//!
//! One call of [`Autopilot::derivative`], in the order the data flows (each step is explained
//! in its module):
//! 0. The nominal model at this instant: q̄, the controls' effectiveness, the nominal
//!    aerodynamics and the networks' corrections (`nominal_model`).
//! 1. V_F → V_c, γ_c, χ_c (7.1)-(7.3) on the air-relative command V_F - ŵ (`wind`), with the
//!    flight-path limits, the airspeed limits and the S-turns (`velocity_command`); or, with
//!    `outer_loop = "energy"`, the total-energy loop's thrust and γ_c (`energy`).
//! 2. Raw attitude references (Remark 9) and 3. their prefilters (Remark 10) and the α
//!    envelope (`attitude`).
//! 4. (7.24) body-rate commands, 5. their command filter and 6. the moment command (7.25)
//!    (`rate_loop`).
//! 7. (7.19) inverted for the surfaces, (7.20) for the throttle, each command clamped to its
//!    limit (`inversion`).
//! 8. Adaptation (7.23), (7.28) with ball projection and anti-wind-up (`adaptation`).
//!
//! The state's layout is [`AutopilotState`]'s; the design data the steps read is built once
//! (`control_law`).

use super::control_law::ControlLaw;
use super::prefilter::{IntegralPrefilter, SecondOrderFilter, SmoothIntegralPrefilter};
use super::signals::{AutopilotInput, AutopilotOutput};
use super::state::{AUTOPILOT_STATE_LEN, AutopilotState};
use super::wind::measured_wind_ned_fps;
use crate::frames::Vec3;
use crate::scenario::check::InvalidValue;
use crate::scenario::{AutopilotSection, OuterLoop};
use crate::world::aircraft::{AirData, AircraftParams};

/// The Chapter 7 controller for one aircraft (its nominal model and the gains).
#[derive(Debug, Clone)]
pub struct Autopilot {
    law: ControlLaw,
}

impl Autopilot {
    /// A controller for the aircraft `params` (its nominal model) with the gains of `section`.
    /// Fails on an invalid section or aircraft, or when aileron and rudder cannot be solved for
    /// separately (the lateral block of (7.19) is singular).
    pub fn new(params: &AircraftParams, section: &AutopilotSection) -> Result<Self, InvalidValue> {
        Ok(Self {
            law: ControlLaw::new(params, section)?,
        })
    }

    /// Length of the controller's state slice ([`AUTOPILOT_STATE_LEN`]).
    pub fn state_len(&self) -> usize {
        AUTOPILOT_STATE_LEN
    }

    /// Initial state for an aircraft in the flight condition `air_data` (e.g. a trim): every
    /// filter at rest on the present airspeed, attitude and rates, so that the first commands
    /// reproduce the present state; weights zero.
    pub fn initial_state(&self, air_data: &AirData) -> Vec<f64> {
        let euler = &air_data.euler;
        let wind = measured_wind_ned_fps(air_data);
        let state = AutopilotState {
            airspeed_filter: IntegralPrefilter::initial_state(air_data.airspeed_fps),
            roll_filter: SmoothIntegralPrefilter::initial_state(euler.phi_rad),
            pitch_filter: SmoothIntegralPrefilter::initial_state(euler.theta_rad),
            heading_filter: SmoothIntegralPrefilter::initial_state(euler.psi_rad),
            rate_filter: [0, 1, 2]
                .map(|axis| SecondOrderFilter::initial_state(air_data.body_rates_rps[axis])),
            wind_estimate_ned_fps: if wind.iter().all(|w| w.is_finite()) {
                wind
            } else {
                Vec3::zeros()
            },
            ..AutopilotState::zero()
        };
        let mut x = vec![0.0; AUTOPILOT_STATE_LEN];
        state.pack(&mut x);
        x
    }

    /// Ω_1 of the drag network's projection: ‖Ŵ_D‖ ≤ this.
    pub fn drag_weight_outer_bound(&self) -> f64 {
        (self.law.drag_bound.max_norm.powi(2) + self.law.drag_bound.epsilon).sqrt()
    }

    /// Ω_1 of the moment networks' projection: ‖Ŵ_i‖ ≤ this.
    pub fn moment_weight_outer_bound(&self) -> f64 {
        (self.law.moment_bound.max_norm.powi(2) + self.law.moment_bound.epsilon).sqrt()
    }

    /// Pulls every weight vector back into Ω_1 after an integration step (see
    /// [`crate::projection`]).
    pub fn enforce_bounds(&self, x: &mut [f64]) {
        let mut state = AutopilotState::unpack(x);
        for (k, w) in state.weights.iter_mut().enumerate() {
            self.law.weight_bound(k).clamp_slice(w);
        }
        state.pack(x);
    }

    /// Writes ẋ of the controller's state into `dx` and returns the actuator commands with
    /// telemetry. `x` and `dx` must hold [`Self::state_len`] values. The steps are those of
    /// the module docs.
    pub fn derivative(&self, x: &[f64], input: &AutopilotInput, dx: &mut [f64]) -> AutopilotOutput {
        let law = &self.law;
        let state = AutopilotState::unpack(x);
        let mut rates = AutopilotState::zero();
        let model = law.nominal_model(&state, input);
        let velocity = match law.gains.outer_loop {
            OuterLoop::Chapter7 => law.velocity_references(&state, input, &model, &mut rates),
            OuterLoop::Energy => law.energy_references(&state, input, &model, &mut rates),
        };
        let attitude = law.attitude_references(&state, input, &model, &velocity, &mut rates);
        let rate_loop = law.rate_commands(&state, &input.air_data, &attitude, &mut rates);
        let moment_cmd = law.moment_command(&input.air_data, &model, &attitude, &rate_loop);
        let (unclamped, thrust_cmd) = law.inverted_commands(input, &model, &velocity, &moment_cmd);
        let (controls, saturation) = law.clamp(&unclamped, &input.actuators);
        rates.weights = law.adaptation_rates(
            &state,
            &model.phi,
            velocity.airspeed_error_fps,
            &rate_loop.error_rps,
            &saturation,
        );
        rates.pack(dx);
        AutopilotOutput {
            controls,
            unclamped,
            saturation,
            airspeed_cmd_fps: velocity.airspeed_cmd_fps,
            airspeed_ref_fps: velocity.airspeed_ref.value,
            airspeed_error_fps: velocity.airspeed_error_fps,
            flight_path_cmd_rad: velocity.flight_path_cmd_rad,
            flight_path_limited: velocity.flight_path_limited,
            euler_cmd: attitude.euler_cmd,
            euler_rate_cmd_rps: attitude.euler_rate_cmd_rps,
            euler_error_rad: attitude.euler_error_rad,
            rate_cmd_rps: rate_loop.command_rps,
            rate_cmd_filtered_rps: rate_loop.filtered_rps,
            rate_error_rps: rate_loop.error_rps,
            thrust_cmd_lbf: thrust_cmd,
            moment_cmd_lbf_ft: moment_cmd,
            drag_correction_fps2: model.drag_correction_fps2,
            moment_correction_rps2: model.moment_correction_rps2,
        }
    }
}
