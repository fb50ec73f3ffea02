//! The follower's flight controller (seed 7.3, (7.20)-(7.33); SPEC §7): airspeed law with an
//! RBF drag correction, block backstepping from Euler angles to body rates to moments with RBF
//! moment corrections, inversion of (7.19) for the surfaces, saturation and anti-wind-up.
//!
//! One call of [`Autopilot::derivative`], in the order the data flows:
//! 1. V_F → V_c, γ_c, χ_c (7.1)-(7.3); γ_c is kept between the steepest descent and climb
//!    the thrust range allows at steady speed ([`super::reference::limit_flight_path`]; a
//!    commanded speed change does not bend the path: with the speed reference's rate V̇_m in
//!    the limits, a follower slowing at idle was held level or climbing while told to descend,
//!    and the camera lost the target below the frame (measured); now the slowing waits).
//!    With `wind_compensation`, (7.1)-(7.3) are applied to the air-relative command V_F - ŵ,
//!    ŵ a low-passed measurement of the wind (inertial minus air-relative velocity, from the
//!    air data and the attitude): the seed's V_c = ‖V_F‖ assumes still air, and in wind (or
//!    slow turbulence) it would fly the right airspeed and heading but the wrong inertial
//!    velocity. γ in (7.20) is the air-relative flight path, as in (7.15). V_c is kept within
//!    [`min_airspeed_cmd_fps`, `max_airspeed_cmd_fps`]: a margin above the stall speed, and a
//!    top speed the seed's thrust model T ∝ V² lacks (its excess thrust at full throttle grows
//!    with V², so an unbounded command, e.g. from a guidance law closing a gap, would
//!    accelerate the aircraft without end).
//! 2. Raw attitude references (Remark 9): ψ_c = χ_c (unwrapped against the filter state, so
//!    it never jumps by 2π); θ_c = γ_c + α_ref cos φ, α_ref from the nominal lift curve
//!    ((7.8)-(7.9) with β = 0; the seed's θ_c = γ_c would leave the aircraft flying its trim α,
//!    4.5°, below the commanded path, i.e. sinking at 4 ft/s when told to fly level);
//!    φ_c = atan(ψ̇_d V_m / g) (7.14) for the heading rate that (7.24) demands,
//!    ψ̇_d = ψ̇_m - k_ψ e_ψ, e_ψ = ψ - ψ_m, limited to the turn rate of the bank limit (the
//!    *filtered* heading rate ψ̇_m, not the raw command's; with ψ̇_m alone, as in (7.14), a
//!    heading error the reference has run ahead of is flown on the rudder, skidding).
//! 3. Prefilters (Remark 10): V_c goes through the seed's (7.33), φ_c, θ_c, ψ_c through (7.33)
//!    with one more integrator ([`SmoothIntegralPrefilter`]: the rate it hands to (7.24) is a
//!    state, continuous even when the command jumps). Each gives the filtered reference and
//!    its exact derivative, and follows ramps (a steady turn, a steady speed change) without
//!    lag.
//!    θ_c is then held inside γ + [α_min, α_max] cos φ (an α envelope: pitch tracking by model
//!    inversion would otherwise hold the aircraft in a stall once it got there).
//! 4. (7.24): [p_c, q_c, r_c] = H [-k_φ e_φ + φ̇_m, -k_θ e_θ + θ̇_m, -k_ψ e_ψ + ψ̇_m], H = P⁻¹,
//!    the heading-rate demand clamped to the rate of a coordinated turn at the bank limit,
//!    g tan φ_max / V (a large heading step is then flown as a banked turn, not a skid).
//! 5. Command filter (dynamic surface / command-filtered backstepping): a second-order filter
//!    per axis gives ω_f and ω̇_f; e_ω = ω - ω_f and ṗ_c, q̇_c, ṙ_c = ω̇_f in (7.25). This
//!    avoids differentiating H, the Euler errors and the references analytically.
//! 6. (7.25): [L, M, N]_cmd = ω × Jω - J Pᵀ e_E - J Ŵᵀ Φ + J [-k_p e_p + ṗ_c, ...]. Pᵀ (not the
//!    seed's printed P) cancels the cross term of (7.27) (SPEC §7).
//! 7. (7.19) inverted: [δa, δe, δr] = B(q̄)⁻¹ ([L, M, N]_cmd - M_0), M_0 the nominal moments at
//!    zero deflection; (7.20) T → δT = T / (q̄ S C_TδT). Each command is clamped to its limit.
//! 8. Adaptation (7.23), (7.28) with ball projection; a network stops adapting while the
//!    actuator it acts through is clamped (anti-wind-up, see `adaptation_rates`).
//!
//! Sign of (7.23): the thrust law adds + m Ŵ_DᵀΦ (Ŵ_DᵀΦ estimates ΔD/m, (7.18)), so with
//! W̃ = Ŵ - W the speed error obeys ė_V = -k_V e_V + W̃_DᵀΦ - ε_D and V̇₁ ≤ -k_V e_V² needs
//! Ŵ_D' = G_D Proj(Ŵ_D, **-** e_V Φ). The seed prints ė_V = ... - W̃ᵀΦ and
//! Ŵ_D' = G_D Proj(Ŵ_D, e_V Φ), which would make the drag estimate run away from the true
//! drag; the moment laws (7.28) are consistent as printed (J⁻¹Δ enters (7.25) with a minus).
//!
//! State layout (offsets in the controller's slice, [`Autopilot::state_len`] values):
//! ```text
//! 0  V_I, V_m                        airspeed prefilter (7.33)
//! 2  φ_I, φ_m, φ̇_m                   roll prefilter
//! 5  θ_I, θ_m, θ̇_m                   pitch prefilter
//! 8  ψ_I, ψ_m, ψ̇_m                   heading prefilter (ψ_m continuous, not wrapped)
//! 11 p_f, ṗ_f, q_f, q̇_f, r_f, ṙ_f     rate command filter
//! 17 ŵ_N, ŵ_E, ŵ_D                   wind estimate, ft/s
//! 20 Ŵ_D, Ŵ_l, Ŵ_m, Ŵ_n              RBF weights, RBF_CENTRES each
//! ```

