//! Compensation for a follower that does not realise the guidance's command (the 6-DOF
//! aircraft; beyond the seed, whose Chapters 4-6 follower flies the command exactly). With the
//! kinematic follower no law carries it and each is the seed's law unchanged.
//!
//! **Velocity law.** The adaptive laws (4.5) and the estimator (6.10) rest on ṙ = d - V_F/b. An
//! aircraft flies V_a ≠ V_F (its velocity lags the command by a second or two, its speed and turn
//! rate are bounded). Then the seed's gain k = 3.5 on the error makes the loop through the aircraft
//! oscillate, and the shortfall g - g_a, g_a = V_a/b̂ the realised scaled velocity, drives e: the
//! adaptation reads it as a wrong b̂ and d̂ and winds up (docs/findings.md, What the guidance and
//! control code rests on). The law therefore flies V_F = b̂ (k_F e + d̂ - ṙ_c) with a gentler k_F
//! (`guidance.k_aircraft`) and, with the follower's realised velocity V_a (its own navigation),
//! runs its adaptation on a compensated error, as command-filtered backstepping does (Farrell,
//! Polycarpou, Sharma and Dong, "Command filtered backstepping", IEEE TAC 54(6), 2009). The lag
//! error η obeys
//! ```text
//! η' = -k η + (k - k_F) e + (g - g_a),   ē = e - η   ⇒   ē' = -k ē + d̃ - (b̃/b) g_a
//! ```
//! (e the error the law feeds back: r̂ - r_c with the estimator, whose k r̃ term then also
//! follows (6.15)). ē has exactly the error dynamics, with the seed's k, that (4.5) and (6.16)
//! were derived for, so the adaptation runs on ē with g_a in place of g and the estimator
//! (6.10) on the realised velocity; the excitation's error energy is read from ē too.
//!
//! **Acceleration law.** Its design assumes the follower flies V_F = V_F(0) + ∫ a_F; an
//! aircraft's velocity V_a lags V_F by a second or two and is bounded. Left alone, the lag
//! enters y as if the target had manoeuvred, the observer, d̂ and b̂ chase it and a_F grows
//! until the follower loses the target. The follower's navigation gives the
//! shortfall s = V_F - V_a; its leaky integral, the lead ℓ' = s - ℓ/τ (ft), is how far the
//! follower is behind where a_F would have put it, recently. The law runs on y - ℓ/b̂, the
//! measurement as if the follower had realised its commands over the last τ; a shortfall that
//! lasts longer than τ (a climb the thrust cannot hold) shows in y and is corrected.

use crate::frames::Vec3;

/// The velocity law's compensation: the gain it feeds the error back with, and the lag error's
/// dynamics (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityLagCompensation {
    /// k, the seed's gain the adaptation's error dynamics are written for, 1/s.
    pub adaptation_gain_per_s: f64,
    /// k_F, the gain on the error in the V_F the follower is given, 1/s.
    pub feedback_gain_per_s: f64,
}

impl VelocityLagCompensation {
    /// η' = -k η + (k - k_F) e + (g - g_a), for the lag error η, the fed-back error e,
    /// the commanded scaled velocity g and the realised one g_a = V_a / b̂.
    pub fn lag_error_rate(
        &self,
        lag_error: &Vec3,
        error: &Vec3,
        commanded: &Vec3,
        realised: &Vec3,
    ) -> Vec3 {
        let k = self.adaptation_gain_per_s;
        -lag_error * k + error * (k - self.feedback_gain_per_s) + (commanded - realised)
    }
}

/// The acceleration law's compensation: the time constant of the shortfall's leaky integral
/// (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShortfallCompensation {
    /// τ, s.
    pub time_constant_s: f64,
}

impl ShortfallCompensation {
    /// y - ℓ/b̂: the measurement as if the follower had realised its commands over the last τ.
    pub fn measurement(&self, y: &Vec3, lead_ft: &Vec3, b_hat_ft: f64) -> Vec3 {
        y - lead_ft / b_hat_ft
    }

