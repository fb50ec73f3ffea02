//! Reference frames and attitude conventions (docs/equations.md, Frames and angles).
//!
//! Inertial frame E is flat-Earth NED (x North, y East, z Down); an aircraft's body frame B has
//! x forward, y right wing, z down. Attitudes are 3-2-1 Euler angles (roll φ, pitch θ, yaw ψ).
//! Transforms are named `b_from_a`: `body_from_ned(euler) * v_ned = v_body`.

use nalgebra::{Matrix3, Vector3};

/// A 3-vector of `f64` (positions in ft, velocities in ft/s, …: the unit is in the name of the
/// variable that holds it).
pub type Vec3 = Vector3<f64>;
/// A 3x3 matrix of `f64`.
pub type Mat3 = Matrix3<f64>;

/// Standard gravity, ft/s^2.
pub const GRAVITY_FPS2: f64 = 32.174;
/// Sea-level air density, slug/ft^3.
pub const SEA_LEVEL_DENSITY_SLUG_FT3: f64 = 0.002377;

/// 3-2-1 Euler angles in radians.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EulerAngles {
    /// Roll φ, rad.
    pub phi_rad: f64,
    /// Pitch θ, rad.
    pub theta_rad: f64,
    /// Yaw ψ, rad.
    pub psi_rad: f64,
}

impl EulerAngles {
    /// Angles from roll, pitch, yaw in radians.
    pub fn new(phi_rad: f64, theta_rad: f64, psi_rad: f64) -> Self {
        Self {
            phi_rad,
            theta_rad,
            psi_rad,
        }
    }

    /// L_BE, the direction-cosine matrix from NED to body.
    pub fn body_from_ned(&self) -> Mat3 {
        let (sf, cf) = self.phi_rad.sin_cos();
        let (st, ct) = self.theta_rad.sin_cos();
        let (sp, cp) = self.psi_rad.sin_cos();
        Mat3::new(
            ct * cp,
            ct * sp,
            -st,
            sf * st * cp - cf * sp,
            sf * st * sp + cf * cp,
            sf * ct,
            cf * st * cp + sf * sp,
            cf * st * sp - sf * cp,
            cf * ct,
        )
    }

    /// Euler angles of a body-from-NED rotation matrix (inverse of [`Self::body_from_ned`]);
    /// pitch is returned in [-π/2, π/2].
    pub fn from_body_from_ned(m: &Mat3) -> Self {
        let theta_rad = (-m[(0, 2)]).clamp(-1.0, 1.0).asin();
        let phi_rad = m[(1, 2)].atan2(m[(2, 2)]);
        let psi_rad = m[(0, 1)].atan2(m[(0, 0)]);
        Self {
            phi_rad,
            theta_rad,
            psi_rad,
        }
    }

    /// The matrix P of (7.16) mapping body rates [p, q, r] to Euler-angle rates.
    pub fn rates_from_body_rates_matrix(&self) -> Mat3 {
        let (sf, cf) = self.phi_rad.sin_cos();
        let (st, ct) = self.theta_rad.sin_cos();
        let tt = st / ct;
        Mat3::new(1.0, sf * tt, cf * tt, 0.0, cf, -sf, 0.0, sf / ct, cf / ct)
    }

    /// H = P⁻¹ of (7.24), mapping Euler-angle rates to body rates [p, q, r]:
    /// H = [[1, 0, -sθ], [0, cφ, sφ cθ], [0, -sφ, cφ cθ]].
    pub fn body_rates_from_rates_matrix(&self) -> Mat3 {
        let (sf, cf) = self.phi_rad.sin_cos();
        let (st, ct) = self.theta_rad.sin_cos();
        Mat3::new(1.0, 0.0, -st, 0.0, cf, sf * ct, 0.0, -sf, cf * ct)
    }
}

/// An angle wrapped into (-π, π].
pub fn wrap_angle_rad(angle_rad: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let wrapped = (angle_rad + PI).rem_euclid(TAU) - PI;
    if wrapped <= -PI {
        wrapped + TAU
    } else {
        wrapped
    }
}

