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
//!    Beyond the seed, each off by default: `climb_waits_for_speed` and
//!    `descent_waits_for_speed` keep in the climb and descent limits the acceleration or
//!    deceleration the airspeed law asks for (a slow follower gains speed before it climbs, a
//!    fast one sheds it before it dives); `limited_descent_keeps_horizontal_speed` flies a
//!    descent the limit holds short at the command's horizontal speed, V_c = ‖V_h‖ / cos γ_c,
//!    not at its norm; `weave_period_s` turns a command slower than the aircraft can fly into
//!    S-turns: χ_c ± acos(‖V_h‖ / (V_min cos γ_c)), the side alternating every half period,
//!    which keeps the commanded speed along the course.
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
//! State: [`AutopilotState`], `[V_I, V_m | φ_I, φ_m, φ̇_m | θ_I, θ_m, θ̇_m | ψ_I, ψ_m, ψ̇_m |
//! p_f, ṗ_f, q_f, q̇_f, r_f, ṙ_f | ŵ (3) | Ŵ_D, Ŵ_l, Ŵ_m, Ŵ_n]`, the weights RBF_CENTRES each.

use crate::frames::{
    EulerAngles, GRAVITY_FPS2, Mat3, SEA_LEVEL_DENSITY_SLUG_FT3, Vec3, wrap_angle_rad,
};
use crate::projection::BallBound;
use crate::scenario::AutopilotSection;
use crate::scenario::check::{InvalidValue, require};
use crate::state_block::{StateReader, StateWriter};
use crate::world::aircraft::actuators::ActuatorLimits;
use crate::world::aircraft::{
    AirAngles, AirData, AircraftParams, CoefficientValues, ControlEffectiveness, Controls,
};

use super::prefilter::{
    FilteredCommand, IntegralPrefilter, SecondOrderFilter, SmoothIntegralPrefilter,
};
use super::rbf::{RBF_CENTRES, RbfBasis, RbfInput};
use super::reference::{
    AlphaReferenceInput, VelocityReference, alpha_reference_rad, coordinated_turn_bank_rad,
    flight_path_for_thrust_rad, limit_flight_path, unwrap_near_rad,
};

/// Largest course offset of an S-turn leg (60°: half the commanded speed along the course).
const MAX_WEAVE_OFFSET_RAD: f64 = std::f64::consts::FRAC_PI_3;

/// Length of the controller's state.
pub const AUTOPILOT_STATE_LEN: usize = 20 + 4 * RBF_CENTRES;

/// Index of each network among the weights: drag, roll, pitch, yaw moment.
const DRAG: usize = 0;
const ROLL: usize = 1;
const PITCH: usize = 2;
const YAW: usize = 3;

/// The controller's continuous state ([`AUTOPILOT_STATE_LEN`] values, in this order);
/// holding rates, its derivative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutopilotState {
    /// `[V_I, V_m]`: the airspeed prefilter (7.33).
    pub airspeed_filter: [f64; 2],
    /// `[φ_I, φ_m, φ̇_m]`: the roll prefilter.
    pub roll_filter: [f64; 3],
    /// `[θ_I, θ_m, θ̇_m]`: the pitch prefilter.
    pub pitch_filter: [f64; 3],
    /// `[ψ_I, ψ_m, ψ̇_m]`: the heading prefilter (ψ_m continuous, not wrapped).
    pub heading_filter: [f64; 3],
    /// `[ω_f, ω̇_f]` for p, q and r: the rate command filter.
    pub rate_filter: [[f64; 2]; 3],
    /// ŵ: the wind estimate, NED, ft/s.
    pub wind_estimate_ned_fps: Vec3,
    /// The RBF weights Ŵ_D, Ŵ_l, Ŵ_m, Ŵ_n.
    pub weights: [[f64; RBF_CENTRES]; 4],
}

impl AutopilotState {
    /// Everything zero.
    pub fn zero() -> Self {
        Self {
            airspeed_filter: [0.0; 2],
            roll_filter: [0.0; 3],
            pitch_filter: [0.0; 3],
            heading_filter: [0.0; 3],
            rate_filter: [[0.0; 2]; 3],
            wind_estimate_ned_fps: Vec3::zeros(),
            weights: [[0.0; RBF_CENTRES]; 4],
        }
    }

