//! Steps 2-3 of the controller: the attitude references and their prefilters.
//!
//! Raw attitude references (Remark 9): ψ_c = χ_c (unwrapped against the filter state, so it
//! never jumps by 2π); θ_c = γ_c + α_ref cos φ, α_ref from the nominal lift curve
//! ((7.8)-(7.9) with β = 0; the seed's θ_c = γ_c would leave the aircraft flying its trim α,
//! 4.5°, below the commanded path, i.e. sinking at 4 ft/s when told to fly level);
//! φ_c = atan(ψ̇_d V_m / g) (7.14) for the heading rate that (7.24) demands,
//! ψ̇_d = ψ̇_m - k_ψ e_ψ, e_ψ = ψ - ψ_m, limited to the turn rate of the bank limit (the
//! *filtered* heading rate ψ̇_m, not the raw command's; with ψ̇_m alone, as in (7.14), a
//! heading error the reference has run ahead of is flown on the rudder, skidding).
//!
//! Prefilters (Remark 10): V_c goes through the seed's (7.33) (step 1), φ_c, θ_c, ψ_c through
//! (7.33) with one more integrator ([`super::SmoothIntegralPrefilter`]: the rate it hands to
//! (7.24) is a state, continuous even when the command jumps). Each gives the filtered
//! reference and its exact derivative, and follows ramps (a steady turn, a steady speed
//! change) without lag. θ_c is then held inside γ + [α_min, α_max] cos φ (an α envelope: pitch
//! tracking by model inversion would otherwise hold the aircraft in a stall once it got
//! there).

use super::control_law::ControlLaw;
use super::nominal_model::NominalModel;
use super::prefilter::FilteredCommand;
use super::reference::{
    AlphaReferenceInput, alpha_reference_rad, coordinated_turn_bank_rad, unwrap_near_rad,
};
use super::signals::AutopilotInput;
use super::state::AutopilotState;
use super::velocity_command::VelocityReferences;
use crate::frames::{EulerAngles, GRAVITY_FPS2, Vec3, wrap_angle_rad};
use crate::scenario::BankLimit;
use crate::world::aircraft::AirData;

/// Steps 2-3's references.
pub(super) struct AttitudeReferences {
    pub(super) euler_cmd: EulerAngles,
    pub(super) euler_rate_cmd_rps: Vec3,
    pub(super) euler_error_rad: Vec3,
    /// The turn rate of the bank limit, rad/s.
    pub(super) max_turn_rate_rps: f64,
}

impl ControlLaw {
    /// Steps 2-3: the raw attitude references (Remark 9, with the bank for the heading rate
    /// (7.24) asks for and the α reference) through their prefilters, then the α envelope.
    pub(super) fn attitude_references(
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
        let max_bank_rad = g.max_bank_deg.to_radians();
        let max_turn_rate_rps = max_turn_rate_rps(
            air.airspeed_fps.max(g.min_control_airspeed_fps),
            max_bank_rad,
        );
        let heading_rate_demand = (psi_ref.rate
            - g.yaw_gain_per_s * wrap_angle_rad(air.euler.psi_rad - psi_ref.value))
        .clamp(-max_turn_rate_rps, max_turn_rate_rps);
        let bank_cmd = coordinated_turn_bank_rad(
            heading_rate_demand,
            velocity.airspeed_ref.value,
            max_bank_rad,
        );
        let phi_ref = self.bank_envelope(
            self.roll_filter
                .derivative(&state.roll_filter, bank_cmd, &mut rates.roll_filter),
            max_bank_rad,
        );
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

    /// With `bank_limit = "reference"` the prefiltered bank reference held inside
    /// ±`max_bank_rad` (the prefilter's steps overshoot the limit the command was clamped
    /// to: an S-turn reversal from -30° to 30° reached 46°), at rest while held there; with
    /// `"command"`, the seed's, as it is.
    fn bank_envelope(&self, phi_ref: FilteredCommand, max_bank_rad: f64) -> FilteredCommand {
        if self.gains.bank_limit == BankLimit::Command || phi_ref.value.abs() <= max_bank_rad {
            return phi_ref;
        }
        FilteredCommand {
            value: phi_ref.value.clamp(-max_bank_rad, max_bank_rad),
            rate: 0.0,
        }
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
}

/// The turn rate of a coordinated turn at the bank limit, g tan φ_max / V, rad/s.
fn max_turn_rate_rps(airspeed_fps: f64, max_bank_rad: f64) -> f64 {
    GRAVITY_FPS2 * max_bank_rad.tan() / airspeed_fps
}
