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
}
