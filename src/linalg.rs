//! Matrix equations the guidance design needs, on nalgebra matrices.

use nalgebra::DMatrix;

/// Why a matrix equation could not be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinalgError {
    /// The matrices' shapes do not fit the equation.
    #[error("matrix shapes do not fit: {0}")]
    Shape(String),
    /// The equation has no unique solution (e.g. A has eigenvalues λi + λj = 0).
    #[error("the equation has no unique solution: {0}")]
    Singular(String),
    /// A Riccati equation has no stabilising solution (an unobservable or undetectable mode,
    /// or Hamiltonian eigenvalues on the imaginary axis), or a weight is not definite.
    #[error("no stabilising solution: {0}")]
    NoStabilisingSolution(String),
}

/// Solves the continuous Lyapunov equation Aᵀ P + P A = -Q for P (used for P_v in (6.16) with
/// A = A_v). Solved as the Kronecker-product linear system (I ⊗ Aᵀ + Aᵀ ⊗ I) vec P = -vec Q,
/// which suits the small (≤ 12x12) matrices of the guidance laws. The result is symmetrised.
pub fn solve_continuous_lyapunov(
    a: &DMatrix<f64>,
    q: &DMatrix<f64>,
) -> Result<DMatrix<f64>, LinalgError> {
    let n = a.nrows();
    if a.ncols() != n || q.nrows() != n || q.ncols() != n {
        return Err(LinalgError::Shape(format!(
            "A is {}x{}, Q is {}x{}",
            a.nrows(),
            a.ncols(),
            q.nrows(),
            q.ncols()
        )));
    }
    let at = a.transpose();
    let identity = DMatrix::<f64>::identity(n, n);
    let system = identity.kronecker(&at) + at.kronecker(&identity);
    let rhs = -DMatrix::from_column_slice(n * n, 1, q.as_slice());
    let solution = system
        .lu()
        .solve(&rhs)
        .ok_or_else(|| LinalgError::Singular("Aᵀ P + P A = -Q".to_string()))?;
    let p = DMatrix::from_column_slice(n, n, solution.as_slice());
    Ok((&p + p.transpose()) * 0.5)
}

/// Relative residual ‖Aᵀ P + P A + Q‖ / ‖Q‖ of a Lyapunov solution.
pub fn lyapunov_residual(a: &DMatrix<f64>, p: &DMatrix<f64>, q: &DMatrix<f64>) -> f64 {
    (a.transpose() * p + p * a + q).norm() / q.norm()
}

/// The stabilising solution X of a filter-form algebraic Riccati equation and its gain.
#[derive(Debug, Clone, PartialEq)]
pub struct RiccatiSolution {
    /// X = Xᵀ ≥ 0, the steady-state estimation-error covariance (K_z of (6.62)).
    pub x: DMatrix<f64>,
    /// L = X Cᵀ R⁻¹, the steady-state estimator gain (L_a of (6.62)); A - L C is Hurwitz.
    pub gain: DMatrix<f64>,
}

/// Most iterations of the matrix-sign Newton iteration (it converges in 10-20 from the
/// scaled start; more means eigenvalues on or near the imaginary axis).
const SIGN_MAX_ITERATIONS: usize = 100;
/// Newton-Kleinman refinement steps after the sign-function solution (quadratic convergence:
/// two steps take a 1e-8 start to round-off).
const KLEINMAN_STEPS: usize = 3;