use crate::frames::{
    EulerAngles, GRAVITY_FPS2, Mat3, SEA_LEVEL_DENSITY_SLUG_FT3, Vec3, wrap_angle_rad,
};
use crate::guidance::projection::BallBound;
use crate::scenario::AutopilotSection;
use crate::scenario::check::{InvalidValue, require};
use crate::world::aircraft::actuators::ActuatorLimits;
use crate::world::aircraft::{AirAngles, AirData, AircraftParams, Controls};

use super::prefilter::{
    FilteredCommand, IntegralPrefilter, SecondOrderFilter, SmoothIntegralPrefilter,
};
use super::rbf::{RBF_CENTRES, RbfBasis, RbfInput, clamp_ball, project_ball};
use super::reference::{
    AlphaReferenceInput, VelocityReference, alpha_reference_rad, coordinated_turn_bank_rad,
    flight_path_for_thrust_rad, limit_flight_path, unwrap_near_rad,
};

/// Offset of the airspeed prefilter state `[V_I, V_m]`.
pub const AIRSPEED_FILTER: usize = 0;
/// Offset of the roll prefilter state `[φ_I, φ_m, φ̇_m]`.
pub const ROLL_FILTER: usize = 2;
/// Offset of the pitch prefilter state `[θ_I, θ_m, θ̇_m]`.
pub const PITCH_FILTER: usize = 5;
/// Offset of the heading prefilter state `[ψ_I, ψ_m, ψ̇_m]`.
pub const HEADING_FILTER: usize = 8;
/// Offset of the rate command filter `[p_f, ṗ_f, q_f, q̇_f, r_f, ṙ_f]`.
pub const RATE_FILTER: usize = 11;
/// Offset of the wind estimate ŵ (NED, ft/s).
pub const WIND_ESTIMATE: usize = 17;
/// Offset of the RBF weights `[Ŵ_D, Ŵ_l, Ŵ_m, Ŵ_n]`, [`RBF_CENTRES`] each.
pub const WEIGHTS: usize = 20;
/// Length of the controller's state.
pub const AUTOPILOT_STATE_LEN: usize = WEIGHTS + 4 * RBF_CENTRES;

/// Index of each network among the weights: drag, roll, pitch, yaw moment.
const DRAG: usize = 0;
const ROLL: usize = 1;
const PITCH: usize = 2;
const YAW: usize = 3;

/// What the controller reads at one instant besides its own state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutopilotInput {
    /// The guidance command V_F, NED, ft/s.
    pub velocity_cmd_ned_fps: Vec3,
    /// Air data of the follower (airspeed, α, β, attitude, rates, loads).
    pub air_data: AirData,
    /// Actuator positions (the plant's actuator states): RBF inputs u of (7.18) and the
    /// elevator's lift in α_ref.
    pub actuators: Controls,
}

