//! Velocity guidance (Chapter 4, SPEC §4): V_F = b̂ g with adaptive estimates of the target's
//! size b̂ and scaled velocity d̂, a command-shaping filter, and optionally the state estimator
//! of Chapter 6 ((6.10)-(6.17)) for noisy measurements.
//!
//! State slice layout: `[b̂, d̂ (3), r_cf (3), r̂ (3, with the estimator), χ (3, with
//! compensation)]`.
//!
//! Compensation for a follower that does not realise V_F (the 6-DOF aircraft; beyond the
//! seed, whose Chapters 4-6 follower flies V_F exactly). The adaptive laws (4.5) and the
//! estimator (6.10) rest on ṙ = d - V_F/b. An aircraft flies V_a ≠ V_F (its velocity lags the
//! command by a second or two, its speed and turn rate are bounded). Then the seed's gain
//! k = 3.5 on the error makes the loop through the aircraft oscillate (measured: stable up to
//! k ≈ 0.5 with b̂ = b), and the shortfall g - g_a, g_a = V_a/b̂ the realised scaled velocity,
//! drives e: the adaptation reads it as a wrong b̂ and d̂ and winds up (measured: b̂ runs to
//! its bound within seconds and the follower loses the target). The law therefore flies
//! V_F = b̂ (k_F e + d̂ - ṙ_c) with a gentler k_F (`guidance.k_aircraft`) and, with the
//! follower's realised velocity V_a (its own navigation, as the delay compensation uses R_F),
//! runs its adaptation on a compensated error, as command-filtered backstepping does
//! (Farrell, Polycarpou, Sharma and Dong, "Command filtered backstepping", IEEE TAC 54(6),
//! 2009):
//! ```text
//! χ' = -k χ + (k - k_F) e + (g - g_a),   ē = e - χ   ⇒   ē' = -k ē + d̃ - (b̃/b) g_a
//! ```
//! (e the error the law feeds back: r̂ - r_c with the estimator, whose k r̃ term then also
//! follows (6.15)). ē has exactly the error dynamics, with the seed's k, that (4.5) and
//! (6.16) were derived for, so the adaptation runs on ē with g_a in place of g
//! (b̂' = σ Proj(g_aᵀ ē), d̂' = G Proj(ē), ξ*'s first block r* - r_c - χ) and the estimator
//! (6.10) on the realised velocity (r̂' = d̂ - g_a + L_v (r* - r̂)); the excitation's error
//! energy is read from ē too (the error the law answers for). With V_a = V_F and k_F = k
//! (kinematic follower) χ stays 0 and this is the seed's law.
//!
//! Command shaping: ṙ_cf = -p (r_cf - R_c/b̂) + Ṙ_c/b̂ from r_cf(0) = r(0). For the seed's
//! constant inertial R_c this is the seed's filter; a body-frame command (3.13) rotates with
//! the follower, and the feed-forward Ṙ_c/b̂ lets r_cf turn with it instead of lagging every
//! turn by 1/p = 10 s. (Shaping R_c/b̂ by an offset that decays instead would put the term
//! -b̂' R_c/b̂² of (4.15) into g, and with σ = 39 the loop b̂' → g → b̂' is singular once
//! eᵀR_c reaches b̂²/σ, an error of about 0.01.)

use super::law::GuidanceInput;
use super::projection::{BallBound, IntervalBound};
use crate::frames::{Mat3, Vec3};
use crate::linalg::{LinalgError, solve_continuous_lyapunov};
use crate::scenario::GuidanceSection;
use nalgebra::{DMatrix, SMatrix};

/// Offsets into the guidance state slice.
const B_HAT: usize = 0;
const D_HAT: usize = 1;
const R_CF: usize = 4;
const R_HAT: usize = 7;
/// Length of the law's state without estimator and compensation.
const BASE_LEN: usize = 7;

/// The Chapter 6 state estimator: gain L_v and the 3x6 matrix B_vᵀ P_v of (6.16)-(6.17).
#[derive(Debug, Clone, PartialEq)]
pub struct VelocityEstimator {
    /// Estimator gain L_v.
    pub gain: Mat3,
    /// B_vᵀ P_v with A_vᵀ P_v + P_v A_v = -Q_v.
    pub bt_p: SMatrix<f64, 3, 6>,
}

