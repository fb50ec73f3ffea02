//! What the controller reads at one instant besides its own state, and what it gives back:
//! the actuator commands, which of them were clamped, and its telemetry.

use crate::frames::{EulerAngles, Vec3};
use crate::world::aircraft::{AirData, Controls};

/// What the controller reads at one instant besides its own state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutopilotInput {
    /// The guidance command V_F, NED, ft/s.
    pub velocity_cmd_ned_fps: Vec3,
    /// Air data of the follower (airspeed, α, β, attitude, rates, loads): the truth the
    /// inner loops fly on.
    pub air_data: AirData,
    /// The air data as the follower's sensors read it (airspeed, α, β with their errors,
    /// attitude and inertial velocity from its navigation): what the wind estimate is built
    /// from. `air_data` itself when they are perfect.
    pub sensed_air_data: AirData,
    /// Actuator positions (the plant's actuator states): RBF inputs u of (7.18) and the
    /// elevator's lift in α_ref.
    pub actuators: Controls,
    /// The side of an S-turn leg, +1 right or -1 left of the commanded course (see
    /// `weave_period_s`; unused with it 0); 0: no S-turn (a slot beside the target).
    pub weave_side: f64,
    /// The slot's line as the follower's estimate places it, with S-turns by geometry
    /// (`weave_half_width_ft`): their legs are placed about it; `None`: about the command's
    /// course.
    pub slot_line: Option<SlotAxis>,
}

/// The slot's line as the S-turns by geometry fly about it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlotAxis {
    /// Its course (the target's estimated track), rad.
    pub track_rad: f64,
    /// How far the follower is ahead of its slot along it, ft (from the Kalman estimate).
    pub ahead_of_slot_ft: f64,
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