/// Solves the filter-form continuous algebraic Riccati equation (6.62) with a process-noise
/// term,
/// ```text
/// 0 = A X + X Aᵀ - X Cᵀ R⁻¹ C X + Q,      L = X Cᵀ R⁻¹,
/// ```
/// for its stabilising solution (A - L C Hurwitz). A is n×n, C is p×n, Q n×n symmetric ≥ 0
/// and R p×p symmetric > 0.
///
/// Method: the stable invariant subspace [I; X] of the Hamiltonian
/// H = [[Aᵀ, -Cᵀ R⁻¹ C], [-Q, -A]] (the dual control-form equation) from the matrix sign
/// function W = sign(H) (Newton iteration with determinant scaling, Roberts/Byers): (W + I)
/// annihilates the stable subspace, so [W12; W22 + I] X = -[W11 + I; W21] (least squares).
/// The result is then polished with Newton-Kleinman steps, each a Lyapunov equation for the
/// closed loop A - L_k C (stabilising from the sign-function start). No stabilising start is
/// needed from the caller.
///
/// Errors: [`LinalgError::Shape`] for mismatched sizes, [`LinalgError::NoStabilisingSolution`]
/// when R is not positive definite, H has eigenvalues on the imaginary axis, the subspace is
/// not a graph [I; X] (an undetectable mode), or the result fails to stabilise A - L C.
pub fn solve_continuous_are(
    a: &DMatrix<f64>,
    c: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
) -> Result<RiccatiSolution, LinalgError> {
    check_riccati_shapes(a, c, q, r)?;
    let n = a.nrows();
    let r_inv = r
        .clone()
        .cholesky()
        .ok_or_else(|| LinalgError::NoStabilisingSolution("R is not positive definite".into()))?
        .inverse();
    let g = c.transpose() * &r_inv * c;
    let mut h = DMatrix::<f64>::zeros(2 * n, 2 * n);
    h.view_mut((0, 0), (n, n)).copy_from(&a.transpose());
    h.view_mut((0, n), (n, n)).copy_from(&(-&g));
    h.view_mut((n, 0), (n, n)).copy_from(&(-q));
    h.view_mut((n, n), (n, n)).copy_from(&(-a));
    let w = matrix_sign(h)?;
    let identity = DMatrix::<f64>::identity(n, n);
    let mut lhs = DMatrix::<f64>::zeros(2 * n, n);
    lhs.view_mut((0, 0), (n, n))
        .copy_from(&w.view((0, n), (n, n)));
    lhs.view_mut((n, 0), (n, n))
        .copy_from(&(w.view((n, n), (n, n)) + &identity));
    let mut rhs = DMatrix::<f64>::zeros(2 * n, n);
    rhs.view_mut((0, 0), (n, n))
        .copy_from(&(-(w.view((0, 0), (n, n)) + &identity)));
    rhs.view_mut((n, 0), (n, n))
        .copy_from(&(-w.view((n, 0), (n, n))));
    let svd = lhs.svd(true, true);
    let largest = svd.singular_values.max();
    if svd.singular_values.min() <= 1e-10 * largest.max(1.0) {
        return Err(LinalgError::NoStabilisingSolution(
            "the stable subspace of the Hamiltonian is not a graph [I; X]".into(),
        ));
    }
    let x = svd
        .solve(&rhs, 0.0)
        .map_err(|e| LinalgError::NoStabilisingSolution(e.to_string()))?;
    let mut x = (&x + x.transpose()) * 0.5;
    for _ in 0..KLEINMAN_STEPS {
        match kleinman_step(a, c, q, r, &r_inv, &x) {
            Ok(next) => x = next,
            Err(_) => break,
        }
    }
    let gain = &x * c.transpose() * &r_inv;
    if !is_hurwitz(&(a - &gain * c)) {
        return Err(LinalgError::NoStabilisingSolution(
            "A - L C is not Hurwitz".into(),
        ));
    }
    Ok(RiccatiSolution { x, gain })
}

/// Relative residual of a filter-form Riccati solution:
/// ‖A X + X Aᵀ - X Cᵀ R⁻¹ C X + Q‖ / (‖Q‖ + 2‖A X‖ + ‖X Cᵀ R⁻¹ C X‖) (Frobenius norms; the
/// denominator is the size of the terms that cancel, so the ratio is meaningful for Q = 0).
pub fn riccati_residual(
    a: &DMatrix<f64>,
    c: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    x: &DMatrix<f64>,
) -> f64 {
    let Some(r_inv) = r.clone().try_inverse() else {
        return f64::INFINITY;
    };
    let ax = a * x;
    let quadratic = x * c.transpose() * r_inv * c * x;
    let residual = &ax + ax.transpose() - &quadratic + q;
    let scale = q.norm() + 2.0 * ax.norm() + quadratic.norm();
    if scale == 0.0 {
        residual.norm()
    } else {
        residual.norm() / scale
    }
}

