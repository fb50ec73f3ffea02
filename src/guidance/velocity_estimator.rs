//! The Chapter 6 state estimator of the velocity law (6.10)-(6.17): its gain L_v, fixed or
//! from the steady-state error covariance (6.33)-(6.36), and the matrix B_vᵀ P_v with which
//! (6.16) weighs the adaptation.

use crate::frames::Mat3;
use crate::linalg::{LinalgError, solve_continuous_lyapunov};
use nalgebra::{DMatrix, SMatrix};

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

#[cfg(test)]
mod tests {
    use super::*;

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
