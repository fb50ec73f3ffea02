//! The projection operator of Appendix A (Proj in (4.5); docs/equations.md, Velocity guidance
//! (Chapter 4)), for a scalar interval and a vector ball.
//!
//! For a convex f with Ω_c = {θ : f(θ) ≤ c}:
//! Proj(θ, y) = y if f(θ) < 0 or ∇fᵀy ≤ 0, else y - (∇f ∇fᵀ y / ‖∇f‖²) f(θ).
//! Ω_0 is the set the user bounds the estimate to; Ω_1 ⊃ Ω_0 is where the continuous-time
//! operator keeps it. A discrete integrator can overshoot ∂Ω_1 by one step, so every
//! integrated estimate is also clamped back into Ω_1 after each step (`clamp_*`): that is the
//! exact continuous-time property enforced at sampling instants.

use crate::frames::Vec3;

/// Interval bound Ω_0 = [min, max] of a scalar estimate, with tolerance ε:
/// f(b) = ((b - mid)² - half²) / ε, (A.1) specialised to one dimension.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntervalBound {
    /// Lower end of Ω_0.
    pub min: f64,
    /// Upper end of Ω_0.
    pub max: f64,
    /// ε > 0: Ω_1 is [mid - sqrt(half² + ε), mid + sqrt(half² + ε)].
    pub epsilon: f64,
}

impl IntervalBound {
    fn mid(&self) -> f64 {
        0.5 * (self.max + self.min)
    }

    fn half(&self) -> f64 {
        0.5 * (self.max - self.min)
    }

    /// f(b).
    pub fn f(&self, b: f64) -> f64 {
        ((b - self.mid()).powi(2) - self.half().powi(2)) / self.epsilon
    }

    /// Proj(b, y).
    pub fn project(&self, b: f64, y: f64) -> f64 {
        let f = self.f(b);
        let grad = 2.0 * (b - self.mid()) / self.epsilon;
        if f < 0.0 || grad * y <= 0.0 {
            y
        } else {
            // Scalar case of y - ∇f∇fᵀy f / ‖∇f‖²: y (1 - f).
            y * (1.0 - f)
        }
    }

    /// Half-width of Ω_1 about the midpoint.
    fn outer_half(&self) -> f64 {
        (self.half().powi(2) + self.epsilon).sqrt()
    }

    /// The nearest point of Ω_1.
    pub fn clamp(&self, b: f64) -> f64 {
        let h = self.outer_half();
        b.clamp(self.mid() - h, self.mid() + h)
    }
}

/// Ball bound Ω_0 = {d : ‖d‖ ≤ max_norm} with tolerance ε: f(d) = (dᵀd - max²)/ε.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallBound {
    /// Radius of Ω_0.
    pub max_norm: f64,
    /// ε > 0: Ω_1 is the ball of radius sqrt(max² + ε).
    pub epsilon: f64,
}

impl BallBound {
    /// f(d) for a vector of any length.
    pub fn f_slice(&self, d: &[f64]) -> f64 {
        (dot(d, d) - self.max_norm * self.max_norm) / self.epsilon
    }

    /// f(d).
    pub fn f(&self, d: &Vec3) -> f64 {
        self.f_slice(d.as_slice())
    }

    /// Proj(d, y) for vectors of any length, in place on `y`: unchanged when f(d) < 0 or
    /// ∇fᵀy ≤ 0, else y - ∇f ∇fᵀ y f(d) / ‖∇f‖² (∇f = 2d/ε, so the correction reduces to
    /// (dᵀy / dᵀd) f(d) d).
    pub fn project_slice(&self, d: &[f64], y: &mut [f64]) {
        let f = self.f_slice(d);
        let dy = dot(d, y);
        let dd = dot(d, d);
        if f < 0.0 || dy <= 0.0 || dd <= 0.0 {
            return;
        }
        let scale = dy * f / dd;
        for (yi, di) in y.iter_mut().zip(d) {
            *yi -= scale * di;
        }
    }

    /// Proj(d, y).
    pub fn project(&self, d: &Vec3, y: &Vec3) -> Vec3 {
        let mut out = *y;
        self.project_slice(d.as_slice(), out.as_mut_slice());
        out
    }

    /// Pulls a vector of any length back onto Ω_1 = {‖d‖² ≤ max² + ε}, in place.
    pub fn clamp_slice(&self, d: &mut [f64]) {
        let outer = (self.max_norm * self.max_norm + self.epsilon).sqrt();
        let norm = dot(d, d).sqrt();
        if norm > outer {
            let s = outer / norm;
            d.iter_mut().for_each(|di| *di *= s);
        }
    }