impl VelocityEstimator {
    /// Builds B_vᵀ P_v for A_v = [[-k I, k I], [0, -L_v]] (6.16) with Q_v = q_v I (6.17).
    ///
    /// The seed leaves Q_v free. P_v, and with it the adaptation signal B_vᵀ P_v ξ*_v of
    /// (6.16), scales with q_v: its e block is p_11 = q_v / (2k), so q_v = 2k makes (6.16)
    /// weigh e as (4.5) does (up to the r̃ terms), q_v = 1 weighs it 2k times less. That
    /// weight multiplies the measurement noise in ξ*_v as much as the error.
    pub fn new(k: f64, gain: Mat3, lyapunov_weight: f64) -> Result<Self, LinalgError> {
        let a = error_system_matrix(k, &gain);
        let p = solve_continuous_lyapunov(&a, &(DMatrix::identity(6, 6) * lyapunov_weight))?;
        let mut bt_p = SMatrix::<f64, 3, 6>::zeros();
        for i in 0..3 {
            for j in 0..6 {
                bt_p[(i, j)] = p[(i, j)] + p[(i + 3, j)];
            }
        }
        Ok(Self { gain, bt_p })
    }
}

/// Most fixed-point passes of [`steady_state_estimator_gain`] (it converges quadratically: a
/// handful from any positive start).
const MAX_GAIN_ITERATIONS: usize = 60;

/// A_v = [[-k I, k I], [0, -L_v]] of (6.15), 6x6.
fn error_system_matrix(k: f64, gain: &Mat3) -> DMatrix<f64> {
    let mut a = DMatrix::<f64>::zeros(6, 6);
    for i in 0..3 {
        a[(i, i)] = -k;
        a[(i, i + 3)] = k;
        for j in 0..3 {
            a[(i + 3, j + 3)] = -gain[(i, j)];
        }
    }
    a
}

/// The steady-state error covariance K_ξ of ξ_v = [e; r̃] (6.15) for the estimator gain L_v:
/// the solution of the Lyapunov equation (6.36)
/// 0 = A_v K_ξ + K_ξ A_vᵀ + D_v K_nr D_vᵀ + B_v q B_vᵀ, D_v = [0; L_v], B_v = [I; I],
/// with the parameters at their steady state (b̃ = d̃ = 0, Remark 8) and white noise of
/// intensities K_nr = `noise_psd` I (measurement) and q I (the disturbance δ).
pub fn steady_state_error_covariance(
    k: f64,
    gain: &Mat3,
    process_psd: f64,
    noise_psd: f64,
) -> Result<DMatrix<f64>, LinalgError> {
    let a = error_system_matrix(k, gain);
    let mut forcing = DMatrix::<f64>::zeros(6, 6);
    let noise = gain * gain.transpose() * noise_psd;
    for i in 0..3 {
        for j in 0..3 {
            forcing[(i + 3, j + 3)] = noise[(i, j)];
        }
        // B_v q B_vᵀ = q [[I, I], [I, I]].
        for (r, c) in [(i, i), (i, i + 3), (i + 3, i), (i + 3, i + 3)] {
            forcing[(r, c)] += process_psd;
        }
    }
    // solve_continuous_lyapunov solves Mᵀ P + P M = -Q; with M = A_vᵀ that is (6.36).
    solve_continuous_lyapunov(&a.transpose(), &forcing)
}