/// Which actuator commands were clamped to their limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Saturation {
    /// δT command outside [0, 1].
    pub throttle: bool,
    /// δe command beyond its limit.
    pub elevator: bool,
    /// δa command beyond its limit.
    pub aileron: bool,
    /// δr command beyond its limit.
    pub rudder: bool,
}

/// The controller's output at one instant: actuator commands plus telemetry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutopilotOutput {
    /// Commands to the actuators, inside their limits.
    pub controls: Controls,
    /// The commands before clamping.
    pub unclamped: Controls,
    /// Which commands were clamped.
    pub saturation: Saturation,
    /// V_c (7.1) of the air-relative command V_F - ŵ (V_F in still air or without wind
    /// compensation), kept within [`min_airspeed_cmd_fps`, `max_airspeed_cmd_fps`], ft/s.
    pub airspeed_cmd_fps: f64,
    /// V_m, the prefiltered airspeed command (7.33), ft/s.
    pub airspeed_ref_fps: f64,
    /// e_V = V - V_m, ft/s.
    pub airspeed_error_fps: f64,
    /// γ_c (7.2) after the flight-path limits, rad.
    pub flight_path_cmd_rad: f64,
    /// Whether a flight-path limit changed γ_c.
    pub flight_path_limited: bool,
    /// φ_c, θ_c, ψ_c: the attitude the backstepping tracks (ψ_c continuous, not wrapped).
    pub euler_cmd: EulerAngles,
    /// φ̇_c, θ̇_c, ψ̇_c, rad/s.
    pub euler_rate_cmd_rps: Vec3,
    /// e_φ, e_θ, e_ψ (e_ψ wrapped into (-π, π]), rad.
    pub euler_error_rad: Vec3,
    /// [p_c, q_c, r_c] of (7.24), rad/s.
    pub rate_cmd_rps: Vec3,
    /// The command-filtered rates ω_f the rate loop tracks, rad/s.
    pub rate_cmd_filtered_rps: Vec3,
    /// e_p, e_q, e_r = ω - ω_f, rad/s.
    pub rate_error_rps: Vec3,
    /// Thrust of (7.20), lbf.
    pub thrust_cmd_lbf: f64,
    /// [L, M, N] of (7.25), lbf ft.
    pub moment_cmd_lbf_ft: Vec3,
    /// Ŵ_DᵀΦ, the drag correction ΔD/m, ft/s².
    pub drag_correction_fps2: f64,
    /// [Ŵ_lᵀΦ, Ŵ_mᵀΦ, Ŵ_nᵀΦ], the moment corrections J⁻¹Δ, rad/s².
    pub moment_correction_rps2: Vec3,
}

/// The Chapter 7 controller for one aircraft (its nominal model and the gains).
#[derive(Debug, Clone)]
pub struct Autopilot {
    params: AircraftParams,
    inertia_slug_ft2: Mat3,
    gains: AutopilotSection,
    airspeed_filter: IntegralPrefilter,
    roll_filter: SmoothIntegralPrefilter,
    pitch_filter: SmoothIntegralPrefilter,
    heading_filter: SmoothIntegralPrefilter,
    rate_filter: SecondOrderFilter,
    basis: RbfBasis,
    drag_bound: BallBound,
    moment_bound: BallBound,
}