    /// The typed state of a state slice.
    pub fn unpack(x: &[f64]) -> Self {
        let mut r = StateReader::new(x);
        Self {
            airspeed_filter: r.array(),
            roll_filter: r.array(),
            pitch_filter: r.array(),
            heading_filter: r.array(),
            rate_filter: [(); 3].map(|_| r.array()),
            wind_estimate_ned_fps: r.vec3(),
            weights: [(); 4].map(|_| r.array()),
        }
    }

    /// Writes the block into its state slice.
    pub fn pack(&self, x: &mut [f64]) {
        let mut w = StateWriter::new(x);
        w.values(&self.airspeed_filter)
            .values(&self.roll_filter)
            .values(&self.pitch_filter)
            .values(&self.heading_filter);
        for axis in &self.rate_filter {
            w.values(axis);
        }
        w.vec3(&self.wind_estimate_ned_fps);
        for network in &self.weights {
            w.values(network);
        }
    }

    /// Ŵ_D.
    pub fn drag_weights(&self) -> &[f64; RBF_CENTRES] {
        &self.weights[DRAG]
    }

    /// Ŵ_l, Ŵ_m, Ŵ_n (in that order).
    pub fn moment_weights(&self) -> [&[f64; RBF_CENTRES]; 3] {
        [
            &self.weights[ROLL],
            &self.weights[PITCH],
            &self.weights[YAW],
        ]
    }
}

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
    /// The side of an S-turn leg, +1 right or -1 left of the commanded course (see
    /// `weave_period_s`; unused with it 0).
    pub weave_side: f64,
}