    /// The nearest point of Ω_1.
    pub fn clamp(&self, d: &Vec3) -> Vec3 {
        let mut out = *d;
        self.clamp_slice(out.as_mut_slice());
        out
    }
}

/// The projection bounds of a law's parameter estimates: b̂ in an interval, d̂ in a ball.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EstimateBounds {
    /// Bound of b̂.
    pub b: IntervalBound,
    /// Bound of d̂.
    pub d: BallBound,
}

impl EstimateBounds {
    /// b̂ and d̂ clamped back into Ω_1 (after an integration step).
    pub fn clamp(&self, b_hat: f64, d_hat: &Vec3) -> (f64, Vec3) {
        (self.b.clamp(b_hat), self.d.clamp(d_hat))
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::Rk4;
    use proptest::prelude::*;

    const B: IntervalBound = IntervalBound {
        min: 1.0,
        max: 30.0,
        epsilon: 1.0,
    };
    const D: BallBound = BallBound {
        max_norm: 20.0,
        epsilon: 1.0,
    };

    proptest! {
        /// (θ - θ*)ᵀ(Proj(θ, y) - y) ≤ 0 for θ* in Ω_0 and θ in Ω_1 (Appendix A, property 2).
        #[test]
        fn interval_projection_never_helps_the_error(b in -1.0f64..32.0, star in 1.0f64..30.0, y in -100.0f64..100.0) {
            let b = B.clamp(b);
            prop_assert!((b - star) * (B.project(b, y) - y) <= 1e-9);
        }

        #[test]
        fn ball_projection_never_helps_the_error(
            d in prop::array::uniform3(-25.0f64..25.0),
            star in prop::array::uniform3(-11.0f64..11.0),
            y in prop::array::uniform3(-100.0f64..100.0),
        ) {
            let d = D.clamp(&Vec3::from(d));
            let star = Vec3::from(star);
            let y = Vec3::from(y);
            prop_assert!((d - star).dot(&(D.project(&d, &y) - y)) <= 1e-9);
        }

        /// On ∂Ω_1 (f = 1) the projected direction is tangent or inward: ∇fᵀ Proj ≤ 0.
        #[test]
        fn ball_projection_is_tangent_on_outer_boundary(dir in prop::array::uniform3(-1.0f64..1.0), y in prop::array::uniform3(-100.0f64..100.0)) {
            let dir = Vec3::from(dir);
            prop_assume!(dir.norm() > 1e-3);
            let d = dir.normalize() * (D.max_norm.powi(2) + D.epsilon).sqrt();
            let p = D.project(&d, &Vec3::from(y));
            prop_assert!(d.dot(&p) <= 1e-9 * p.norm().max(1.0) * d.norm());
        }
    }

    /// An estimate integrated with huge adaptation steps pushing outward never leaves Ω_1.
    #[test]
    fn integrated_estimates_stay_in_outer_set() {
        let mut rk = Rk4::new(4);
        let mut x = [4.0, 0.0, 0.0, 0.0];
        let mut highest: f64 = 0.0;
        let dt = 0.05;
        for i in 0..2000 {
            let t = i as f64 * dt;
            rk.step(t, dt, &mut x, |t, x, dx| {
                let push = 1e4 * (1.0 + (3.0 * t).sin());
                dx[0] = B.project(x[0], push);
                let d = Vec3::new(x[1], x[2], x[3]);
                let y = Vec3::new(push, -push, 0.5 * push);
                let p = D.project(&d, &y);
                dx[1..4].copy_from_slice(p.as_slice());
            });
            x[0] = B.clamp(x[0]);
            let d = D.clamp(&Vec3::new(x[1], x[2], x[3]));
            x[1..4].copy_from_slice(d.as_slice());
            assert!(B.f(x[0]) <= 1.0 + 1e-12);
            highest = highest.max(x[0]);
            assert!(D.f(&d) <= 1.0 + 1e-12);
        }
        // The push did reach the boundary (the test is not passing by staying inside).
        assert!(highest > 30.0, "highest b = {highest}");
    }

    /// Inside Ω_0 the operator is the identity.
    #[test]
    fn identity_inside() {
        assert_eq!(B.project(10.0, 5.0), 5.0);
        let y = Vec3::new(1.0, 2.0, 3.0);
        assert_eq!(D.project(&Vec3::new(1.0, 1.0, 1.0), &y), y);
    }
}