fn check_riccati_shapes(
    a: &DMatrix<f64>,
    c: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
) -> Result<(), LinalgError> {
    let n = a.nrows();
    let p = c.nrows();
    let fits = n > 0
        && a.ncols() == n
        && c.ncols() == n
        && q.shape() == (n, n)
        && r.shape() == (p, p)
        && p > 0;
    if fits {
        Ok(())
    } else {
        Err(LinalgError::Shape(format!(
            "A is {:?}, C is {:?}, Q is {:?}, R is {:?}; need A n×n, C p×n, Q n×n, R p×p",
            a.shape(),
            c.shape(),
            q.shape(),
            r.shape()
        )))
    }
}

/// sign(H) by the scaled Newton iteration Z ← (c Z + (c Z)⁻¹) / 2, c = |det Z|^(-1/m).
fn matrix_sign(mut z: DMatrix<f64>) -> Result<DMatrix<f64>, LinalgError> {
    let m = z.nrows() as f64;
    let on_axis = || {
        LinalgError::NoStabilisingSolution("the Hamiltonian has imaginary-axis eigenvalues".into())
    };
    for _ in 0..SIGN_MAX_ITERATIONS {
        let lu = z.clone().lu();
        let det = lu.determinant().abs();
        let inverse = lu.try_inverse().ok_or_else(on_axis)?;
        let scale = if det.is_finite() && det > 0.0 {
            det.powf(-1.0 / m)
        } else {
            1.0
        };
        let next = (&z * scale + inverse / scale) * 0.5;
        let change = (&next - &z).norm();
        let size = next.norm();
        z = next;
        if !size.is_finite() {
            break;
        }
        if change <= 1e-13 * size {
            return Ok(z);
        }
    }
    Err(on_axis())
}

/// One Newton-Kleinman step: with L = X Cᵀ R⁻¹ and A_L = A - L C, the next X solves
/// A_L X + X A_Lᵀ = -(Q + L R Lᵀ).
fn kleinman_step(
    a: &DMatrix<f64>,
    c: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    r_inv: &DMatrix<f64>,
    x: &DMatrix<f64>,
) -> Result<DMatrix<f64>, LinalgError> {
    let l = x * c.transpose() * r_inv;
    let closed = a - &l * c;
    if !is_hurwitz(&closed) {
        return Err(LinalgError::NoStabilisingSolution(
            "Kleinman start is not stabilising".into(),
        ));
    }
    let weight = q + &l * r * l.transpose();
    // solve_continuous_lyapunov solves Mᵀ P + P M = -W; M = A_Lᵀ gives the filter form.
    solve_continuous_lyapunov(&closed.transpose(), &weight)
}

