//! Gaussian radial basis functions (2.34) of the flight condition, and the ball projection of
//! Appendix A for weight vectors of any length (SPEC §3; the 3-vector version is
//! [`crate::guidance::projection::BallBound`], whose parameters are reused here).
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
use crate::guidance::projection::BallBound;
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

/// f(W) = (WᵀW - W_max²)/ε of the ball bound, for a weight vector of any length.
pub fn ball_f(bound: &BallBound, w: &[f64]) -> f64 {
    (dot(w, w) - bound.max_norm * bound.max_norm) / bound.epsilon
}

/// Proj(W, y) of Appendix A for the ball bound, in place on `y`: unchanged when f(W) < 0 or
/// ∇fᵀy ≤ 0, else y - ∇f ∇fᵀ y f(W) / ‖∇f‖² (∇f = 2W/ε, so the factor reduces to
/// (Wᵀy / WᵀW) f(W) W).
pub fn project_ball(bound: &BallBound, w: &[f64], y: &mut [f64]) {
    let f = ball_f(bound, w);
    let wy = dot(w, y);
    let ww = dot(w, w);
    if f < 0.0 || wy <= 0.0 || ww <= 0.0 {
        return;
    }
    let scale = wy * f / ww;
    for (yi, wi) in y.iter_mut().zip(w) {
        *yi -= scale * wi;
    }
}

/// Pulls W back onto Ω_1 = {‖W‖² ≤ W_max² + ε} after an integration step (the discrete
/// integrator can overshoot the continuous-time bound by one step).
pub fn clamp_ball(bound: &BallBound, w: &mut [f64]) {
    let outer = (bound.max_norm * bound.max_norm + bound.epsilon).sqrt();
    let norm = dot(w, w).sqrt();
    if norm > outer {
        let s = outer / norm;
        w.iter_mut().for_each(|wi| *wi *= s);
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
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

    /// The slice projection agrees with the 3-vector [`BallBound::project`] and keeps
    /// (W - W*)ᵀ(Proj - y) ≤ 0 for W* inside Ω_0.
    #[test]
    fn slice_projection_matches_vector_version() {
        let bound = BallBound {
            max_norm: 2.0,
            epsilon: 0.5,
        };
        let w = Vec3::new(1.6, 1.3, 0.3);
        assert!(ball_f(&bound, w.as_slice()) > 0.0);
        let y = Vec3::new(2.0, -0.5, 1.0);
        let mut y_slice = [y.x, y.y, y.z];
        project_ball(&bound, w.as_slice(), &mut y_slice);
        let expected = bound.project(&w, &y);
        assert!((Vec3::from(y_slice) - expected).norm() < 1e-12);
        let star = Vec3::new(-1.0, 0.5, 1.0);
        assert!((w - star).dot(&(expected - y)) <= 1e-12);
        let mut big = [10.0, 0.0, 0.0];
        clamp_ball(&bound, &mut big);
        assert!((big[0] - 4.5f64.sqrt()).abs() < 1e-12);
    }
}