/// The S-turn leg after `flown_s` of flight: +1 (right of the commanded course) for the first
/// half of each `weave_period_s`, -1 (left) for the second; +1 without S-turns (period 0).
pub fn weave_side(flown_s: f64, weave_period_s: f64) -> f64 {
    if weave_period_s > 0.0 && (flown_s / weave_period_s).fract() >= 0.5 {
        -1.0
    } else {
        1.0
    }
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

/// What the controller knows of the aircraft at one instant ([`Autopilot::derivative`]).
struct NominalModel {
    /// q̄ the inversions use, floored at the minimum control airspeed, lbf/ft².
    qbar_control: f64,
    /// Forces and moments per unit of each control at that q̄.
    effectiveness: ControlEffectiveness,
    /// Φ, the RBF basis (2.34).
    phi: [f64; RBF_CENTRES],
    /// Ŵ_DᵀΦ, ft/s².
    drag_correction_fps2: f64,
    /// [Ŵ_lᵀΦ, Ŵ_mᵀΦ, Ŵ_nᵀΦ], rad/s².
    moment_correction_rps2: Vec3,
    /// Nominal coefficients at zero deflection.
    coefficients: CoefficientValues,
    /// q̄ S, lbf.
    qs: f64,
    /// Nominal drag, lbf.
    nominal_drag_lbf: f64,
}

/// Step 1's references.
struct VelocityReferences {
    /// χ_c of the air-relative command, rad (None when it is vertical or zero).
    course_rad: Option<f64>,
    /// V_c, ft/s.
    airspeed_cmd_fps: f64,
    /// V_m and V̇_m.
    airspeed_ref: FilteredCommand,
    /// e_V = V - V_m, ft/s.
    airspeed_error_fps: f64,
    /// γ of the air-relative velocity, rad.
    air_flight_path_rad: f64,
    /// γ_c before and after the flight-path limits, rad.
    raw_flight_path_rad: f64,
    flight_path_cmd_rad: f64,
}

/// Steps 2-3's references.
struct AttitudeReferences {
    euler_cmd: EulerAngles,
    euler_rate_cmd_rps: Vec3,
    euler_error_rad: Vec3,
    /// The turn rate of the bank limit, rad/s.
    max_turn_rate_rps: f64,
}

/// Steps 4-5's rate commands.
struct RateLoop {
    /// [p_c, q_c, r_c] of (7.24).
    command_rps: Vec3,
    /// ω_f and ω̇_f.
    filtered_rps: Vec3,
    filtered_rate_rps2: Vec3,
    /// e_ω = ω - ω_f.
    error_rps: Vec3,
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
                follows_ramps: section.attitude_prefilters_follow_ramps,
            },
            pitch_filter: SmoothIntegralPrefilter {
                omega_rps: section.pitch_prefilter_omega_rps,
                zeta: section.pitch_prefilter_zeta,
                follows_ramps: section.attitude_prefilters_follow_ramps,
            },
            heading_filter: SmoothIntegralPrefilter {
                omega_rps: section.heading_prefilter_omega_rps,
                zeta: section.heading_prefilter_zeta,
                follows_ramps: section.attitude_prefilters_follow_ramps,
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
        (self.drag_bound.max_norm.powi(2) + self.drag_bound.epsilon).sqrt()
    }

    /// Ω_1 of the moment networks' projection: ‖Ŵ_i‖ ≤ this.
    pub fn moment_weight_outer_bound(&self) -> f64 {
        (self.moment_bound.max_norm.powi(2) + self.moment_bound.epsilon).sqrt()
    }

    /// The projection bound of network `k` (drag, or a moment).
    fn weight_bound(&self, k: usize) -> &BallBound {
        if k == DRAG {
            &self.drag_bound
        } else {
            &self.moment_bound
        }
    }

    /// Pulls every weight vector back into Ω_1 after an integration step (see
    /// [`crate::projection`]).
    pub fn enforce_bounds(&self, x: &mut [f64]) {
        let mut state = AutopilotState::unpack(x);
        for (k, w) in state.weights.iter_mut().enumerate() {
            self.weight_bound(k).clamp_slice(w);
        }
        state.pack(x);
    }

    /// Writes ẋ of the controller's state into `dx` and returns the actuator commands with
    /// telemetry. `x` and `dx` must hold [`Self::state_len`] values. The steps are those of
    /// the module docs.
    pub fn derivative(&self, x: &[f64], input: &AutopilotInput, dx: &mut [f64]) -> AutopilotOutput {
        let state = AutopilotState::unpack(x);
        let mut rates = AutopilotState::zero();
        let model = self.nominal_model(&state, input);
        let velocity = self.velocity_references(&state, input, &model, &mut rates);
        let attitude = self.attitude_references(&state, input, &model, &velocity, &mut rates);
        let rate_loop = self.rate_commands(&state, &input.air_data, &attitude, &mut rates);
        let moment_cmd = self.moment_command(&input.air_data, &model, &attitude, &rate_loop);
        let (unclamped, thrust_cmd) = self.inverted_commands(input, &model, &velocity, &moment_cmd);
        let (controls, saturation) = self.clamp(&unclamped, &input.actuators);
        rates.weights = self.adaptation_rates(
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
            flight_path_limited: velocity.flight_path_cmd_rad != velocity.raw_flight_path_rad,
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

    /// What the controller knows of the aircraft at this instant: the dynamic pressure it
    /// inverts with (floored at the minimum control airspeed), the controls' effectiveness
    /// there, the nominal aerodynamics at zero deflection (its model: no Δ) and the RBF
    /// networks' corrections.
    fn nominal_model(&self, state: &AutopilotState, input: &AutopilotInput) -> NominalModel {
        let air = &input.air_data;
        let density = if air.airspeed_fps > 1.0 {
            2.0 * air.dynamic_pressure_lbf_ft2 / (air.airspeed_fps * air.airspeed_fps)
        } else {
            SEA_LEVEL_DENSITY_SLUG_FT3
        };
        let qbar_floor = 0.5 * density * self.gains.min_control_airspeed_fps.powi(2);
        let qbar_control = air.dynamic_pressure_lbf_ft2.max(qbar_floor);
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
        let network =
            |k: usize| -> f64 { state.weights[k].iter().zip(&phi).map(|(a, b)| a * b).sum() };
        let angles = AirAngles {
            airspeed_fps: air.airspeed_fps,
            alpha_rad: air.alpha_rad,
            beta_rad: air.beta_rad,
        };
        let coefficients =
            self.params
                .coefficients(&angles, &air.body_rates_rps, &Controls::default());
        let qs = air.dynamic_pressure_lbf_ft2 * self.params.geometry.wing_area_ft2;
        NominalModel {
            qbar_control,
            effectiveness: self.params.control_effectiveness(qbar_control),
            drag_correction_fps2: network(DRAG),
            moment_correction_rps2: Vec3::new(network(ROLL), network(PITCH), network(YAW)),
            phi,
            nominal_drag_lbf: qs * coefficients.drag,
            coefficients,
            qs,
        }
    }

    /// The wind estimate's rate, and the command relative to the air: V_F - ŵ (V_F without
    /// wind compensation), NED, ft/s.
    fn air_velocity_cmd_ned_fps(
        &self,
        state: &AutopilotState,
        input: &AutopilotInput,
        rates: &mut AutopilotState,
    ) -> Vec3 {
        let g = &self.gains;
        let air = &input.air_data;
        let wind_measured = air.velocity_ned_fps - air_velocity_ned_fps(air);
        let wind_estimate = state.wind_estimate_ned_fps;
        if wind_measured.iter().all(|w| w.is_finite()) {
            rates.wind_estimate_ned_fps =
                (wind_measured - wind_estimate) / g.wind_filter_time_constant_s;
        }
        if g.wind_compensation {
            input.velocity_cmd_ned_fps - wind_estimate
        } else {
            input.velocity_cmd_ned_fps
        }
    }

    /// Step 1: the wind estimate, then V_F → V_c, γ_c, χ_c (held at the filter states for a
    /// non-finite command), the airspeed prefilter, the flight-path limits and the S-turn's
    /// course offset.
    fn velocity_references(
        &self,
        state: &AutopilotState,
        input: &AutopilotInput,
        model: &NominalModel,
        rates: &mut AutopilotState,
    ) -> VelocityReferences {
        let g = &self.gains;
        let air = &input.air_data;
        let air_velocity_cmd = self.air_velocity_cmd_ned_fps(state, input, rates);
        let air_flight_path_rad = if air.airspeed_fps > 0.0 {
            (-air_velocity_ned_fps(air).z / air.airspeed_fps)
                .clamp(-1.0, 1.0)
                .asin()
        } else {
            0.0
        };
        let reference = VelocityReference::from_velocity_ned(&air_velocity_cmd);
        let norm_cmd_fps = reference
            .map_or(state.airspeed_filter[1], |r| r.airspeed_fps)
            .clamp(g.min_airspeed_cmd_fps, g.max_airspeed_cmd_fps);
        let raw_flight_path_rad = reference.map_or(air_flight_path_rad, |r| r.flight_path_rad);
        // What the airspeed law (7.20) asks of the thrust beyond holding the speed, for the
        // norm of the command (the flight-path limits keep it).
        let norm_ref = self.airspeed_filter.derivative(
            &state.airspeed_filter,
            norm_cmd_fps,
            &mut rates.airspeed_filter,
        );
        let airspeed_error_fps = air.airspeed_fps - norm_ref.value;
        let speed_demand_fps2 = norm_ref.rate - g.airspeed_gain_per_s * airspeed_error_fps;
        let flight_path_cmd_rad =
            self.limited_flight_path(raw_flight_path_rad, air, model, speed_demand_fps2);
        // A descent held short of the command (the descent limit raised it).
        let descent_limited = reference.is_some() && flight_path_cmd_rad > raw_flight_path_rad;
        let (airspeed_cmd_fps, airspeed_ref) =
            if descent_limited && g.limited_descent_keeps_horizontal_speed {
                let cmd = self.horizontal_airspeed_cmd_fps(&air_velocity_cmd, flight_path_cmd_rad);
                let filtered = self.airspeed_filter.derivative(
                    &state.airspeed_filter,
                    cmd,
                    &mut rates.airspeed_filter,
                );
                (cmd, filtered)
            } else {
                (norm_cmd_fps, norm_ref)
            };
        let weave_offset_rad = self.weave_offset_rad(&air_velocity_cmd, flight_path_cmd_rad);
        VelocityReferences {
            course_rad: reference
                .and_then(|r| r.course_rad)
                .map(|course| course + input.weave_side * weave_offset_rad),
            airspeed_cmd_fps,
            airspeed_ref,
            airspeed_error_fps,
            air_flight_path_rad,
            raw_flight_path_rad,
            flight_path_cmd_rad,
        }
    }

    /// Steps 2-3: the raw attitude references (Remark 9, with the bank for the heading rate
    /// (7.24) asks for and the α reference) through their prefilters, then the α envelope.
    fn attitude_references(
        &self,
        state: &AutopilotState,
        input: &AutopilotInput,
        model: &NominalModel,
        velocity: &VelocityReferences,
        rates: &mut AutopilotState,
    ) -> AttitudeReferences {
        let g = &self.gains;
        let air = &input.air_data;
        let psi_m = state.heading_filter[1];
        let heading_cmd = velocity
            .course_rad
            .map_or(psi_m, |course| unwrap_near_rad(course, psi_m));
        let psi_ref = self.heading_filter.derivative(
            &state.heading_filter,
            heading_cmd,
            &mut rates.heading_filter,
        );
        // Bank for the heading rate (7.24) asks for, ψ̇_m - k_ψ e_ψ, limited to the turn rate
        // of the bank limit: with the seed's φ_c from ψ̇_m alone a heading error the reference
        // has run ahead of (a large turn) is flown on the rudder, skidding with it at its limit.
        let max_turn_rate_rps = self.max_turn_rate_rps(air);
        let heading_rate_demand = (psi_ref.rate
            - g.yaw_gain_per_s * wrap_angle_rad(air.euler.psi_rad - psi_ref.value))
        .clamp(-max_turn_rate_rps, max_turn_rate_rps);
        let bank_cmd = coordinated_turn_bank_rad(
            heading_rate_demand,
            velocity.airspeed_ref.value,
            g.max_bank_deg.to_radians(),
        );
        let phi_ref =
            self.roll_filter
                .derivative(&state.roll_filter, bank_cmd, &mut rates.roll_filter);
        let pitch_offset = self.pitch_offset_rad(
            air,
            velocity.flight_path_cmd_rad,
            model.qbar_control * self.params.geometry.wing_area_ft2,
            input.actuators.elevator_rad,
        );
        let pitch_cmd = velocity.flight_path_cmd_rad + pitch_offset;
        let theta_ref =
            self.pitch_filter
                .derivative(&state.pitch_filter, pitch_cmd, &mut rates.pitch_filter);
        let (theta_cmd, theta_rate_cmd) =
            self.alpha_envelope(&theta_ref, velocity.air_flight_path_rad, air.euler.phi_rad);
        let euler_cmd = EulerAngles::new(phi_ref.value, theta_cmd, psi_ref.value);
        let euler = &air.euler;
        AttitudeReferences {
            euler_cmd,
            euler_rate_cmd_rps: Vec3::new(phi_ref.rate, theta_rate_cmd, psi_ref.rate),
            euler_error_rad: Vec3::new(
                euler.phi_rad - euler_cmd.phi_rad,
                euler.theta_rad - euler_cmd.theta_rad,
                wrap_angle_rad(euler.psi_rad - euler_cmd.psi_rad),
            ),
            max_turn_rate_rps,
        }
    }

    /// The turn rate of a coordinated turn at the bank limit, g tan φ_max / V, rad/s.
    fn max_turn_rate_rps(&self, air: &AirData) -> f64 {
        let g = &self.gains;
        GRAVITY_FPS2 * g.max_bank_deg.to_radians().tan()
            / air.airspeed_fps.max(g.min_control_airspeed_fps)
    }

    /// Steps 4-5: the body-rate commands of (7.24) and the command filter's ω_f and ω̇_f.
    fn rate_commands(
        &self,
        state: &AutopilotState,
        air: &AirData,
        attitude: &AttitudeReferences,
        rates: &mut AutopilotState,
    ) -> RateLoop {
        let g = &self.gains;
        let gains_euler = Vec3::new(g.roll_gain_per_s, g.pitch_gain_per_s, g.yaw_gain_per_s);
        let mut euler_rate_demand =
            -gains_euler.component_mul(&attitude.euler_error_rad) + attitude.euler_rate_cmd_rps;
        // Turn no faster than a coordinated turn at the bank limit can: beyond it the yaw
        // channel would skid the aircraft round with the rudder.
        let limit = attitude.max_turn_rate_rps;
        euler_rate_demand.z = euler_rate_demand.z.clamp(-limit, limit);
        let command_rps = air.euler.body_rates_from_rates_matrix() * euler_rate_demand;
        let mut filtered = [FilteredCommand::default(); 3];
        for (axis, out) in filtered.iter_mut().enumerate() {
            *out = self.rate_filter.derivative(
                &state.rate_filter[axis],
                command_rps[axis],
                &mut rates.rate_filter[axis],
            );
        }
        let filtered_rps = Vec3::new(filtered[0].value, filtered[1].value, filtered[2].value);
        RateLoop {
            command_rps,
            filtered_rps,
            filtered_rate_rps2: Vec3::new(filtered[0].rate, filtered[1].rate, filtered[2].rate),
            error_rps: air.body_rates_rps - filtered_rps,
        }
    }

    /// Step 6, (7.25): [L, M, N]_cmd = ω × Jω - J Pᵀ e_E - J Ŵᵀ Φ + J [-k e_ω + ω̇_f], lbf ft.
    fn moment_command(
        &self,
        air: &AirData,
        model: &NominalModel,
        attitude: &AttitudeReferences,
        rate_loop: &RateLoop,
    ) -> Vec3 {
        let g = &self.gains;
        let j = &self.inertia_slug_ft2;
        let gains_rate = Vec3::new(
            g.roll_rate_gain_per_s,
            g.pitch_rate_gain_per_s,
            g.yaw_rate_gain_per_s,
        );
        let omega = air.body_rates_rps;
        let p_matrix = air.euler.rates_from_body_rates_matrix();
        let angular_accel_demand =
            -gains_rate.component_mul(&rate_loop.error_rps) + rate_loop.filtered_rate_rps2;
        omega.cross(&(j * omega))
            - j * (p_matrix.transpose() * attitude.euler_error_rad)
            - j * model.moment_correction_rps2
            + j * angular_accel_demand
    }

    /// Step 7: (7.19) inverted for the surfaces, [δa, δe, δr] = B(q̄)⁻¹ ([L, M, N]_cmd - M_0),
    /// and (7.20) for the throttle; the commands before clamping and the thrust, lbf.
    fn inverted_commands(
        &self,
        input: &AutopilotInput,
        model: &NominalModel,
        velocity: &VelocityReferences,
        moment_cmd: &Vec3,
    ) -> (Controls, f64) {
        let g = &self.gains;
        let air = &input.air_data;
        let (span, chord) = (self.params.geometry.span_ft, self.params.geometry.chord_ft);
        let c = &model.coefficients;
        let qs = model.qs;
        let moment_zero = Vec3::new(qs * span * c.roll, qs * chord * c.pitch, qs * span * c.yaw);
        let surfaces = model
            .effectiveness
            .moment_per_surface_lbf_ft
            .try_inverse()
            .map_or(Vec3::zeros(), |inverse| {
                inverse * (moment_cmd - moment_zero)
            });
        let mass = self.params.mass.mass_slug;
        let cos_alpha_beta = (air.alpha_rad.cos() * air.beta_rad.cos()).max(0.1);
        let thrust_cmd = (mass * GRAVITY_FPS2 * velocity.air_flight_path_rad.sin()
            + model.nominal_drag_lbf
            + mass * model.drag_correction_fps2
            - mass * g.airspeed_gain_per_s * velocity.airspeed_error_fps
            + mass * velocity.airspeed_ref.rate)
            / cos_alpha_beta;
        let unclamped = Controls {
            throttle: thrust_cmd / model.effectiveness.thrust_per_throttle_lbf,
            aileron_rad: surfaces.x,
            elevator_rad: surfaces.y,
            rudder_rad: surfaces.z,
        };
        (unclamped, thrust_cmd)
    }

    /// γ_c kept between the steepest descent and climb that (7.20) can hold with the
    /// throttle inside its range less the margins ([`limit_flight_path`]); unchanged with
    /// `flight_path_limits` off. The limits are those of steady speed (module docs), with
    /// the drag correction Ŵ_DᵀΦ; with `climb_waits_for_speed` the climb's also keeps the
    /// acceleration `speed_demand_fps2` the airspeed law asks for (when positive).
    fn limited_flight_path(
        &self,
        raw_rad: f64,
        air: &AirData,
        model: &NominalModel,
        speed_demand_fps2: f64,
    ) -> f64 {
        let g = &self.gains;
        if !g.flight_path_limits {
            return raw_rad;
        }
        let thrust_per_throttle_lbf = model.effectiveness.thrust_per_throttle_lbf;
        let full = thrust_per_throttle_lbf * self.params.actuators.throttle.max;
        let idle = thrust_per_throttle_lbf * self.params.actuators.throttle.min;
        let margin = g.thrust_margin_fraction * (full - idle);
        let at_thrust = |thrust: f64, specific_force_fps2: f64| {
            flight_path_for_thrust_rad(
                thrust,
                air.alpha_rad,
                air.beta_rad,
                model.nominal_drag_lbf,
                self.params.mass.mass_slug,
                specific_force_fps2,
            )
        };
        let steady = model.drag_correction_fps2;
        let climbing = if g.climb_waits_for_speed {
            steady + speed_demand_fps2.max(0.0)
        } else {
            steady
        };
        let descending = if g.descent_waits_for_speed {
            steady + speed_demand_fps2.min(0.0)
        } else {
            steady
        };
        limit_flight_path(
            raw_rad,
            at_thrust(idle + margin, descending),
            at_thrust(full - margin, climbing),
        )
    }

    /// V_c = ‖V_h‖ / cos γ_c: the command's horizontal air speed on the limited path, within
    /// [`min_airspeed_cmd_fps`, `max_airspeed_cmd_fps`], ft/s.
    fn horizontal_airspeed_cmd_fps(&self, air_velocity_cmd: &Vec3, flight_path_rad: f64) -> f64 {
        let g = &self.gains;
        (air_velocity_cmd.x.hypot(air_velocity_cmd.y) / flight_path_rad.cos())
            .clamp(g.min_airspeed_cmd_fps, g.max_airspeed_cmd_fps)
    }

    /// The course offset of an S-turn, rad: when the commanded horizontal air speed is below
    /// the slowest the aircraft flies on the commanded path, V_min cos γ_c, the aircraft flies
    /// V_min at acos(V_h,cmd / (V_min cos γ_c)) (at most [`MAX_WEAVE_OFFSET_RAD`]) off the
    /// commanded course, which keeps the commanded speed along it. 0 with `weave_period_s` 0.
    fn weave_offset_rad(&self, air_velocity_cmd: &Vec3, flight_path_cmd_rad: f64) -> f64 {
        let g = &self.gains;
        if g.weave_period_s <= 0.0 {
            return 0.0;
        }
        let slowest_horizontal_fps = g.min_airspeed_cmd_fps * flight_path_cmd_rad.cos();
        let horizontal_fps = air_velocity_cmd.x.hypot(air_velocity_cmd.y);
        (horizontal_fps / slowest_horizontal_fps)
            .min(1.0)
            .acos()
            .min(MAX_WEAVE_OFFSET_RAD)
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
        state: &AutopilotState,
        phi: &[f64; RBF_CENTRES],
        airspeed_error: f64,
        rate_error: &Vec3,
        saturation: &Saturation,
    ) -> [[f64; RBF_CENTRES]; 4] {
        let g = &self.gains;
        let freeze = g.freeze_adaptation_on_saturation;
        let lateral = saturation.aileron || saturation.rudder;
        let networks = [
            (-airspeed_error, g.drag_adaptation_gain, saturation.throttle),
            (rate_error.x, g.roll_adaptation_gain, lateral),
            (rate_error.y, g.pitch_adaptation_gain, saturation.elevator),
            (rate_error.z, g.yaw_adaptation_gain, lateral),
        ];
        let mut rates = [[0.0; RBF_CENTRES]; 4];
        for (k, (error, gain, saturated)) in networks.into_iter().enumerate() {
            let active = g.rbf_enabled && !(freeze && saturated) && error.is_finite();
            if !active {
                continue;
            }
            let out = &mut rates[k];
            for (o, p) in out.iter_mut().zip(phi) {
                *o = error * p;
            }
            self.weight_bound(k).project_slice(&state.weights[k], out);
            out.iter_mut().for_each(|o| *o *= gain);
        }
        rates
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
/// The names of the controller's state elements, in [`AutopilotState`]'s order (for
/// messages): "autopilot: RBF weight 3 of the pitch channel".
pub fn autopilot_state_names() -> Vec<String> {
    use crate::state_block::{NED, element_names};
    let filter = ["filtered command", "its rate"];
    let mut names = element_names(
        "autopilot",
        &[
            ("airspeed prefilter", &["integral", "V_m"]),
            ("roll prefilter", &["integral", "φ_m", "φ̇_m"]),
            ("pitch prefilter", &["integral", "θ_m", "θ̇_m"]),
            ("heading prefilter", &["integral", "ψ_m", "ψ̇_m"]),
            ("p command filter", &filter),
            ("q command filter", &filter),
            ("r command filter", &filter),
            ("wind estimate, ft/s", NED),
        ],
    );
    for channel in ["drag", "roll", "pitch", "yaw"] {
        names.extend(
            (0..RBF_CENTRES).map(|k| format!("autopilot: RBF weight {k} of the {channel} channel")),
        );
    }
    names
}
