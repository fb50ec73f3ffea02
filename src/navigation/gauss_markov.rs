//! The first-order process every error of the follower's navigation is built from
//! (docs/equations.md, The follower's own navigation and sensors):
//!
//! ```text
//! ẋ = (m - x) / τ + w,   E[w(t) w(s)] = (2 σ² / τ) δ(t - s)
//! ```
//!
//! with m held over a step: x relaxes toward m with time constant τ and, about it, is a
//! Gauss-Markov process of stationary standard deviation σ. It is stepped exactly (not by
//! Euler), so its statistics do not depend on the step.

/// A first-order Gauss-Markov process of time constant τ and stationary σ about its mean.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussMarkov {
    /// τ, s (> 0).
    pub time_constant_s: f64,
    /// Stationary standard deviation about the mean, in the state's unit (≥ 0).
    pub sigma: f64,
}

impl GaussMarkov {
    /// x(t + dt) from x(t) for the mean `mean` held over the step and a standard normal draw
    /// `normal`: m + e^(-dt/τ) (x - m) + σ √(1 - e^(-2 dt/τ)) n.
    pub fn step(&self, x: f64, mean: f64, dt_s: f64, normal: f64) -> f64 {
        let decay = (-dt_s / self.time_constant_s).exp();
        mean + decay * (x - mean) + self.sigma * (1.0 - decay * decay).sqrt() * normal
    }

    /// A draw from the stationary distribution about `mean` (a run starts in steady state).
    pub fn stationary(&self, mean: f64, normal: f64) -> f64 {
        mean + self.sigma * normal
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Without noise the process relaxes exactly as e^(-t/τ), whatever the step.
    #[test]
    fn relaxes_exponentially_for_any_step() {
        let p = GaussMarkov {
            time_constant_s: 2.0,
            sigma: 0.0,
        };
        for steps in [1, 10, 1000] {
            let dt = 2.0 / f64::from(steps);
            let mut x = 1.0;
            for _ in 0..steps {
                x = p.step(x, 3.0, dt, 0.0);
            }
            let expected = 3.0 + (1.0 - 3.0) * (-1.0f64).exp();
            assert!((x - expected).abs() < 1e-12, "{steps} steps: {x}");
        }
    }

    /// The stationary variance is kept by a step: (σ² e^(-2dt/τ) + σ²(1 - e^(-2dt/τ))).
    #[test]
    fn a_step_keeps_the_stationary_variance() {
        let p = GaussMarkov {
            time_constant_s: 0.5,
            sigma: 2.0,
        };
        let decay = (-0.1f64 / 0.5).exp();
        let from_state = p.step(1.0, 0.0, 0.1, 0.0) / 1.0;
        let from_noise = p.step(0.0, 0.0, 0.1, 1.0);
        let variance = (from_state * p.sigma).powi(2) + from_noise.powi(2);
        assert!((from_state - decay).abs() < 1e-15);
        assert!((variance - 4.0).abs() < 1e-12, "{variance}");
    }
}
