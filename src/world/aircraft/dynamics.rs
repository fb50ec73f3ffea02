//! The follower's 6-DOF equations of motion in a singularity-free body-axis form, equivalent to
//! the seed's wind/body form (7.15)-(7.16) (docs/equations.md, The 6-DOF follower):
//! ```text
//! ṗ_NED = R(q) v                       (position)
//! v̇     = F / m - ω × v                (v = [u, v, w]: inertial velocity in body axes)
//! q̇     = ½ q ⊗ [0, ω]                 (attitude quaternion, NED → body)
//! J ω̇   = -ω × (J ω) + [L, M, N]ᵀ      (7.16)
//! δ̇     = sat_rate((sat_pos(δ_cmd) - δ) / τ)   (actuators)
//! ```
//! F = aerodynamic force (wind axes, from the air-relative velocity v - L_BE (wind + gust)) +
//! thrust (body x) + m g (gravity, NED down). Loads use the actuator positions clamped into
//! their limits.

use nalgebra::Quaternion;

use crate::frames::{GRAVITY_FPS2, Mat3, Vec3};
use crate::scenario::check::InvalidValue;
use crate::world::atmosphere::AtmosphereSample;

use super::aero::{AirAngles, Loads};
use super::air_data::AirData;
use super::params::AircraftParams;
use super::state::{
    ATTITUDE_QUATERNION, AircraftState, BODY_RATES_RPS, Controls, POSITION_NED_FT, STATE_LEN,
    VELOCITY_BODY_FPS, actuators_at, raw_quaternion,
};

/// The follower's plant: validated data plus precomputed inertia.
#[derive(Debug, Clone)]
pub struct Aircraft {
    params: AircraftParams,
    inertia_slug_ft2: Mat3,
    inverse_inertia: Mat3,
}

/// Rigid-body part of the state with the loads that act on it.
#[derive(Debug, Clone, Copy)]
pub(super) struct RigidBodyRates {
    pub position_rate_ned_fps: Vec3,
    pub velocity_rate_body_fps2: Vec3,
    pub quaternion_rate: Quaternion<f64>,
    pub body_rates_rate_rps2: Vec3,
}

/// What the loads are computed from at one instant.
#[derive(Debug, Clone, Copy)]
pub(super) struct Kinematics {
    /// R(q) = L_BEᵀ from the normalised quaternion.
    pub ned_from_body: Mat3,
    pub air: AirAngles,
}

impl Aircraft {
    /// A plant from aircraft data (re-validated: the fields of [`AircraftParams`] are public).
    pub fn new(params: AircraftParams) -> Result<Self, InvalidValue> {
        params.validate()?;
        let inertia_slug_ft2 = params.mass.inertia_slug_ft2();
        // Validation makes J positive definite (positive diagonal, Jxz² < Jxx Jzz).
        let inverse_inertia = inertia_slug_ft2.try_inverse().ok_or_else(|| InvalidValue {
            key: "mass.jxz_slug_ft2".to_string(),
            value: params.mass.jxz_slug_ft2.to_string(),
            allowed: "a value that leaves J invertible".to_string(),
        })?;
        Ok(Self {
            params,
            inertia_slug_ft2,
            inverse_inertia,
        })
    }

    /// The aircraft data (geometry, derivatives, actuator limits: what a controller inverts).
    pub fn params(&self) -> &AircraftParams {
        &self.params
    }

    /// J of (7.16), slug ft².
    pub fn inertia_slug_ft2(&self) -> &Mat3 {
        &self.inertia_slug_ft2
    }

    /// ẋ = f(x, u) for the flat state `x` (layout in [`super::state`]) with actuator
    /// `commands` and the air held over the step. `x` and `dx` must hold at least
    /// [`STATE_LEN`] values (only those are read and written); with fewer, `dx` is left alone.
    pub fn derivative(
        &self,
        x: &[f64],
        commands: &Controls,
        air: &AtmosphereSample,
        dx: &mut [f64],
    ) {
        debug_assert!(x.len() >= STATE_LEN && dx.len() >= STATE_LEN);
        let (Some(x), Some(dx)) = (
            x.first_chunk::<STATE_LEN>(),
            dx.first_chunk_mut::<STATE_LEN>(),
        ) else {
            return;
        };
        let positions = actuators_at(x);
        let controls = self.params.actuators.clamp(&positions);
        let rigid = self.rigid_body_rates(x, &controls, air);
        dx[POSITION_NED_FT..POSITION_NED_FT + 3]
            .copy_from_slice(rigid.position_rate_ned_fps.as_slice());
        dx[VELOCITY_BODY_FPS..VELOCITY_BODY_FPS + 3]
            .copy_from_slice(rigid.velocity_rate_body_fps2.as_slice());
        let qd = rigid.quaternion_rate;
        dx[ATTITUDE_QUATERNION..ATTITUDE_QUATERNION + 4].copy_from_slice(&[qd.w, qd.i, qd.j, qd.k]);
        dx[BODY_RATES_RPS..BODY_RATES_RPS + 3]
            .copy_from_slice(rigid.body_rates_rate_rps2.as_slice());
        let rates = self.params.actuators.rates(&positions, commands);
        dx[super::state::ELEVATOR_RAD] = rates.elevator_rad;
        dx[super::state::AILERON_RAD] = rates.aileron_rad;
        dx[super::state::RUDDER_RAD] = rates.rudder_rad;
        dx[super::state::THROTTLE] = rates.throttle;
    }