/// Attitude of a body whose x axis is along `velocity_ned` (θ = γ, ψ = χ) with the given bank
/// angle: the kinematic attitude of the seed's Remark 9 (docs/equations.md, Commands and the
/// camera's field of view). Returns `None` when the speed is zero (the heading is undefined).
pub fn attitude_along_velocity(velocity_ned_fps: &Vec3, bank_rad: f64) -> Option<EulerAngles> {
    let speed_fps = velocity_ned_fps.norm();
    if speed_fps <= 0.0 || !speed_fps.is_finite() {
        return None;
    }
    let gamma_rad = (-velocity_ned_fps.z / speed_fps).clamp(-1.0, 1.0).asin();
    let chi_rad = velocity_ned_fps.y.atan2(velocity_ned_fps.x);
    Some(EulerAngles::new(bank_rad, gamma_rad, chi_rad))
}

/// Coordinated-turn bank angle φ = atan(ψ̇ V / g) ((7.14) with α = β = 0) for a
/// velocity and acceleration in NED; ψ̇ is the rate of the horizontal course angle.
pub fn coordinated_turn_bank_rad(velocity_ned_fps: &Vec3, accel_ned_fps2: &Vec3) -> f64 {
    let horizontal_sq = velocity_ned_fps.x.powi(2) + velocity_ned_fps.y.powi(2);
    if horizontal_sq <= 1e-12 {
        return 0.0;
    }
    let course_rate_rps = (velocity_ned_fps.x * accel_ned_fps2.y
        - velocity_ned_fps.y * accel_ned_fps2.x)
        / horizontal_sq;
    (course_rate_rps * velocity_ned_fps.norm() / GRAVITY_FPS2).atan()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn identity_attitude_is_identity_matrix() {
        let m = EulerAngles::default().body_from_ned();
        assert!((m - Mat3::identity()).norm() < 1e-15);
    }

    #[test]
    fn yaw_90_maps_east_to_body_forward() {
        let m = EulerAngles::new(0.0, 0.0, std::f64::consts::FRAC_PI_2).body_from_ned();
        let v = m * Vec3::new(0.0, 1.0, 0.0);
        assert!((v - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn positive_pitch_puts_up_ahead() {
        // Nose up 90°: a point straight up (negative down) is straight ahead.
        let m = EulerAngles::new(0.0, std::f64::consts::FRAC_PI_2, 0.0).body_from_ned();
        let v = m * Vec3::new(0.0, 0.0, -1.0);
        assert!((v - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-12);
    }

    /// H inverts P: H P = I.
    #[test]
    fn body_rate_matrix_inverts_euler_rate_matrix() {
        let e = EulerAngles::new(0.4, -0.3, 2.0);
        let product = e.body_rates_from_rates_matrix() * e.rates_from_body_rates_matrix();
        assert!((product - Mat3::identity()).norm() < 1e-12);
    }

    /// Wrapped angles lie in (-π, π] and differ from the input by whole turns.
    #[test]
    fn wrap_is_in_range() {
        use std::f64::consts::PI;
        for a in [-10.0, -PI, -1.0, 0.0, 1.0, PI, 3.0 * PI, 7.0] {
            let w = wrap_angle_rad(a);
            assert!(w > -PI && w <= PI + 1e-15, "{a} -> {w}");
            let turns = (a - w) / (2.0 * PI);
            assert!((turns - turns.round()).abs() < 1e-12, "{a} -> {w}");
        }
        assert!((wrap_angle_rad(-PI) - PI).abs() < 1e-12);
    }

    #[test]
    fn coordinated_turn_bank_is_right_for_right_turn() {
        // Flying north, accelerating east: turning right, positive bank.
        let bank = coordinated_turn_bank_rad(&Vec3::new(50.0, 0.0, 0.0), &Vec3::new(0.0, 3.0, 0.0));
        assert!((bank - (3.0 / GRAVITY_FPS2).atan()).abs() < 1e-12);
    }

    proptest! {
        #[test]
        fn dcm_is_orthonormal_and_round_trips(phi in -3.1f64..3.1, theta in -1.5f64..1.5, psi in -3.1f64..3.1) {
            let e = EulerAngles::new(phi, theta, psi);
            let m = e.body_from_ned();
            prop_assert!((m * m.transpose() - Mat3::identity()).norm() < 1e-12);
            prop_assert!((m.determinant() - 1.0).abs() < 1e-12);
            let back = EulerAngles::from_body_from_ned(&m);
            prop_assert!((back.body_from_ned() - m).norm() < 1e-12);
        }
    }
}
