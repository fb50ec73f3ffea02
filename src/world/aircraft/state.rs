//! The plant's flat state vector (what [`crate::integrate::Rk4`] integrates) and its typed
//! view [`AircraftState`].
//!
//! Layout (all f64): position NED (ft) | body velocity u, v, w (ft/s, inertial velocity in body
//! axes) | attitude quaternion q0, q1, q2, q3 (scalar first) | body rates p, q, r (rad/s) |
//! actuator positions δe, δa, δr (rad), δT.
//!
//! The quaternion q is the rotation that carries the NED axes onto the body axes: its rotation
//! matrix R(q) maps body components to NED components, R(q) = L_BEᵀ (`frames`), and for 3-2-1
//! Euler angles q = q_z(ψ) q_y(θ) q_x(φ).

use nalgebra::{Quaternion, UnitQuaternion};

use crate::frames::{EulerAngles, Mat3, Vec3};

/// Index of the NED position (3 values, ft).
pub const POSITION_NED_FT: usize = 0;
/// Index of the body-axis inertial velocity u, v, w (3 values, ft/s).
pub const VELOCITY_BODY_FPS: usize = 3;
/// Index of the attitude quaternion q0 (scalar), q1, q2, q3 (4 values).
pub const ATTITUDE_QUATERNION: usize = 6;
/// Index of the body rates p, q, r (3 values, rad/s).
pub const BODY_RATES_RPS: usize = 10;
/// Index of the elevator position δe, rad.
pub const ELEVATOR_RAD: usize = 13;
/// Index of the aileron position δa, rad.
pub const AILERON_RAD: usize = 14;
/// Index of the rudder position δr, rad.
pub const RUDDER_RAD: usize = 15;
/// Index of the throttle position δT.
pub const THROTTLE: usize = 16;
/// Number of values in the plant's state.
pub const STATE_LEN: usize = 17;

/// Throttle and surface deflections: commands to the actuators, or their positions.
///
/// Signs follow the aerodynamic data (`assets/aircraft/follower.toml`): +δe nose down,
/// +δa right wing down, +δr nose left; δT in [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Controls {
    /// Throttle δT, 0 to 1.
    pub throttle: f64,
    /// Elevator δe, rad.
    pub elevator_rad: f64,
    /// Aileron δa, rad.
    pub aileron_rad: f64,
    /// Rudder δr, rad.
    pub rudder_rad: f64,
}

/// Typed view of the plant's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftState {
    /// Position of the centre of gravity, NED, ft.
    pub position_ned_ft: Vec3,
    /// Inertial velocity in body axes (u, v, w), ft/s.
    pub velocity_body_fps: Vec3,
    /// Attitude: the rotation from NED axes to body axes (maps body components to NED).
    pub attitude: UnitQuaternion<f64>,
    /// Body rates (p, q, r), rad/s.
    pub body_rates_rps: Vec3,
    /// Actuator positions.
    pub actuators: Controls,
}

impl AircraftState {
    /// A state at `position_ned_ft` with the given attitude, body velocity, rates and actuators.
    pub fn from_euler(
        position_ned_ft: Vec3,
        euler: &EulerAngles,
        velocity_body_fps: Vec3,
        body_rates_rps: Vec3,
        actuators: Controls,
    ) -> Self {
        Self {
            position_ned_ft,
            velocity_body_fps,
            attitude: attitude_from_euler(euler),
            body_rates_rps,
            actuators,
        }
    }

    /// The flat state (layout in the module docs).
    pub fn pack(&self) -> [f64; STATE_LEN] {
        let mut x = [0.0; STATE_LEN];
        let q = self.attitude.quaternion();
        x[POSITION_NED_FT..POSITION_NED_FT + 3].copy_from_slice(self.position_ned_ft.as_slice());
        x[VELOCITY_BODY_FPS..VELOCITY_BODY_FPS + 3]
            .copy_from_slice(self.velocity_body_fps.as_slice());
        x[ATTITUDE_QUATERNION..ATTITUDE_QUATERNION + 4].copy_from_slice(&[q.w, q.i, q.j, q.k]);
        x[BODY_RATES_RPS..BODY_RATES_RPS + 3].copy_from_slice(self.body_rates_rps.as_slice());
        x[ELEVATOR_RAD] = self.actuators.elevator_rad;
        x[AILERON_RAD] = self.actuators.aileron_rad;
        x[RUDDER_RAD] = self.actuators.rudder_rad;
        x[THROTTLE] = self.actuators.throttle;
        x
    }

