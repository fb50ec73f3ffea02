//! Step 7 of the controller: (7.19) inverted, [δa, δe, δr] = B(q̄)⁻¹ ([L, M, N]_cmd - M_0),
//! M_0 the nominal moments at zero deflection; (7.20) T → δT = T / (q̄ S C_TδT) (or the energy
//! loop's T, [`super::energy`]). Each command is clamped to its limit.

use super::control_law::ControlLaw;
use super::nominal_model::NominalModel;
use super::signals::{AutopilotInput, Saturation};
use super::velocity_command::VelocityReferences;
use crate::frames::{GRAVITY_FPS2, Vec3};
use crate::world::aircraft::Controls;
use crate::world::aircraft::actuators::ActuatorLimits;

impl ControlLaw {
    /// Step 7: (7.19) inverted for the surfaces, [δa, δe, δr] = B(q̄)⁻¹ ([L, M, N]_cmd - M_0),
    /// and (7.20) for the throttle; the commands before clamping and the thrust, lbf.
    pub(super) fn inverted_commands(
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
        let thrust_cmd = velocity.thrust_cmd_lbf.unwrap_or_else(|| {
            (mass * GRAVITY_FPS2 * velocity.air_flight_path_rad.sin()
                + model.nominal_drag_lbf
                + mass * model.drag_correction_fps2
                - mass * g.airspeed_gain_per_s * velocity.airspeed_error_fps
                + mass * velocity.airspeed_ref.rate)
                / cos_alpha_beta
        });
        let unclamped = Controls {
            throttle: thrust_cmd / model.effectiveness.thrust_per_throttle_lbf,
            aileron_rad: surfaces.x,
            elevator_rad: surfaces.y,
            rudder_rad: surfaces.z,
        };
        (unclamped, thrust_cmd)
    }

    /// Clamps each command into its actuator's limits; a non-finite command holds the
    /// actuator's present position (and counts as saturated, which stops adaptation).
    pub(super) fn clamp(
        &self,
        unclamped: &Controls,
        positions: &Controls,
    ) -> (Controls, Saturation) {
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
}