impl Autopilot {
    /// A controller for the aircraft `params` (its nominal model) with the gains of `section`.
    /// Fails on an invalid section or aircraft, or when aileron and rudder cannot be solved for
    /// separately (the lateral block of (7.19) is singular).
    pub fn new(params: &AircraftParams, section: &AutopilotSection) -> Result<Self, InvalidValue> {
        section.validate()?;
        params.validate()?;
        let a = &params.aero;
        let lateral_det =
            a.c_roll_da_per_rad * a.c_yaw_dr_per_rad - a.c_roll_dr_per_rad * a.c_yaw_da_per_rad;
        require(
            lateral_det.abs() > 1e-9,
            "aero.c_roll_da_per_rad",
            a.c_roll_da_per_rad,
            "a value with C_lδa C_nδr - C_lδr C_nδa != 0 (aileron and rudder must be separable)",
        )?;
        Ok(Self {
            params: params.clone(),
            inertia_slug_ft2: params.mass.inertia_slug_ft2(),
            gains: section.clone(),
            airspeed_filter: IntegralPrefilter {
                omega_rps: section.airspeed_prefilter_omega_rps,
                zeta: section.airspeed_prefilter_zeta,
            },
            roll_filter: SmoothIntegralPrefilter {
                omega_rps: section.roll_prefilter_omega_rps,
                zeta: section.roll_prefilter_zeta,
            },
            pitch_filter: SmoothIntegralPrefilter {
                omega_rps: section.pitch_prefilter_omega_rps,
                zeta: section.pitch_prefilter_zeta,
            },
            heading_filter: SmoothIntegralPrefilter {
                omega_rps: section.heading_prefilter_omega_rps,
                zeta: section.heading_prefilter_zeta,
            },
            rate_filter: SecondOrderFilter {
                omega_rps: section.rate_filter_omega_rps,
                zeta: section.rate_filter_zeta,
            },
            basis: RbfBasis::axis_star(section.rbf_width),
            drag_bound: BallBound {
                max_norm: section.drag_weight_max,
                epsilon: section.weight_epsilon,
            },
            moment_bound: BallBound {
                max_norm: section.moment_weight_max,
                epsilon: section.weight_epsilon,
            },
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
        let mut x = vec![0.0; AUTOPILOT_STATE_LEN];
        let euler = &air_data.euler;
        x[AIRSPEED_FILTER..AIRSPEED_FILTER + 2]
            .copy_from_slice(&IntegralPrefilter::initial_state(air_data.airspeed_fps));
        for (at, value) in [
            (ROLL_FILTER, euler.phi_rad),
            (PITCH_FILTER, euler.theta_rad),
            (HEADING_FILTER, euler.psi_rad),
        ] {
            x[at..at + 3].copy_from_slice(&SmoothIntegralPrefilter::initial_state(value));
        }
        for axis in 0..3 {
            let at = RATE_FILTER + 2 * axis;
            x[at..at + 2].copy_from_slice(&SecondOrderFilter::initial_state(
                air_data.body_rates_rps[axis],
            ));
        }
        let wind = measured_wind_ned_fps(air_data);
        if wind.iter().all(|w| w.is_finite()) {
            x[WIND_ESTIMATE..WIND_ESTIMATE + 3].copy_from_slice(wind.as_slice());
        }
        x
    }

    /// ŵ of a state slice, NED, ft/s.
    pub fn wind_estimate_ned_fps(x: &[f64]) -> Vec3 {
        Vec3::new(x[WIND_ESTIMATE], x[WIND_ESTIMATE + 1], x[WIND_ESTIMATE + 2])
    }

    /// Ŵ_D of a state slice.
    pub fn drag_weights(x: &[f64]) -> &[f64] {
        &x[WEIGHTS..WEIGHTS + RBF_CENTRES]
    }

    /// Ŵ_l, Ŵ_m, Ŵ_n of a state slice (in that order).
    pub fn moment_weights(x: &[f64]) -> [&[f64]; 3] {
        let at = |k: usize| &x[WEIGHTS + k * RBF_CENTRES..WEIGHTS + (k + 1) * RBF_CENTRES];
        [at(ROLL), at(PITCH), at(YAW)]
    }

    /// Ω_1 of the drag network's projection: ‖Ŵ_D‖ ≤ this.
    pub fn drag_weight_outer_bound(&self) -> f64 {
        (self.drag_bound.max_norm.powi(2) + self.drag_bound.epsilon).sqrt()
    }

    /// Ω_1 of the moment networks' projection: ‖Ŵ_i‖ ≤ this.
    pub fn moment_weight_outer_bound(&self) -> f64 {
        (self.moment_bound.max_norm.powi(2) + self.moment_bound.epsilon).sqrt()
    }

    /// Pulls every weight vector back into Ω_1 after an integration step (see
    /// [`crate::guidance::projection`]).
    pub fn enforce_bounds(&self, x: &mut [f64]) {
        for k in 0..4 {
            let bound = if k == DRAG {
                &self.drag_bound
            } else {
                &self.moment_bound
            };
            let w = &mut x[WEIGHTS + k * RBF_CENTRES..WEIGHTS + (k + 1) * RBF_CENTRES];
            clamp_ball(bound, w);
        }
    }

    /// Writes ẋ of the controller's state into `dx` and returns the actuator commands with
    /// telemetry. `x` and `dx` must hold [`Self::state_len`] values.
    pub fn derivative(&self, x: &[f64], input: &AutopilotInput, dx: &mut [f64]) -> AutopilotOutput {
        debug_assert!(x.len() >= AUTOPILOT_STATE_LEN && dx.len() >= AUTOPILOT_STATE_LEN);
        let g = &self.gains;
        let air = &input.air_data;
        let mass = self.params.mass.mass_slug;
        let wing_area = self.params.geometry.wing_area_ft2;

        // Dynamic pressure used by the inversions, floored at the minimum control airspeed.
        let density = if air.airspeed_fps > 1.0 {
            2.0 * air.dynamic_pressure_lbf_ft2 / (air.airspeed_fps * air.airspeed_fps)
        } else {
            SEA_LEVEL_DENSITY_SLUG_FT3
        };
        let qbar_floor = 0.5 * density * g.min_control_airspeed_fps.powi(2);
        let qbar_control = air.dynamic_pressure_lbf_ft2.max(qbar_floor);
        let effectiveness = self.params.control_effectiveness(qbar_control);

        // RBF basis and the networks' outputs.
        let mut phi = [0.0; RBF_CENTRES];
        self.basis.evaluate(
            &RbfInput {
                airspeed_fps: air.airspeed_fps,
                alpha_rad: air.alpha_rad,
                beta_rad: air.beta_rad,
                body_rates_rps: air.body_rates_rps,
                actuators: input.actuators,
            },
            &mut phi,
        );
        let network = |k: usize| -> f64 {
            let w = &x[WEIGHTS + k * RBF_CENTRES..WEIGHTS + (k + 1) * RBF_CENTRES];
            w.iter().zip(&phi).map(|(a, b)| a * b).sum()
        };
        let drag_correction = network(DRAG);
        let moment_correction = Vec3::new(network(ROLL), network(PITCH), network(YAW));

        // Nominal aerodynamics at zero deflection (the controller's model: no Δ).
        let angles = AirAngles {
            airspeed_fps: air.airspeed_fps,
            alpha_rad: air.alpha_rad,
            beta_rad: air.beta_rad,
        };
        let zero = Controls::default();
        let coefficients = self
            .params
            .coefficients(&angles, &air.body_rates_rps, &zero);
        let qs = air.dynamic_pressure_lbf_ft2 * wing_area;
        let nominal_drag_lbf = qs * coefficients.drag;

        // 1. Wind estimate, then V_F → V_c, γ_c, χ_c (held at the filter states for a
        // non-finite command).
        let air_velocity_ned = air_velocity_ned_fps(air);
        let wind_measured = air.velocity_ned_fps - air_velocity_ned;
        let wind_estimate = Self::wind_estimate_ned_fps(x);
        let wind_rate = if wind_measured.iter().all(|w| w.is_finite()) {
            (wind_measured - wind_estimate) / g.wind_filter_time_constant_s
        } else {
            Vec3::zeros()
        };
        dx[WIND_ESTIMATE..WIND_ESTIMATE + 3].copy_from_slice(wind_rate.as_slice());
        let air_velocity_cmd = if g.wind_compensation {
            input.velocity_cmd_ned_fps - wind_estimate
        } else {
            input.velocity_cmd_ned_fps
        };
        let air_flight_path = if air.airspeed_fps > 0.0 {
            (-air_velocity_ned.z / air.airspeed_fps)
                .clamp(-1.0, 1.0)
                .asin()
        } else {
            0.0
        };
        let reference = VelocityReference::from_velocity_ned(&air_velocity_cmd);
        let airspeed_cmd = reference
            .map_or(x[AIRSPEED_FILTER + 1], |r| r.airspeed_fps)
            .clamp(g.min_airspeed_cmd_fps, g.max_airspeed_cmd_fps);
        let v_ref = self.airspeed_filter.derivative(
            &x[AIRSPEED_FILTER..],
            airspeed_cmd,
            &mut dx[AIRSPEED_FILTER..],
        );
        let euler = air.euler;
        let raw_flight_path = reference.map_or(air_flight_path, |r| r.flight_path_rad);
        let flight_path_cmd = self.limited_flight_path(
            raw_flight_path,
            air,
            effectiveness.thrust_per_throttle_lbf,
            nominal_drag_lbf,
            drag_correction,
        );

        // 2-3. Attitude references and their prefilters.
        let psi_m = x[HEADING_FILTER + 1];
        let heading_cmd = reference
            .and_then(|r| r.course_rad)
            .map_or(psi_m, |course| unwrap_near_rad(course, psi_m));
        let psi_ref = self.heading_filter.derivative(
            &x[HEADING_FILTER..],
            heading_cmd,
            &mut dx[HEADING_FILTER..],
        );
        // Bank for the heading rate (7.24) asks for, ψ̇_m - k_ψ e_ψ, limited to the turn rate
        // of the bank limit: with the seed's φ_c from ψ̇_m alone a heading error the reference
        // has run ahead of (a large turn) is flown on the rudder, skidding with it at its limit.
        let max_turn_rate = GRAVITY_FPS2 * g.max_bank_deg.to_radians().tan()
            / air.airspeed_fps.max(g.min_control_airspeed_fps);
        let heading_rate_demand = (psi_ref.rate
            - g.yaw_gain_per_s * wrap_angle_rad(air.euler.psi_rad - psi_ref.value))
        .clamp(-max_turn_rate, max_turn_rate);
        let bank_cmd = coordinated_turn_bank_rad(
            heading_rate_demand,
            v_ref.value,
            g.max_bank_deg.to_radians(),
        );
        let phi_ref =
            self.roll_filter
                .derivative(&x[ROLL_FILTER..], bank_cmd, &mut dx[ROLL_FILTER..]);
        let pitch_offset = self.pitch_offset_rad(
            air,
            flight_path_cmd,
            qbar_control * wing_area,
            input.actuators.elevator_rad,
        );
        let pitch_cmd = flight_path_cmd + pitch_offset;
        let theta_ref =
            self.pitch_filter
                .derivative(&x[PITCH_FILTER..], pitch_cmd, &mut dx[PITCH_FILTER..]);
        let (theta_cmd, theta_rate_cmd) =
            self.alpha_envelope(&theta_ref, air_flight_path, euler.phi_rad);
        let euler_cmd = EulerAngles::new(phi_ref.value, theta_cmd, psi_ref.value);
        let euler_rate_cmd = Vec3::new(phi_ref.rate, theta_rate_cmd, psi_ref.rate);

        // 4. (7.24): body-rate commands.
        let euler_error = Vec3::new(
            euler.phi_rad - euler_cmd.phi_rad,
            euler.theta_rad - euler_cmd.theta_rad,
            wrap_angle_rad(euler.psi_rad - euler_cmd.psi_rad),
        );
        let gains_euler = Vec3::new(g.roll_gain_per_s, g.pitch_gain_per_s, g.yaw_gain_per_s);
        let mut euler_rate_demand = -gains_euler.component_mul(&euler_error) + euler_rate_cmd;
        // Turn no faster than a coordinated turn at the bank limit can: beyond it the yaw
        // channel would skid the aircraft round with the rudder.
        euler_rate_demand.z = euler_rate_demand.z.clamp(-max_turn_rate, max_turn_rate);
        let rate_cmd = euler.body_rates_from_rates_matrix() * euler_rate_demand;

        // 5. Command filter: ω_f and ω̇_f.
        let mut filtered = [FilteredCommand::default(); 3];
        for (axis, out) in filtered.iter_mut().enumerate() {
            let at = RATE_FILTER + 2 * axis;
            *out = self
                .rate_filter
                .derivative(&x[at..], rate_cmd[axis], &mut dx[at..]);
        }
        let rate_filtered = Vec3::new(filtered[0].value, filtered[1].value, filtered[2].value);
        let rate_filtered_dot = Vec3::new(filtered[0].rate, filtered[1].rate, filtered[2].rate);
        let omega = air.body_rates_rps;
        let rate_error = omega - rate_filtered;

        // 6. (7.25): moments.
        let j = &self.inertia_slug_ft2;
        let gains_rate = Vec3::new(
            g.roll_rate_gain_per_s,
            g.pitch_rate_gain_per_s,
            g.yaw_rate_gain_per_s,
        );
        let p_matrix = euler.rates_from_body_rates_matrix();
        let angular_accel_demand = -gains_rate.component_mul(&rate_error) + rate_filtered_dot;
        let moment_cmd = omega.cross(&(j * omega))
            - j * (p_matrix.transpose() * euler_error)
            - j * moment_correction
            + j * angular_accel_demand;

        // 7. Invert (7.19) for the surfaces and (7.20) for the throttle.
        let span = self.params.geometry.span_ft;
        let chord = self.params.geometry.chord_ft;
        let moment_zero = Vec3::new(
            qs * span * coefficients.roll,
            qs * chord * coefficients.pitch,
            qs * span * coefficients.yaw,
        );
        let surfaces = effectiveness
            .moment_per_surface_lbf_ft
            .try_inverse()
            .map_or(Vec3::zeros(), |inverse| {
                inverse * (moment_cmd - moment_zero)
            });
        let airspeed_error = air.airspeed_fps - v_ref.value;
        let cos_alpha_beta = (air.alpha_rad.cos() * air.beta_rad.cos()).max(0.1);
        let thrust_cmd = (mass * GRAVITY_FPS2 * air_flight_path.sin()
            + nominal_drag_lbf
            + mass * drag_correction
            - mass * g.airspeed_gain_per_s * airspeed_error
            + mass * v_ref.rate)
            / cos_alpha_beta;
        let unclamped = Controls {
            throttle: thrust_cmd / effectiveness.thrust_per_throttle_lbf,
            aileron_rad: surfaces.x,
            elevator_rad: surfaces.y,
            rudder_rad: surfaces.z,
        };
        let (controls, saturation) = self.clamp(&unclamped, &input.actuators);

        // 8. Adaptation (7.23), (7.28).
        self.adaptation_rates(
            x,
            &phi,
            airspeed_error,
            &rate_error,
            &saturation,
            &mut dx[WEIGHTS..AUTOPILOT_STATE_LEN],
        );

        AutopilotOutput {
            controls,
            unclamped,
            saturation,
            airspeed_cmd_fps: airspeed_cmd,
            airspeed_ref_fps: v_ref.value,
            airspeed_error_fps: airspeed_error,
            flight_path_cmd_rad: flight_path_cmd,
            flight_path_limited: flight_path_cmd != raw_flight_path,
            euler_cmd,
            euler_rate_cmd_rps: euler_rate_cmd,
            euler_error_rad: euler_error,
            rate_cmd_rps: rate_cmd,
            rate_cmd_filtered_rps: rate_filtered,
            rate_error_rps: rate_error,
            thrust_cmd_lbf: thrust_cmd,
            moment_cmd_lbf_ft: moment_cmd,
            drag_correction_fps2: drag_correction,
            moment_correction_rps2: moment_correction,
        }
    }

    /// γ_c kept between the steepest descent and climb that (7.20) can hold with the
    /// throttle inside its range less the margins ([`limit_flight_path`]); unchanged with
    /// `flight_path_limits` off. `specific_force_fps2` is Ŵ_DᵀΦ: the limits are those of
    /// steady speed (module docs).
    fn limited_flight_path(
        &self,
        raw_rad: f64,
        air: &AirData,
        thrust_per_throttle_lbf: f64,
        nominal_drag_lbf: f64,
        specific_force_fps2: f64,
    ) -> f64 {
        let g = &self.gains;
        if !g.flight_path_limits {
            return raw_rad;
        }
        let full = thrust_per_throttle_lbf * self.params.actuators.throttle.max;
        let idle = thrust_per_throttle_lbf * self.params.actuators.throttle.min;
        let margin = g.thrust_margin_fraction * (full - idle);
        let at_thrust = |thrust: f64| {
            flight_path_for_thrust_rad(
                thrust,
                air.alpha_rad,
                air.beta_rad,
                nominal_drag_lbf,
                self.params.mass.mass_slug,
                specific_force_fps2,
            )
        };
        limit_flight_path(raw_rad, at_thrust(idle + margin), at_thrust(full - margin))
    }

    /// The pitch offset α_ref cos φ added to γ_c in θ_c (0 with `alpha_feedforward` off).
    fn pitch_offset_rad(
        &self,
        air: &AirData,
        flight_path_cmd_rad: f64,
        dynamic_pressure_area_lbf: f64,
        elevator_rad: f64,
    ) -> f64 {
        let g = &self.gains;
        if !g.alpha_feedforward {
            return 0.0;
        }
        let a = &self.params.aero;
        let max_alpha = g.max_alpha_ref_deg.to_radians();
        alpha_reference_rad(&AlphaReferenceInput {
            mass_slug: self.params.mass.mass_slug,
            dynamic_pressure_area_lbf,
            flight_path_rad: flight_path_cmd_rad,
            bank_rad: air.euler.phi_rad,
            thrust_lbf: air.thrust_lbf,
            alpha_rad: air.alpha_rad,
            c_lift_0: a.c_lift_0,
            c_lift_alpha_per_rad: a.c_lift_alpha_per_rad,
            c_lift_elevator: a.c_lift_de_per_rad * elevator_rad,
        })
        .map_or(0.0, |alpha| {
            alpha.clamp(-max_alpha, max_alpha) * air.euler.phi_rad.cos()
        })
    }

    /// α envelope: θ_c (and θ̇_c) kept within γ + [α_min, α_max] cos φ, so that tracking θ_c
    /// can never hold the aircraft beyond the stall (inside the envelope nothing changes).
    fn alpha_envelope(
        &self,
        theta_ref: &FilteredCommand,
        air_flight_path_rad: f64,
        phi_rad: f64,
    ) -> (f64, f64) {
        let g = &self.gains;
        let cos_phi = phi_rad.cos().max(0.0);
        let ceiling = air_flight_path_rad + g.max_alpha_deg.to_radians() * cos_phi;
        let floor = air_flight_path_rad + g.min_alpha_deg.to_radians() * cos_phi;
        if theta_ref.value > ceiling {
            (ceiling, 0.0)
        } else if theta_ref.value < floor {
            (floor, 0.0)
        } else {
            (theta_ref.value, theta_ref.rate)
        }
    }

    /// Clamps each command into its actuator's limits; a non-finite command holds the
    /// actuator's present position (and counts as saturated, which stops adaptation).
    fn clamp(&self, unclamped: &Controls, positions: &Controls) -> (Controls, Saturation) {
        let limits = &self.params.actuators;
        let one = |command: f64, position: f64, limit: &ActuatorLimits| -> (f64, bool) {
            if command.is_finite() {
                (
                    command.clamp(limit.min, limit.max),
                    command < limit.min || command > limit.max,
                )
            } else {
                (position, true)
            }
        };
        let (throttle, t) = one(unclamped.throttle, positions.throttle, &limits.throttle);
        let (elevator_rad, e) = one(
            unclamped.elevator_rad,
            positions.elevator_rad,
            &limits.elevator,
        );
        let (aileron_rad, a) = one(
            unclamped.aileron_rad,
            positions.aileron_rad,
            &limits.aileron,
        );
        let (rudder_rad, r) = one(unclamped.rudder_rad, positions.rudder_rad, &limits.rudder);
        (
            Controls {
                throttle,
                elevator_rad,
                aileron_rad,
                rudder_rad,
            },
            Saturation {
                throttle: t,
                elevator: e,
                aileron: a,
                rudder: r,
            },
        )
    }

    /// Ŵ' of the four networks into `dw` (4 × RBF_CENTRES values):
    /// Ŵ_D' = G_D Proj(Ŵ_D, -e_V Φ) (sign: module docs), Ŵ_i' = G_i Proj(Ŵ_i, e_i Φ) (7.28).
    /// Anti-wind-up: with `freeze_adaptation_on_saturation`, the drag network stops while the
    /// throttle is clamped, the pitch network while the elevator is, and the roll and yaw
    /// networks while the aileron or the rudder is (the inversion couples them).
    fn adaptation_rates(
        &self,
        x: &[f64],
        phi: &[f64; RBF_CENTRES],
        airspeed_error: f64,
        rate_error: &Vec3,
        saturation: &Saturation,
        dw: &mut [f64],
    ) {
        let g = &self.gains;
        let freeze = g.freeze_adaptation_on_saturation;
        let lateral = saturation.aileron || saturation.rudder;
        let networks = [
            (
                DRAG,
                -airspeed_error,
                g.drag_adaptation_gain,
                saturation.throttle,
            ),
            (ROLL, rate_error.x, g.roll_adaptation_gain, lateral),
            (
                PITCH,
                rate_error.y,
                g.pitch_adaptation_gain,
                saturation.elevator,
            ),
            (YAW, rate_error.z, g.yaw_adaptation_gain, lateral),
        ];
        for (k, error, gain, saturated) in networks {
            let range = k * RBF_CENTRES..(k + 1) * RBF_CENTRES;
            let out = &mut dw[range.clone()];
            let active = g.rbf_enabled && !(freeze && saturated) && error.is_finite();
            if !active {
                out.fill(0.0);
                continue;
            }
            for (o, p) in out.iter_mut().zip(phi) {
                *o = error * p;
            }
            let w = &x[WEIGHTS + range.start..WEIGHTS + range.end];
            let bound = if k == DRAG {
                &self.drag_bound
            } else {
                &self.moment_bound
            };
            project_ball(bound, w, out);
            out.iter_mut().for_each(|o| *o *= gain);
        }
    }
}

/// The air-relative velocity in NED: L_BEᵀ V [cos α cos β, sin β, sin α cos β].
fn air_velocity_ned_fps(air: &AirData) -> Vec3 {
    let angles = AirAngles {
        airspeed_fps: air.airspeed_fps,
        alpha_rad: air.alpha_rad,
        beta_rad: air.beta_rad,
    };
    air.euler.body_from_ned().transpose() * angles.air_velocity_body_fps()
}

/// The wind the air data and the inertial velocity imply: inertial minus air-relative
/// velocity, NED, ft/s.
pub fn measured_wind_ned_fps(air: &AirData) -> Vec3 {
    air.velocity_ned_fps - air_velocity_ned_fps(air)
}
