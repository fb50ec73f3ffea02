//! What the controller knows of the aircraft at one instant: the dynamic pressure its
//! inversions use, the controls' effectiveness there, the nominal aerodynamics at zero
//! deflection and the RBF networks' corrections Ŵᵀ Φ.

use super::control_law::ControlLaw;
use super::rbf::{RBF_CENTRES, RbfInput};
use super::signals::AutopilotInput;
use super::state::{AutopilotState, DRAG, PITCH, ROLL, YAW};
use crate::frames::{SEA_LEVEL_DENSITY_SLUG_FT3, Vec3};
use crate::world::aircraft::{AirAngles, CoefficientValues, ControlEffectiveness, Controls};

/// What the controller knows of the aircraft at one instant (step 0 of
/// [`super::Autopilot::derivative`]).
pub(super) struct NominalModel {
    /// q̄ the inversions use, floored at the minimum control airspeed, lbf/ft².
    pub(super) qbar_control: f64,
    /// Forces and moments per unit of each control at that q̄.
    pub(super) effectiveness: ControlEffectiveness,
    /// Φ, the RBF basis (2.34).
    pub(super) phi: [f64; RBF_CENTRES],
    /// Ŵ_DᵀΦ, ft/s².
    pub(super) drag_correction_fps2: f64,
    /// [Ŵ_lᵀΦ, Ŵ_mᵀΦ, Ŵ_nᵀΦ], rad/s².
    pub(super) moment_correction_rps2: Vec3,
    /// Nominal coefficients at zero deflection.
    pub(super) coefficients: CoefficientValues,
    /// q̄ S, lbf.
    pub(super) qs: f64,
    /// Nominal drag, lbf.
    pub(super) nominal_drag_lbf: f64,
}

impl ControlLaw {
    /// What the controller knows of the aircraft at this instant: the dynamic pressure it
    /// inverts with (floored at the minimum control airspeed), the controls' effectiveness
    /// there, the nominal aerodynamics at zero deflection (its model: no Δ) and the RBF
    /// networks' corrections.
    pub(super) fn nominal_model(
        &self,
        state: &AutopilotState,
        input: &AutopilotInput,
    ) -> NominalModel {
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
}