    /// ℓ' = s - ℓ/τ for the lead ℓ (ft) and the shortfall s = V_F - V_a (ft/s).
    pub fn lead_rate(&self, lead_ft: &Vec3, shortfall_ned_fps: &Vec3) -> Vec3 {
        shortfall_ned_fps - lead_ft / self.time_constant_s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A follower that realises the command (g_a = g) with k_F = k leaves the lag error at
    /// exactly zero, whatever the error: the law is then the seed's.
    #[test]
    fn exact_follower_needs_no_lag_error() {
        let c = VelocityLagCompensation {
            adaptation_gain_per_s: 3.5,
            feedback_gain_per_s: 3.5,
        };
        let g = Vec3::new(6.0, -1.0, 0.5);
        let rate = c.lag_error_rate(&Vec3::zeros(), &Vec3::new(0.3, -0.2, 0.1), &g, &g);
        assert_eq!(rate, Vec3::zeros());
        let s = ShortfallCompensation {
            time_constant_s: 2.0,
        };
        assert_eq!(s.lead_rate(&Vec3::zeros(), &Vec3::zeros()), Vec3::zeros());
        let y = Vec3::new(4.0, 1.0, 0.0);
        assert_eq!(s.measurement(&y, &Vec3::zeros(), 8.0), y);
    }

    /// One axis of ṙ = d - V_a/b with b̂ = b and d̂ = d known, r_c = 0: the law flies
    /// V_F = b (k_F e + d) and the follower's velocity lags it by a second. The error e decays
    /// at whatever rate the lag allows, but ē = e - η decays exactly as e^{-k t}, the error
    /// dynamics the seed's adaptation is written for.
    #[test]
    fn compensated_error_has_the_seeds_dynamics_behind_a_lag() {
        let c = VelocityLagCompensation {
            adaptation_gain_per_s: 3.5,
            feedback_gain_per_s: 0.5,
        };
        let (b, d, lag_s) = (8.0, 6.25, 1.0);
        // State [e, V_a, η] on the x axis.
        let f = |x: [f64; 3]| -> [f64; 3] {
            let [e, v_a, chi] = x;
            let g = c.feedback_gain_per_s * e + d;
            let g_a = v_a / b;
            let chi_rate = c.lag_error_rate(
                &Vec3::new(chi, 0.0, 0.0),
                &Vec3::new(e, 0.0, 0.0),
                &Vec3::new(g, 0.0, 0.0),
                &Vec3::new(g_a, 0.0, 0.0),
            );
            [d - g_a, (b * g - v_a) / lag_s, chi_rate.x]
        };
        let mut x = [1.0, 40.0, 0.0];
        let dt = 1e-3;
        for _ in 0..3000 {
            let k1 = f(x);
            let k2 = f(std::array::from_fn(|i| x[i] + 0.5 * dt * k1[i]));
            let k3 = f(std::array::from_fn(|i| x[i] + 0.5 * dt * k2[i]));
            let k4 = f(std::array::from_fn(|i| x[i] + dt * k3[i]));
            x = std::array::from_fn(|i| x[i] + dt / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]));
        }
        let expected = (-3.5f64 * 3.0).exp();
        assert!(((x[0] - x[2]) - expected).abs() < 1e-9, "{x:?}");
        assert!(
            (x[0] - expected).abs() > 0.1,
            "the lag does show in e itself: {x:?}"
        );
    }

    /// A steady shortfall s builds the lead up to s τ: the measurement is then read as if the
    /// follower were s τ further along, where its commands would have put it over the last τ.
    #[test]
    fn steady_shortfall_leads_by_s_tau() {
        let c = ShortfallCompensation {
            time_constant_s: 2.0,
        };
        let s = Vec3::new(0.0, 3.0, -1.0);
        let mut lead = Vec3::zeros();
        for _ in 0..40_000 {
            lead += c.lead_rate(&lead, &s) * 1e-3;
        }
        assert!((lead - s * 2.0).norm() < 1e-6, "{lead}");
        let y = Vec3::new(4.0, 1.0, 0.0);
        let corrected = c.measurement(&y, &lead, 8.0);
        assert!((corrected - (y - s * 2.0 / 8.0)).norm() < 1e-6);
    }
}