/// Every eigenvalue has a negative real part.
pub fn is_hurwitz(a: &DMatrix<f64>) -> bool {
    a.is_square()
        && a.clone()
            .complex_eigenvalues()
            .iter()
            .all(|e| e.re < 0.0 && e.re.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Scalar case: 2 a p = -q.
    #[test]
    fn scalar_closed_form() {
        let p = solve_continuous_lyapunov(
            &DMatrix::from_element(1, 1, -2.0),
            &DMatrix::from_element(1, 1, 3.0),
        )
        .expect("solvable");
        assert!((p[(0, 0)] - 0.75).abs() < 1e-15);
    }

    /// The velocity-estimator matrix A_v of (6.16) for one axis (k = 3.5, L_v = 1.7), Q = I,
    /// has the closed form p11 = 1/(2k), p12 = k p11/(k + L), p22 = (1 + 2k p12)/(2L).
    #[test]
    fn velocity_estimator_matrix() {
        let (k, l) = (3.5, 1.7);
        let a = DMatrix::from_row_slice(2, 2, &[-k, k, 0.0, -l]);
        let q = DMatrix::identity(2, 2);
        let p = solve_continuous_lyapunov(&a, &q).expect("Hurwitz A");
        assert!(lyapunov_residual(&a, &p, &q) < 1e-12);
        assert!((p[(0, 0)] - 1.0 / (2.0 * k)).abs() < 1e-12);
        let p12 = k * p[(0, 0)] / (k + l);
        assert!((p[(0, 1)] - p12).abs() < 1e-12);
        assert!((p[(1, 1)] - (1.0 + 2.0 * k * p12) / (2.0 * l)).abs() < 1e-12);
        assert!(p.clone().cholesky().is_some());
    }

    /// A random-ish stable 6x6 system: residual below 1e-9.
    #[test]
    fn residual_of_larger_system() {
        let a = DMatrix::from_fn(6, 6, |i, j| {
            if i == j {
                -3.0 - i as f64
            } else {
                ((i * 7 + j * 3) % 5) as f64 * 0.2 - 0.4
            }
        });
        let q = DMatrix::from_fn(6, 6, |i, j| if i == j { 2.0 } else { 0.1 });
        let p = solve_continuous_lyapunov(&a, &q).expect("stable");
        assert!(lyapunov_residual(&a, &p, &q) < 1e-9);
    }

    #[test]
    fn singular_and_shape_errors() {
        let a = DMatrix::zeros(2, 2);
        assert!(matches!(
            solve_continuous_lyapunov(&a, &DMatrix::identity(2, 2)),
            Err(LinalgError::Singular(_))
        ));
        assert!(matches!(
            solve_continuous_lyapunov(&a, &DMatrix::identity(3, 3)),
            Err(LinalgError::Shape(_))
        ));
    }

    fn m(rows: usize, cols: usize, values: &[f64]) -> DMatrix<f64> {
        DMatrix::from_row_slice(rows, cols, values)
    }

    /// Scalar filter ARE 2 a x - x² c²/r + q = 0: x = r (a + sqrt(a² + c² q / r)) / c².
    /// Tested with an unstable a = 1 (the stabilising root is the positive one) and a stable
    /// a = -2. Tolerance 1e-12: a handful of well-conditioned flops.
    #[test]
    fn scalar_closed_form_are() {
        for (a, c, q, r) in [(1.0, 2.0, 3.0, 0.5), (-2.0, 1.0, 0.7, 2.0)] {
            let sol = solve_continuous_are(
                &m(1, 1, &[a]),
                &m(1, 1, &[c]),
                &m(1, 1, &[q]),
                &m(1, 1, &[r]),
            )
            .expect("solvable");
            let x = r * (a + (a * a + c * c * q / r).sqrt()) / (c * c);
            assert!(
                (sol.x[(0, 0)] - x).abs() < 1e-12 * x.max(1.0),
                "{} vs {x}",
                sol.x[(0, 0)]
            );
            assert!((sol.gain[(0, 0)] - x * c / r).abs() < 1e-12 * x.max(1.0));
        }
    }

    /// Double integrator with process noise q on the acceleration, position measured with
    /// noise intensity r: with α = (q/r)^(1/4), x11 = √2 α r, x12 = α² r, x22 = √2 α³ r and
    /// L = [√2 α, α²]ᵀ (derived by substituting into the three scalar equations).
    #[test]
    fn double_integrator_known_answer() {
        let (q, r) = (0.3, 0.02);
        let a = m(2, 2, &[0.0, 1.0, 0.0, 0.0]);
        let c = m(1, 2, &[1.0, 0.0]);
        let qm = m(2, 2, &[0.0, 0.0, 0.0, q]);
        let rm = m(1, 1, &[r]);
        let sol = solve_continuous_are(&a, &c, &qm, &rm).expect("observable, stabilisable");
        let alpha = (q / r).powf(0.25);
        let expected = m(
            2,
            2,
            &[
                2f64.sqrt() * alpha * r,
                alpha * alpha * r,
                alpha * alpha * r,
                2f64.sqrt() * alpha.powi(3) * r,
            ],
        );
        assert!(
            (&sol.x - &expected).norm() < 1e-12 * expected.norm(),
            "{}",
            sol.x
        );
        assert!((sol.gain[(0, 0)] - 2f64.sqrt() * alpha).abs() < 1e-11);
        assert!((sol.gain[(1, 0)] - alpha * alpha).abs() < 1e-11);
        assert!(riccati_residual(&a, &c, &qm, &rm, &sol.x) < 1e-12);
    }

    /// A 6-state, 2-output system with an unstable mode: relative residual below 1e-9, X
    /// symmetric positive semidefinite, A - L C Hurwitz.
    #[test]
    fn larger_system_residual_and_stability() {
        let a = DMatrix::from_fn(6, 6, |i, j| {
            if i == j {
                if i == 0 { 0.5 } else { -1.0 - i as f64 }
            } else {
                ((i * 5 + j * 3) % 7) as f64 * 0.15 - 0.4
            }
        });
        let c = DMatrix::from_fn(2, 6, |i, j| if (i + j) % 3 == 0 { 1.0 } else { 0.2 });
        let q = DMatrix::from_fn(
            6,
            6,
            |i, j| if i == j { 1.0 + 0.1 * i as f64 } else { 0.05 },
        );
        let r = m(2, 2, &[0.1, 0.02, 0.02, 0.3]);
        let sol = solve_continuous_are(&a, &c, &q, &r).expect("solvable");
        assert!(riccati_residual(&a, &c, &q, &r, &sol.x) < 1e-9);
        assert!((&sol.x - sol.x.transpose()).norm() < 1e-12 * sol.x.norm());
        assert!(sol.x.symmetric_eigenvalues().min() > -1e-12);
        assert!(is_hurwitz(&(&a - &sol.gain * &c)));
    }

    /// (6.62) as the seed writes it, without Q, for a Hurwitz A_m: the stabilising solution is
    /// X = 0 (no process noise, nothing to estimate), so L = 0. This is why the simulator
    /// adds the process-noise term Q.
    #[test]
    fn no_process_noise_and_hurwitz_a_gives_zero_gain() {
        let a = m(2, 2, &[-1.75, 0.5, -3.5, -1.0]);
        let c = m(1, 2, &[1.0, 0.0]);
        let sol = solve_continuous_are(&a, &c, &DMatrix::zeros(2, 2), &m(1, 1, &[0.01]))
            .expect("X = 0 is stabilising");
        assert!(sol.x.norm() < 1e-12 && sol.gain.norm() < 1e-10, "{}", sol.x);
    }

    #[test]
    fn riccati_shape_and_solvability_errors() {
        let a = m(2, 2, &[0.0, 1.0, 0.0, 0.0]);
        let c = m(1, 2, &[1.0, 0.0]);
        let q = DMatrix::identity(2, 2);
        let r = m(1, 1, &[1.0]);
        assert!(matches!(
            solve_continuous_are(&a, &c, &DMatrix::identity(3, 3), &r),
            Err(LinalgError::Shape(_))
        ));
        assert!(matches!(
            solve_continuous_are(&a, &m(1, 3, &[1.0, 0.0, 0.0]), &q, &r),
            Err(LinalgError::Shape(_))
        ));
        assert!(matches!(
            solve_continuous_are(&a, &c, &q, &m(1, 1, &[-1.0])),
            Err(LinalgError::NoStabilisingSolution(_))
        ));
        // An unstable mode the output does not see: no stabilising L exists.
        let unobserved = m(2, 2, &[-1.0, 0.0, 0.0, 1.0]);
        assert!(matches!(
            solve_continuous_are(&unobserved, &c, &q, &r),
            Err(LinalgError::NoStabilisingSolution(_))
        ));
        // A marginal mode (eigenvalue 0) that is neither seen nor excited: H has eigenvalues
        // on the imaginary axis.
        let marginal = m(2, 2, &[-1.0, 0.0, 0.0, 0.0]);
        let q_first = m(2, 2, &[1.0, 0.0, 0.0, 0.0]);
        assert!(matches!(
            solve_continuous_are(&marginal, &c, &q_first, &r),
            Err(LinalgError::NoStabilisingSolution(_))
        ));
    }
}
