//! `[acceleration]`: gains of the Chapter 5 acceleration guidance law and of its Chapter 6
//! observer-gain design (6.62). The projection bound of b̂ and b̂(0) are
//! shared with the velocity law and live in `[guidance]`; d̂, which is a filtered
//! acceleration bound in ft/s here and not a scaled velocity, is bounded here.

use serde::{Deserialize, Serialize};

use super::check::{self, Check};

/// Where the observer gain L of (5.10) comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ObserverGainMode {
    /// `observer_gain` as given (the seed's Chapter 5 and 6.3.4 simulations).
    Fixed,
    /// Steady-state Kalman gain from the Riccati equation (6.62) per axis, with the process
    /// noise Q_i = q B̄_i B̄_iᵀ and measurement noise K_n = r; falls back to `observer_gain`
    /// when the result breaks l_i1 ≥ λ_i or l_i2 > 0.
    Riccati,
}

/// `[acceleration]`: acceleration guidance (5.2)-(5.41) and Remark 6. The gains are the same
/// on the three axes, as in the seed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AccelerationSection {
    /// λ_i of the input filters ẇ = -λ w - a_F, ḋ = -λ d + a_T (5.3), rad/s (seed: 2).
    pub lambda_rps: f64,
    /// Reference-model gain K_i = [k_i1 (1/s), k_i2 (-)] of (5.6) (seed: [1.75, 0.5]).
    pub reference_gain: [f64; 2],
    /// Fixed observer gain L_i = [l_i1 (1/s), l_i2 (1/s²)] of (5.10) (seed: [2, 1.6]); also
    /// the fallback of the Riccati design.
    pub observer_gain: [f64; 2],
    /// Fixed gain or the Riccati design (6.62).
    pub observer_gain_mode: ObserverGainMode,
    /// Riccati process-noise intensity q (1/s), Q_i = q B̄_i B̄_iᵀ: the unknown input
    /// (1/b)(d + …) of ż = A z + (1/b) B̄ (w + d) treated as white noise. Default from the
    /// seed target's acceleration bound: (a_T,max / (λ b))² · 1 s = (π / 16)² ≈ 0.04.
    pub riccati_process_psd: f64,
    /// Riccati measurement-noise intensity K_n (s, scaled units² · s) of y* = r + n_r.
    /// Default: white noise at SNR 25 dB on |r| ≈ 4.1 (the seed's 33 ft command over 8 ft),
    /// variance 4.1²/3/10^2.5 per axis, sampled every 1 ms: ≈ 1.8e-5. With the default q this
    /// gives L ≈ [46, 89], far above the fixed [2, 1.6]; since the noise reaches a_F through
    /// ḣ = -K ż̂ (ż̂ ∋ L y*), that gain passes about seven times more noise to a_F. A larger
    /// r lowers it (r = 1e-3 gives L ≈ [5.4, 8.4]; r ≥ 1e-2 breaks l1 ≥ λ and falls back).
    pub riccati_noise_psd: f64,
    /// χ > 0, half-width of the smooth sign (5.31), scaled units (seed: 1.5).
    pub chi: f64,
    /// ρ ≥ 0, adaptation gain of b̂ (5.20). Not in the seed: 1 (see the scenario notes).
    pub rho: f64,
    /// G = gamma_d I ≥ 0, adaptation gain of d̂ (5.41). Not in the seed: 0.2.
    pub gamma_d: f64,
    /// a_f < 0, pole of the sign filter Ṡ_f = A_f (S_f - S_χ(y_a)) (5.34), A_f = a_f I,
    /// rad/s. Not in the seed: -10.
    pub sign_filter_pole_rps: f64,
    /// Projection bound of ‖d̂‖ (5.41), ft/s. Not in the seed: 20, loose against the seed
    /// target's filtered accelerations (|a_T| ≤ 3.2 ft/s², so |d_i| ≤ a_T/λ ≈ 1.6 ft/s).
    pub d_hat_max_fps: f64,
    /// Projection tolerance ε_d of f_d (Appendix A), ft²/s².
    pub d_hat_epsilon_fps2: f64,
    /// 6-DOF follower only (beyond the seed): time constant τ of the lead
    /// ℓ' = (V_F - V_a) - ℓ/τ, the leaky integral of the follower's velocity shortfall, s. The
    /// law reads y - ℓ/b̂, the measurement as if the follower had flown the V_F = ∫ a_F it was
    /// given, for the aircraft's lag; what persists longer than τ it sees and corrects (see
    /// `guidance::compensation`).
    pub shortfall_time_constant_s: f64,
}

impl Default for AccelerationSection {
    fn default() -> Self {
        Self {
            lambda_rps: 2.0,
            reference_gain: [1.75, 0.5],
            observer_gain: [2.0, 1.6],
            observer_gain_mode: ObserverGainMode::Fixed,
            riccati_process_psd: 0.04,
            riccati_noise_psd: 1.8e-5,
            chi: 1.5,
            rho: 1.0,
            gamma_d: 0.2,
            sign_filter_pole_rps: -10.0,
            d_hat_max_fps: 20.0,
            d_hat_epsilon_fps2: 1.0,
            shortfall_time_constant_s: 4.0,
        }
    }
}