    /// Reads the first [`STATE_LEN`] values of `x` (the quaternion is normalised). `None` when
    /// `x` is shorter or its quaternion has no finite, nonzero norm.
    pub fn unpack(x: &[f64]) -> Option<Self> {
        let x = x.first_chunk::<STATE_LEN>()?;
        let q = raw_quaternion(x);
        let norm = q.norm();
        if !(norm.is_finite() && norm > 0.0) {
            return None;
        }
        Some(Self {
            position_ned_ft: Vec3::from_column_slice(&x[POSITION_NED_FT..POSITION_NED_FT + 3]),
            velocity_body_fps: Vec3::from_column_slice(
                &x[VELOCITY_BODY_FPS..VELOCITY_BODY_FPS + 3],
            ),
            attitude: UnitQuaternion::new_normalize(q),
            body_rates_rps: Vec3::from_column_slice(&x[BODY_RATES_RPS..BODY_RATES_RPS + 3]),
            actuators: actuators_at(x),
        })
    }

    /// 3-2-1 Euler angles of the attitude.
    pub fn euler(&self) -> EulerAngles {
        EulerAngles::from_body_from_ned(&self.body_from_ned())
    }

    /// L_BE: NED components to body components.
    pub fn body_from_ned(&self) -> Mat3 {
        self.attitude.to_rotation_matrix().matrix().transpose()
    }

    /// Inertial velocity in NED, ft/s.
    pub fn velocity_ned_fps(&self) -> Vec3 {
        self.attitude * self.velocity_body_fps
    }
}

/// The quaternion of 3-2-1 Euler angles: q = q_z(ψ) q_y(θ) q_x(φ), so R(q) = L_BEᵀ.
pub fn attitude_from_euler(euler: &EulerAngles) -> UnitQuaternion<f64> {
    UnitQuaternion::from_euler_angles(euler.phi_rad, euler.theta_rad, euler.psi_rad)
}

pub(super) fn raw_quaternion(x: &[f64; STATE_LEN]) -> Quaternion<f64> {
    let a = ATTITUDE_QUATERNION;
    Quaternion::new(x[a], x[a + 1], x[a + 2], x[a + 3])
}

pub(super) fn actuators_at(x: &[f64; STATE_LEN]) -> Controls {
    Controls {
        throttle: x[THROTTLE],
        elevator_rad: x[ELEVATOR_RAD],
        aileron_rad: x[AILERON_RAD],
        rudder_rad: x[RUDDER_RAD],
    }
}

/// The names of the packed state's elements, in order (for messages).
pub fn state_names() -> Vec<String> {
    use crate::state_block::{NED, element_names};
    element_names(
        "aircraft",
        &[
            ("position, ft", NED),
            ("body velocity, ft/s", &["u", "v", "w"]),
            ("attitude quaternion", &["q0", "q1", "q2", "q3"]),
            ("body rate, rad/s", &["p", "q", "r"]),
            ("elevator, rad", &[]),
            ("aileron, rad", &[]),
            ("rudder, rad", &[]),
            ("throttle", &[]),
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The quaternion of Euler angles has R(q) = L_BEᵀ of `frames`, and pack/unpack is exact.
        #[test]
        fn quaternion_matches_frames_dcm(phi in -3.1f64..3.1, theta in -1.5f64..1.5, psi in -3.1f64..3.1) {
            let euler = EulerAngles::new(phi, theta, psi);
            let state = AircraftState::from_euler(
                Vec3::new(1.0, 2.0, 3.0), &euler, Vec3::new(50.0, 1.0, 2.0),
                Vec3::new(0.1, 0.2, 0.3), Controls { throttle: 0.4, elevator_rad: -0.1, aileron_rad: 0.05, rudder_rad: 0.02 });
            prop_assert!((state.body_from_ned() - euler.body_from_ned()).norm() < 1e-12);
            let back = AircraftState::unpack(&state.pack()).expect("valid");
            prop_assert!((back.euler().body_from_ned() - euler.body_from_ned()).norm() < 1e-12);
            prop_assert_eq!(back.actuators, state.actuators);
            prop_assert_eq!(back.position_ned_ft, state.position_ned_ft);
        }
    }

    #[test]
    fn short_slice_or_zero_quaternion_is_refused() {
        assert!(AircraftState::unpack(&[0.0; STATE_LEN - 1]).is_none());
        assert!(AircraftState::unpack(&[0.0; STATE_LEN]).is_none());
    }
}
