//! Gaussian radial basis functions (2.34) of the flight condition (the weights are bounded by
//! the ball projection of Appendix A, [`crate::projection::BallBound`]).
//!
//! Inputs (7.18): ξ = (V, α, β, p, q, r) and u = (δT, δa, δe, δr), where u are the actuator
//! *positions* (plant states), not the commands being computed, so Φ never closes an algebraic
//! loop through the control law. Each input is normalised, z_i = (x_i - x_i,0) / s_i, with the
//! centre x_i,0 at the 50 ft/s trim and a scale s_i of a typical excursion in the seed's runs
//! ([`INPUT_CENTRES`], [`INPUT_SCALES`]).
//!
//! Centres: the origin plus ±1 along each of the 10 normalised axes, 21 in all, with one width
//! σ (default 1). This covers the operating envelope one typical excursion each way with few
//! weights per network (the seed notes ε* = O(1/√m); the networks here only have to absorb
//! slowly varying Δ, not the whole aerodynamics, which the nominal model carries). A full grid
//! would need 3¹⁰ centres.

use crate::frames::Vec3;
use crate::world::aircraft::Controls;

/// Number of network inputs: V, α, β, p, q, r, δT, δa, δe, δr.
pub const RBF_INPUTS: usize = 10;
/// Number of Gaussian centres (origin plus ±1 on each normalised axis).
pub const RBF_CENTRES: usize = 1 + 2 * RBF_INPUTS;

/// Centres x_i,0 of the normalisation: 50 ft/s, α = 0.08 rad (the trim's 4.5°), β = p = q =
/// r = 0, half throttle, δa = 0, δe = -0.1 rad (trim -6°), δr = 0.
pub const INPUT_CENTRES: [f64; RBF_INPUTS] = [50.0, 0.08, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0, -0.1, 0.0];
/// Scales s_i: 15 ft/s, 0.1 rad, 0.05 rad, 0.5 rad/s, 0.2 rad/s, 0.2 rad/s, 0.5, 0.1 rad,
/// 0.1 rad, 0.1 rad.
pub const INPUT_SCALES: [f64; RBF_INPUTS] = [15.0, 0.1, 0.05, 0.5, 0.2, 0.2, 0.5, 0.1, 0.1, 0.1];

/// What the basis functions are evaluated at (7.18).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RbfInput {
    /// V, ft/s.
    pub airspeed_fps: f64,
    /// α, rad.
    pub alpha_rad: f64,
    /// β, rad.
    pub beta_rad: f64,
    /// (p, q, r), rad/s.
    pub body_rates_rps: Vec3,
    /// Actuator positions.
    pub actuators: Controls,
}

impl RbfInput {
    /// The normalised input z.
    pub fn normalised(&self) -> [f64; RBF_INPUTS] {
        let raw = [
            self.airspeed_fps,
            self.alpha_rad,
            self.beta_rad,
            self.body_rates_rps.x,
            self.body_rates_rps.y,
            self.body_rates_rps.z,
            self.actuators.throttle,
            self.actuators.aileron_rad,
            self.actuators.elevator_rad,
            self.actuators.rudder_rad,
        ];
        let mut z = [0.0; RBF_INPUTS];
        for (i, zi) in z.iter_mut().enumerate() {
            *zi = (raw[i] - INPUT_CENTRES[i]) / INPUT_SCALES[i];
        }
        z
    }
}

/// The basis Φ (2.34): Φ_k(z) = exp(-‖z - z_k‖² / 2σ²).
#[derive(Debug, Clone, PartialEq)]
pub struct RbfBasis {
    centres: Vec<[f64; RBF_INPUTS]>,
    width: f64,
}

impl RbfBasis {
    /// The 21 centres of the module docs with width σ (normalised units, > 0).
    pub fn axis_star(width: f64) -> Self {
        let mut centres = vec![[0.0; RBF_INPUTS]];
        for axis in 0..RBF_INPUTS {
            for sign in [1.0, -1.0] {
                let mut c = [0.0; RBF_INPUTS];
                c[axis] = sign;
                centres.push(c);
            }
        }
        Self { centres, width }
    }

    /// Number of basis functions (the length of each weight vector).
    pub fn len(&self) -> usize {
        self.centres.len()
    }

    /// Whether the basis is empty (never, for [`Self::axis_star`]).
    pub fn is_empty(&self) -> bool {
        self.centres.is_empty()
    }

    /// Writes Φ(input) into `phi` (as many values as fit). A non-finite input gives Φ = 0 (no
    /// adaptation and no correction from a garbage sample).
    pub fn evaluate(&self, input: &RbfInput, phi: &mut [f64]) {
        let z = input.normalised();
        let finite = z.iter().all(|v| v.is_finite());
        let inv_two_sigma_sq = 0.5 / (self.width * self.width);
        for (out, centre) in phi.iter_mut().zip(&self.centres) {
            *out = if finite {
                let d2: f64 = z.iter().zip(centre).map(|(a, b)| (a - b) * (a - b)).sum();
                (-d2 * inv_two_sigma_sq).exp()
            } else {
                0.0
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trim_input() -> RbfInput {
        RbfInput {
            airspeed_fps: 50.0,
            alpha_rad: 0.08,
            beta_rad: 0.0,
            body_rates_rps: Vec3::zeros(),
            actuators: Controls {
                throttle: 0.5,
                elevator_rad: -0.1,
                aileron_rad: 0.0,
                rudder_rad: 0.0,
            },
        }
    }

    #[test]
    fn basis_peaks_at_its_centre() {
        let basis = RbfBasis::axis_star(1.0);
        assert_eq!(basis.len(), RBF_CENTRES);
        let mut phi = vec![0.0; basis.len()];
        basis.evaluate(&trim_input(), &mut phi);
        assert!((phi[0] - 1.0).abs() < 1e-15);
        // Every other centre is one unit away: e^{-1/2}.
        assert!(phi[1..].iter().all(|p| (p - (-0.5f64).exp()).abs() < 1e-12));
        let mut bad = trim_input();
        bad.alpha_rad = f64::NAN;
        basis.evaluate(&bad, &mut phi);
        assert!(phi.iter().all(|p| *p == 0.0));
    }
}