impl AccelerationSection {
    /// Checks each value and the design conditions of Chapter 5: A_m Hurwitz and G_i(s) SPR
    /// (k_i1 > 0, k_i1 + λ_i k_i2 ≥ λ_i), A - L C Hurwitz with G_o(s) SPR (l_i1 ≥ λ_i,
    /// l_i2 > 0), a_f < 0.
    pub fn validate(&self) -> Check {
        let lambda = self.lambda_rps;
        check::positive("acceleration.lambda_rps", lambda)?;
        let [k1, k2] = self.reference_gain;
        check::require(
            k1.is_finite() && k1 > 0.0 && k2.is_finite(),
            "acceleration.reference_gain",
            format!("{:?}", self.reference_gain),
            "[k1, k2] finite with k1 > 0 (5.7)",
        )?;
        check::require(
            k1 + lambda * k2 >= lambda,
            "acceleration.reference_gain",
            format!("{:?}", self.reference_gain),
            format!("k1 + lambda_rps k2 >= lambda_rps = {lambda} (SPR reference model, (5.7))"),
        )?;
        let [l1, l2] = self.observer_gain;
        check::require(
            l1.is_finite() && l2.is_finite() && l1 >= lambda && l2 > 0.0,
            "acceleration.observer_gain",
            format!("{:?}", self.observer_gain),
            format!("[l1, l2] with l1 >= acceleration.lambda_rps = {lambda} and l2 > 0 (5.13)"),
        )?;
        check::positive("acceleration.riccati_process_psd", self.riccati_process_psd)?;
        check::positive("acceleration.riccati_noise_psd", self.riccati_noise_psd)?;
        check::positive("acceleration.chi", self.chi)?;
        check::non_negative("acceleration.rho", self.rho)?;
        check::non_negative("acceleration.gamma_d", self.gamma_d)?;
        check::positive("acceleration.d_hat_max_fps", self.d_hat_max_fps)?;
        check::positive("acceleration.d_hat_epsilon_fps2", self.d_hat_epsilon_fps2)?;
        check::in_closed(
            "acceleration.shortfall_time_constant_s",
            self.shortfall_time_constant_s,
            0.01,
            1000.0,
        )?;
        check::require(
            self.sign_filter_pole_rps.is_finite() && self.sign_filter_pole_rps < 0.0,
            "acceleration.sign_filter_pole_rps",
            self.sign_filter_pole_rps,
            "a finite number < 0 (5.34)",
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_defaults_are_valid() {
        assert_eq!(AccelerationSection::default().validate(), Ok(()));
    }

    /// Each design condition is checked and its message names key, value and range.
    #[test]
    fn design_conditions_name_key_and_range() {
        let cases: [(AccelerationSection, &str, &str); 5] = [
            (
                AccelerationSection {
                    observer_gain: [1.5, 1.6],
                    ..Default::default()
                },
                "acceleration.observer_gain",
                "l1 >= acceleration.lambda_rps = 2",
            ),
            (
                AccelerationSection {
                    reference_gain: [1.0, 0.2],
                    ..Default::default()
                },
                "acceleration.reference_gain",
                "SPR",
            ),
            (
                AccelerationSection {
                    sign_filter_pole_rps: 10.0,
                    ..Default::default()
                },
                "acceleration.sign_filter_pole_rps",
                "< 0",
            ),
            (
                AccelerationSection {
                    chi: 0.0,
                    ..Default::default()
                },
                "acceleration.chi",
                "> 0",
            ),
            (
                AccelerationSection {
                    lambda_rps: -2.0,
                    ..Default::default()
                },
                "acceleration.lambda_rps",
                "> 0",
            ),
        ];
        for (section, key, allowed) in cases {
            let err = section.validate().expect_err("invalid");
            assert_eq!(err.key, key);
            assert!(err.allowed.contains(allowed), "{}", err);
        }
    }

    /// The section parses from TOML, rejects unknown keys and round-trips.
    #[test]
    fn toml_round_trip_and_unknown_keys() {
        let parsed: AccelerationSection =
            toml::from_str("observer_gain_mode = \"riccati\"\nrho = 2.0\n").expect("valid");
        assert_eq!(parsed.observer_gain_mode, ObserverGainMode::Riccati);
        assert_eq!(parsed.rho, 2.0);
        assert_eq!(parsed.lambda_rps, 2.0);
        let text = toml::to_string(&parsed).expect("serialises");
        let again: AccelerationSection = toml::from_str(&text).expect("round trip");
        assert_eq!(parsed, again);
        assert!(toml::from_str::<AccelerationSection>("rhoo = 1.0").is_err());
    }
}