/// L_v from the steady-state covariance (Section 6.2.3): the gain that satisfies the
/// orthogonality condition (6.33)-(6.34), L_v = K_r K_nr⁻¹, with K_r = C_l K_ξ C_lᵀ the r̃ block
/// of the covariance (6.36) that this same L_v produces.
///
/// The seed's (6.36) forces the covariance with the measurement noise only; then every
/// L_v > 0 gives K_r = L_v K_nr / 2 and the only fixed point is L_v = 0 (no estimator). The
/// disturbance δ = V_T/b - d that the estimator must follow is the process noise that makes
/// the fixed point nontrivial, so it is included (intensity `process_psd`, B_δ = B_v in
/// (6.28)). The fixed point is found by iterating L ← K_r(L) K_nr⁻¹, one Lyapunov solve per
/// pass; per axis that is L ← (L² + q/K_nr) / (2L), Newton's iteration for
/// L_v = sqrt(q / K_nr) I, the steady-state Kalman gain of ṙ = (d - g) + δ, r* = r + n_r
/// (the Riccati equation 0 = q - K_r² / K_nr).
pub fn steady_state_estimator_gain(
    k: f64,
    process_psd: f64,
    noise_psd: f64,
) -> Result<Mat3, LinalgError> {
    if !(process_psd > 0.0 && noise_psd > 0.0 && k > 0.0) {
        return Err(LinalgError::Singular(format!(
            "the covariance design needs k, q and K_nr > 0 (k = {k}, q = {process_psd}, \
             K_nr = {noise_psd})"
        )));
    }
    let mut gain = Mat3::identity();
    for _ in 0..MAX_GAIN_ITERATIONS {
        let covariance = steady_state_error_covariance(k, &gain, process_psd, noise_psd)?;
        let next = Mat3::from_fn(|i, j| covariance[(i + 3, j + 3)] / noise_psd);
        let change = (next - gain).norm();
        gain = next;
        if change <= 1e-13 * gain.norm() {
            return Ok(gain);
        }
    }
    Err(LinalgError::Singular(format!(
        "L_v = K_r K_nr⁻¹ did not converge in {MAX_GAIN_ITERATIONS} passes"
    )))
}

/// The law's output at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityGuidanceOutput {
    /// Commanded follower velocity V_F = b̂ g, NED, ft/s.
    pub velocity_cmd_ned_fps: Vec3,
    /// The scaled command the law tracks (shaped, excitation included).
    pub r_command: Vec3,
    /// Tracking error e = r - r_command of the measurement.
    pub error: Vec3,
    /// The law's estimate of its tracking error: r̂ - r_command with the estimator (6.10),
    /// the measured error without it (zero while the target is lost).
    pub estimated_error: Vec3,
    /// χ, the part of the error due to the follower not realising V_F (zero without
    /// compensation).
    pub compensation: Vec3,
}

/// Velocity guidance (4.3)-(4.5), (4.14)-(4.15), (4.40), with optional estimator (6.10)-(6.17).
#[derive(Debug, Clone, PartialEq)]
pub struct VelocityGuidance {
    k: f64,
    sigma: f64,
    gamma_d: f64,
    b_bound: IntervalBound,
    d_bound: BallBound,
    shaping_pole_rps: f64,
    b0_ft: f64,
    d0: Vec3,
    estimator: Option<VelocityEstimator>,
    /// Offset of χ when the law compensates for a follower that does not realise V_F.
    compensation_at: Option<usize>,
    /// k_F, the gain on the error in V_F: k, or `k_aircraft` with compensation.
    feedback_gain: f64,
}

impl VelocityGuidance {
    /// The law a `[guidance]` section describes, with the estimator when given, and with the
    /// compensation for a follower that does not realise V_F when `compensated` (module docs).
    pub fn new(
        section: &GuidanceSection,
        estimator: Option<VelocityEstimator>,
        compensated: bool,
    ) -> Self {
        let estimator_len = if estimator.is_some() { 3 } else { 0 };
        Self {
            compensation_at: compensated.then_some(BASE_LEN + estimator_len),
            feedback_gain: if compensated {
                section.k_aircraft
            } else {
                section.k
            },
            k: section.k,
            sigma: section.sigma,
            gamma_d: section.gamma_d,
            b_bound: IntervalBound {
                min: section.b_min_ft,
                max: section.b_max_ft,
                epsilon: section.b_epsilon_ft2,
            },
            d_bound: BallBound {
                max_norm: section.d_max_per_s,
                epsilon: section.d_epsilon,
            },
            shaping_pole_rps: section.shaping_pole_rps,
            b0_ft: section.b0_ft,
            d0: Vec3::from(section.d0_per_s),
            estimator,
        }
    }

    /// Length of this law's state slice.
    pub fn state_len(&self) -> usize {
        BASE_LEN
            + if self.estimator.is_some() { 3 } else { 0 }
            + if self.compensation_at.is_some() { 3 } else { 0 }
    }

