//! Steps 4-6 of the controller: the body-rate commands, their command filter and the moment
//! command.
//!
//! - (7.24): [p_c, q_c, r_c] = H [-k_φ e_φ + φ̇_m, -k_θ e_θ + θ̇_m, -k_ψ e_ψ + ψ̇_m], H = P⁻¹,
//!   the heading-rate demand clamped to the rate of a coordinated turn at the bank limit,
//!   g tan φ_max / V (a large heading step is then flown as a banked turn, not a skid).
//! - Command filter (dynamic surface / command-filtered backstepping): a second-order filter
//!   per axis gives ω_f and ω̇_f; e_ω = ω - ω_f and ṗ_c, q̇_c, ṙ_c = ω̇_f in (7.25). This
//!   avoids differentiating H, the Euler errors and the references analytically.
//! - (7.25): [L, M, N]_cmd = ω × Jω - J Pᵀ e_E - J Ŵᵀ Φ + J [-k_p e_p + ṗ_c, ...]. Pᵀ (not the
//!   seed's printed P) cancels the cross term of (7.27).

use super::attitude::AttitudeReferences;
use super::control_law::ControlLaw;
use super::nominal_model::NominalModel;
use super::prefilter::FilteredCommand;
use super::state::AutopilotState;
use crate::frames::Vec3;
use crate::world::aircraft::AirData;

/// Steps 4-5's rate commands.
pub(super) struct RateLoop {
    /// [p_c, q_c, r_c] of (7.24).
    pub(super) command_rps: Vec3,
    /// ω_f and ω̇_f.
    pub(super) filtered_rps: Vec3,
    pub(super) filtered_rate_rps2: Vec3,
    /// e_ω = ω - ω_f.
    pub(super) error_rps: Vec3,
}

impl ControlLaw {
    /// Steps 4-5: the body-rate commands of (7.24) and the command filter's ω_f and ω̇_f.
    pub(super) fn rate_commands(
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
    pub(super) fn moment_command(
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
}