    /// Call after each integration step: renormalises the quaternion (RK4 does not keep its
    /// norm exactly) and clamps the actuator positions into their limits. Fewer than
    /// [`STATE_LEN`] values: nothing is done. A zero or non-finite quaternion is left as is
    /// (the caller's state check reports it).
    pub fn normalize(&self, x: &mut [f64]) {
        let Some(x) = x.first_chunk_mut::<STATE_LEN>() else {
            return;
        };
        let q = &mut x[ATTITUDE_QUATERNION..ATTITUDE_QUATERNION + 4];
        let norm = q.iter().map(|c| c * c).sum::<f64>().sqrt();
        if norm.is_finite() && norm > 0.0 {
            q.iter_mut().for_each(|c| *c /= norm);
        }
        let clamped = self.params.actuators.clamp(&actuators_at(x));
        x[super::state::ELEVATOR_RAD] = clamped.elevator_rad;
        x[super::state::AILERON_RAD] = clamped.aileron_rad;
        x[super::state::RUDDER_RAD] = clamped.rudder_rad;
        x[super::state::THROTTLE] = clamped.throttle;
    }

    /// Air data and loads of a state for the controller and telemetry. `None` when `x` is
    /// shorter than [`STATE_LEN`] or its quaternion is zero or not finite.
    pub fn air_data(&self, x: &[f64], air: &AtmosphereSample) -> Option<AirData> {
        let state = AircraftState::unpack(x)?;
        let x = x.first_chunk::<STATE_LEN>()?;
        let kin = self.kinematics(x, air);
        let controls = self.params.actuators.clamp(&state.actuators);
        let loads = self.loads(&kin, &state.body_rates_rps, &controls, air);
        Some(AirData::new(&state, &kin.air, &loads))
    }

    /// Orientation and air-relative motion of a state.
    pub(super) fn kinematics(&self, x: &[f64; STATE_LEN], air: &AtmosphereSample) -> Kinematics {
        let q = raw_quaternion(x);
        let norm = q.norm();
        let qn = if norm.is_finite() && norm > 0.0 {
            q / norm
        } else {
            Quaternion::identity()
        };
        let ned_from_body = rotation_matrix(&qn);
        let wind_body = ned_from_body.transpose() * air.wind_ned_fps + air.gust_body_fps;
        let air_velocity_body_fps =
            Vec3::from_column_slice(&x[VELOCITY_BODY_FPS..VELOCITY_BODY_FPS + 3]) - wind_body;
        Kinematics {
            ned_from_body,
            air: AirAngles::from_air_velocity_body(&air_velocity_body_fps),
        }
    }

    pub(super) fn loads(
        &self,
        kin: &Kinematics,
        body_rates_rps: &Vec3,
        controls: &Controls,
        air: &AtmosphereSample,
    ) -> Loads {
        self.params.loads(
            &kin.air,
            body_rates_rps,
            controls,
            air.density_slug_ft3,
            air.drag_factor,
            &air.moment_bias_body_lbf_ft,
        )
    }

    /// Rates of position, velocity, attitude and body rates with `controls` used as given (not
    /// clamped: the trim solver searches beyond the limits and reports it).
    pub(super) fn rigid_body_rates(
        &self,
        x: &[f64; STATE_LEN],
        controls: &Controls,
        air: &AtmosphereSample,
    ) -> RigidBodyRates {
        let kin = self.kinematics(x, air);
        let velocity = Vec3::from_column_slice(&x[VELOCITY_BODY_FPS..VELOCITY_BODY_FPS + 3]);
        let omega = Vec3::from_column_slice(&x[BODY_RATES_RPS..BODY_RATES_RPS + 3]);
        let loads = self.loads(&kin, &omega, controls, air);
        let mass = self.params.mass.mass_slug;
        let gravity_body = kin.ned_from_body.transpose() * Vec3::new(0.0, 0.0, GRAVITY_FPS2);
        let j_omega = self.inertia_slug_ft2 * omega;
        let q = raw_quaternion(x);
        RigidBodyRates {
            position_rate_ned_fps: kin.ned_from_body * velocity,
            velocity_rate_body_fps2: loads.force_body_lbf / mass + gravity_body
                - omega.cross(&velocity),
            quaternion_rate: q * Quaternion::new(0.0, omega.x, omega.y, omega.z) * 0.5,
            body_rates_rate_rps2: self.inverse_inertia
                * (loads.moment_body_lbf_ft - omega.cross(&j_omega)),
        }
    }
}

/// R(q) for a unit quaternion q = (w, x, y, z): body components to NED components.
fn rotation_matrix(q: &Quaternion<f64>) -> Mat3 {
    let (w, x, y, z) = (q.w, q.i, q.j, q.k);
    Mat3::new(
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        1.0 - 2.0 * (x * x + y * y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::EulerAngles;

    #[test]
    fn rotation_matrix_matches_nalgebra() {
        let euler = EulerAngles::new(0.3, -0.2, 1.1);
        let uq = super::super::state::attitude_from_euler(&euler);
        let m = rotation_matrix(uq.quaternion());
        assert!((m - uq.to_rotation_matrix().into_inner()).norm() < 1e-14);
        assert!((m.transpose() - euler.body_from_ned()).norm() < 1e-14);
    }
}