    /// Initial state: b̂(0), d̂(0); the shaping filter and the estimator start at the first
    /// measurement r(0).
    pub fn initial_state(&self, r0: &Vec3) -> Vec<f64> {
        let mut x = vec![0.0; self.state_len()];
        x[B_HAT] = self.b0_ft;
        x[D_HAT..D_HAT + 3].copy_from_slice(self.d0.as_slice());
        x[R_CF..R_CF + 3].copy_from_slice(r0.as_slice());
        if self.estimator.is_some() {
            x[R_HAT..R_HAT + 3].copy_from_slice(r0.as_slice());
        }
        x
    }

    /// Restarts the shaping filter and the estimator at the first measurement r(0), keeping
    /// b̂ and d̂ (a camera's first frame arrives after the run starts).
    pub fn start_at(&self, x: &mut [f64], r0: &Vec3) {
        x[R_CF..R_CF + 3].copy_from_slice(r0.as_slice());
        if self.estimator.is_some() {
            x[R_HAT..R_HAT + 3].copy_from_slice(r0.as_slice());
        }
    }

    /// Before the first measurement: no state moves and the follower cruises at V_F = b̂ d̂.
    pub fn idle(&self, x: &[f64], dx: &mut [f64]) -> VelocityGuidanceOutput {
        dx.fill(0.0);
        VelocityGuidanceOutput {
            velocity_cmd_ned_fps: vec3_at(x, D_HAT) * x[B_HAT],
            r_command: vec3_at(x, R_CF),
            error: Vec3::zeros(),
            estimated_error: Vec3::zeros(),
            compensation: self.compensation(x),
        }
    }

    /// χ of a state slice (zero without compensation).
    fn compensation(&self, x: &[f64]) -> Vec3 {
        self.compensation_at
            .map_or(Vec3::zeros(), |at| vec3_at(x, at))
    }

    /// b̂ of a state slice, ft.
    pub fn b_hat_ft(x: &[f64]) -> f64 {
        x[B_HAT]
    }

    /// d̂ of a state slice, 1/s.
    pub fn d_hat(x: &[f64]) -> Vec3 {
        vec3_at(x, D_HAT)
    }

    /// Writes ẋ into `dx` and returns the command. Mission formation or interception is set
    /// by the input: interception is R_c = 0 (4.40).
    pub fn derivative(
        &self,
        x: &[f64],
        input: &GuidanceInput,
        dx: &mut [f64],
    ) -> VelocityGuidanceOutput {
        let b_hat = x[B_HAT];
        let d_hat = vec3_at(x, D_HAT);
        let r_cf = vec3_at(x, R_CF);
        // The command in scaled units: a shaped part (filter state) plus what is added after
        // the filter; the parts given in ft are divided by b̂ (4.14): r_cmd = base + extra / b̂.
        let shaping = self.shaping_pole_rps > 0.0;
        let filter_rate = if shaping {
            (input.command_ned_ft / b_hat - r_cf) * self.shaping_pole_rps
                + input.command_rate_ned_fps / b_hat
        } else {
            Vec3::zeros()
        };
        let (base, base_rate, extra, extra_rate) = if shaping {
            (
                r_cf + input.excitation_scaled,
                filter_rate + input.excitation_scaled_rate,
                input.excitation_ned_ft,
                input.excitation_rate_ned_fps,
            )
        } else {
            (
                input.excitation_scaled,
                input.excitation_scaled_rate,
                input.command_ned_ft + input.excitation_ned_ft,
                input.command_rate_ned_fps + input.excitation_rate_ned_fps,
            )
        };
        let r_cmd = base + extra / b_hat;
        let r_used = match (&self.estimator, input.r_measured) {
            (Some(_), _) => vec3_at(x, R_HAT),
            (None, Some(r_star)) => r_star,
            (None, None) => r_cmd,
        };
        let e_used = r_used - r_cmd;
        // Compensation (module docs): the adaptation reads ē = e - χ.
        let chi = self.compensation(x);
        let adaptation_signal = match (&self.estimator, input.r_measured) {
            (_, None) => Vec3::zeros(),
            (Some(est), Some(r_star)) => {
                let mut xi = SMatrix::<f64, 6, 1>::zeros();
                xi.fixed_rows_mut::<3>(0).copy_from(&(r_star - r_cmd - chi));
                xi.fixed_rows_mut::<3>(3).copy_from(&(r_star - r_used));
                est.bt_p * xi
            }
            (None, Some(_)) => e_used - chi,
        };
        // g_a = V_a / b̂, the realised scaled velocity, when compensating.
        let realised = self
            .compensation_at
            .and(input.follower_velocity_ned_fps)
            .map(|v| v / b_hat);
        // ṙ_cmd contains -b̂' extra / b̂² (4.15) and b̂' depends on g: the algebraic loop is
        // closed by one fixed-point pass starting from b̂' = 0.
        let guidance = |b_hat_rate: f64| -> Vec3 {
            let r_cmd_rate =
                base_rate + extra_rate / b_hat - extra * (b_hat_rate / (b_hat * b_hat));
            e_used * self.feedback_gain + d_hat - r_cmd_rate
        };
        let b_rate_of = |g: &Vec3| {
            let g_a = realised.unwrap_or(*g);
            self.sigma * self.b_bound.project(b_hat, g_a.dot(&adaptation_signal))
        };
        let b_hat_rate = b_rate_of(&guidance(0.0));
        let g = guidance(b_hat_rate);
        let b_hat_rate = b_rate_of(&g);
        let g_a = realised.unwrap_or(g);
        if let Some(at) = self.compensation_at {
            let chi_rate = -chi * self.k + e_used * (self.k - self.feedback_gain) + (g - g_a);
            dx[at..at + 3].copy_from_slice(chi_rate.as_slice());
        }

        dx[B_HAT] = b_hat_rate;
        let d_rate = self.d_bound.project(&d_hat, &adaptation_signal) * self.gamma_d;
        dx[D_HAT..D_HAT + 3].copy_from_slice(d_rate.as_slice());
        dx[R_CF..R_CF + 3].copy_from_slice(filter_rate.as_slice());
        if let Some(est) = &self.estimator {
            // (6.10): r̂' = d̂ - g + L_v (r* - r̂), with g_a when compensating.
            let innovation = input
                .r_measured
                .map_or(Vec3::zeros(), |r_star| r_star - r_used);
            let r_hat_rate = d_hat - g_a + est.gain * innovation;
            dx[R_HAT..R_HAT + 3].copy_from_slice(r_hat_rate.as_slice());
        }
        VelocityGuidanceOutput {
            velocity_cmd_ned_fps: g * b_hat,
            r_command: r_cmd,
            error: input.r_measured.unwrap_or(r_used) - r_cmd - chi,
            estimated_error: e_used - chi,
            compensation: chi,
        }
    }

