//! Step 8 of the controller: adaptation of the RBF weights (7.23), (7.28) with ball
//! projection; a network stops adapting while the actuator it acts through is clamped
//! (anti-wind-up).
//!
//! Sign of (7.23): the thrust law adds + m Ŵ_DᵀΦ (Ŵ_DᵀΦ estimates ΔD/m, (7.18)), so with
//! W̃ = Ŵ - W the speed error obeys ė_V = -k_V e_V + W̃_DᵀΦ - ε_D and V̇₁ ≤ -k_V e_V² needs
//! Ŵ_D' = G_D Proj(Ŵ_D, **-** e_V Φ). The seed prints ė_V = ... - W̃ᵀΦ and
//! Ŵ_D' = G_D Proj(Ŵ_D, e_V Φ), which would make the drag estimate run away from the true
//! drag; the moment laws (7.28) are consistent as printed (J⁻¹Δ enters (7.25) with a minus).

use super::control_law::ControlLaw;
use super::rbf::RBF_CENTRES;
use super::signals::Saturation;
use super::state::{AutopilotState, DRAG};
use crate::frames::Vec3;
use crate::projection::BallBound;

impl ControlLaw {
    /// The projection bound of network `k` (drag, or a moment).
    pub(super) fn weight_bound(&self, k: usize) -> &BallBound {
        if k == DRAG {
            &self.drag_bound
        } else {
            &self.moment_bound
        }
    }

    /// Ŵ' of the four networks into `dw` (4 × RBF_CENTRES values):
    /// Ŵ_D' = G_D Proj(Ŵ_D, -e_V Φ) (sign: module docs), Ŵ_i' = G_i Proj(Ŵ_i, e_i Φ) (7.28).
    /// Anti-wind-up: with `freeze_adaptation_on_saturation`, the drag network stops while the
    /// throttle is clamped, the pitch network while the elevator is, and the roll and yaw
    /// networks while the aileron or the rudder is (the inversion couples them).
    pub(super) fn adaptation_rates(
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