    /// Clamps b̂ and d̂ back into Ω_1 after an integration step (see [`super::projection`]).
    pub fn enforce_bounds(&self, x: &mut [f64]) {
        x[B_HAT] = self.b_bound.clamp(x[B_HAT]);
        let d = self.d_bound.clamp(&vec3_at(x, D_HAT));
        x[D_HAT..D_HAT + 3].copy_from_slice(d.as_slice());
    }
}

/// The 3-vector stored at `x[at..at + 3]`.
pub(crate) fn vec3_at(x: &[f64], at: usize) -> Vec3 {
    Vec3::new(x[at], x[at + 1], x[at + 2])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(r: Vec3) -> GuidanceInput {
        GuidanceInput::steady(r, Vec3::new(32.0, 8.0, 0.0))
    }

    /// With the error at zero and d̂ = d, the follower flies the target's velocity b d and no
    /// estimate moves.
    #[test]
    fn at_equilibrium_nothing_moves() {
        let section = GuidanceSection {
            shaping_pole_rps: 0.0,
            b0_ft: 8.0,
            d0_per_s: [6.25, 0.0, 0.0],
            ..GuidanceSection::default()
        };
        let law = VelocityGuidance::new(&section, None, false);
        let r_c = Vec3::new(32.0, 8.0, 0.0) / 8.0;
        let x = law.initial_state(&r_c);
        let mut dx = vec![0.0; law.state_len()];
        let out = law.derivative(&x, &input(r_c), &mut dx);
        assert!((out.velocity_cmd_ned_fps - Vec3::new(50.0, 0.0, 0.0)).norm() < 1e-12);
        assert!(dx.iter().all(|v| v.abs() < 1e-12), "{dx:?}");
    }

    /// Sign check of (4.6): with a positive error along x the follower speeds up along x.
    #[test]
    fn error_ahead_speeds_up() {
        let section = GuidanceSection {
            d0_per_s: [0.0; 3],
            ..GuidanceSection::default()
        };
        let law = VelocityGuidance::new(&section, None, false);
        let r = Vec3::new(10.0, 2.0, 0.0);
        let mut x = law.initial_state(&r);
        x[R_CF..R_CF + 3].copy_from_slice(Vec3::new(8.0, 2.0, 0.0).as_slice());
        let mut dx = vec![0.0; law.state_len()];
        let out = law.derivative(&x, &input(r), &mut dx);
        assert!(out.velocity_cmd_ned_fps.x > 0.0);
        assert!(dx[D_HAT] > 0.0);
    }

    /// The estimator's B_vᵀ P_v comes from a Lyapunov solution with a small residual.
    #[test]
    fn estimator_matrix_is_consistent() {
        let est = VelocityEstimator::new(3.5, Mat3::identity() * 1.7, 1.0).expect("solvable");
        // Per axis: p11 + p21 and p12 + p22 (see linalg's closed form).
        let (k, l) = (3.5, 1.7);
        let p11 = 1.0 / (2.0 * k);
        let p12 = k * p11 / (k + l);
        let p22 = (1.0 + 2.0 * k * p12) / (2.0 * l);
        assert!((est.bt_p[(0, 0)] - (p11 + p12)).abs() < 1e-12);
        assert!((est.bt_p[(0, 3)] - (p12 + p22)).abs() < 1e-12);
        assert!(est.bt_p[(0, 1)].abs() < 1e-12);
        // P_v scales with Q_v = q_v I.
        let scaled = VelocityEstimator::new(3.5, Mat3::identity() * 1.7, 7.0).expect("solvable");
        assert!((scaled.bt_p - est.bt_p * 7.0).norm() < 1e-12);
    }

    /// The covariance design reaches its fixed point: L_v = K_r(L_v) K_nr⁻¹ with the covariance
    /// solving (6.36) to a relative residual below 1e-9, and L_v equals the steady-state
    /// Kalman gain sqrt(q / K_nr) I that the Riccati solver gives for ṙ = δ, r* = r + n_r.
    #[test]
    fn covariance_gain_is_the_kalman_gain() {
        let (k, q, r) = (3.5, 0.01, 1.8e-5);
        let gain = steady_state_estimator_gain(k, q, r).expect("converges");
        let expected = (q / r).sqrt();
        assert!(
            (gain - Mat3::identity() * expected).norm() < 1e-9 * expected,
            "{gain}"
        );
        let covariance = steady_state_error_covariance(k, &gain, q, r).expect("solvable");
        for i in 0..3 {
            assert!((covariance[(i + 3, i + 3)] / r - gain[(i, i)]).abs() < 1e-9 * expected);
        }
        // Residual of (6.36) itself.
        let a = error_system_matrix(k, &gain);
        let mut forcing = DMatrix::<f64>::zeros(6, 6);
        for i in 0..3 {
            forcing[(i + 3, i + 3)] = expected * expected * r;
            for (row, col) in [(i, i), (i, i + 3), (i + 3, i), (i + 3, i + 3)] {
                forcing[(row, col)] += q;
            }
        }
        assert!(crate::linalg::lyapunov_residual(&a.transpose(), &covariance, &forcing) < 1e-9);
        // The same gain from the algebraic Riccati equation of the estimation error.
        let zero = DMatrix::<f64>::zeros(3, 3);
        let identity = DMatrix::<f64>::identity(3, 3);
        let riccati = crate::linalg::solve_continuous_are(
            &zero,
            &identity,
            &(&identity * q),
            &(&identity * r),
        )
        .expect("solvable");
        assert!((riccati.gain[(1, 1)] - expected).abs() < 1e-9 * expected);
    }

    /// The seed's 1.7 I is the covariance gain for q / K_nr = 1.7²; without the disturbance
    /// term the design has no estimator to offer and says so.
    #[test]
    fn covariance_gain_needs_positive_intensities() {
        let gain = steady_state_estimator_gain(3.5, 1.7 * 1.7 * 1e-4, 1e-4).expect("converges");
        assert!((gain[(2, 2)] - 1.7).abs() < 1e-12 && gain[(0, 1)].abs() < 1e-15);
        assert!(steady_state_estimator_gain(3.5, 0.0, 1e-4).is_err());
    }
}
