//! The kinematic follower of the seed's Chapters 4-6: it realises the guidance command exactly,
//! a commanded velocity (Chapter 4, 6.2: Ṙ_F = V_F) or a commanded inertial acceleration
//! (Chapter 5, 6.3: Ṙ_F = V_F, V̇_F = a_F). It has no attitude dynamics of its own; its camera needs an attitude, so the body
//! x axis turns to the velocity direction (θ → γ, ψ → χ) and the wings to the coordinated-turn
//! bank φ = atan(ψ̇ V / g) (SPEC §2, Remark 9) through a first-order lag of time constant τ.
//! The lag keeps the attitude continuous and gives its rates exactly (the body-frame command
//! (3.13)-(3.14) needs them) without differentiating a command.
//!
//! State slice: `[R_F (3), φ, θ, ψ]`, followed by `V_F (3)` when it realises accelerations.
//! The attitude follows the velocity the follower flies: the commanded V_F of the step's start
//! (a one-tick delay that breaks the loop attitude → body-frame command → V_F) when it
//! realises velocities, its own V_F state when it realises accelerations.

use crate::frames::{EulerAngles, GRAVITY_FPS2, Mat3, Vec3};
use std::f64::consts::PI;

/// Length of the state slice of a follower that realises velocities.
const POSE_LEN: usize = 6;
/// Offset of V_F in the state slice of a follower that realises accelerations.
const VELOCITY: usize = POSE_LEN;

/// What a guidance law commands the follower with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FollowerCommand {
    /// Inertial velocity V_F, NED, ft/s (the velocity law, (4.3)).
    Velocity(Vec3),
    /// Inertial acceleration a_F, NED, ft/s² (the acceleration law, (5.38)).
    Acceleration(Vec3),
}

/// Which command the follower realises exactly.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Realises {
    /// Ṙ_F = V_F as commanded.
    Velocity,
    /// Ṙ_F = V_F, V̇_F = a_F as commanded.
    Acceleration,
}

/// A follower that flies the guidance command exactly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KinematicFollower {
    /// Attitude lag τ, s.
    pub attitude_lag_s: f64,
    /// The command it realises.
    pub realises: Realises,
}

/// Angle wrapped into (-π, π].
pub fn wrap_angle_rad(angle: f64) -> f64 {
    let wrapped = (angle + PI).rem_euclid(2.0 * PI) - PI;
    if wrapped <= -PI {
        wrapped + 2.0 * PI
    } else {
        wrapped
    }
}

impl KinematicFollower {
    /// Length of the state slice.
    pub fn state_len(&self) -> usize {
        match self.realises {
            Realises::Velocity => POSE_LEN,
            Realises::Acceleration => POSE_LEN + 3,
        }
    }

    /// Initial state from a position, an attitude and (when it realises accelerations) V_F(0).
    pub fn initial_state(
        &self,
        position_ned_ft: &Vec3,
        attitude: &EulerAngles,
        velocity_ned_fps: &Vec3,
    ) -> Vec<f64> {
        let mut x = vec![
            position_ned_ft.x,
            position_ned_ft.y,
            position_ned_ft.z,
            attitude.phi_rad,
            attitude.theta_rad,
            attitude.psi_rad,
        ];
        if self.realises == Realises::Acceleration {
            x.extend(velocity_ned_fps.iter());
        }
        x
    }

    /// V_F, NED, ft/s: the commanded velocity, or the velocity state when the follower
    /// integrates accelerations.
    pub fn velocity_ned_fps(&self, x: &[f64], command: &FollowerCommand) -> Vec3 {
        match (self.realises, command) {
            (Realises::Velocity, FollowerCommand::Velocity(v)) => *v,
            _ => self.own_velocity_ned_fps(x),
        }
    }

    /// The velocity state (zero for a follower that realises velocities: it has none).
    fn own_velocity_ned_fps(&self, x: &[f64]) -> Vec3 {
        match self.realises {
            Realises::Velocity => Vec3::zeros(),
            Realises::Acceleration => Vec3::new(x[VELOCITY], x[VELOCITY + 1], x[VELOCITY + 2]),
        }
    }

    /// The velocity the attitude turns to: `held_velocity_ned_fps` (V_F at the step's start)
    /// for a follower that realises velocities, its own V_F otherwise.
    pub fn heading_velocity_ned_fps(&self, x: &[f64], held_velocity_ned_fps: &Vec3) -> Vec3 {
        match self.realises {
            Realises::Velocity => *held_velocity_ned_fps,
            Realises::Acceleration => self.own_velocity_ned_fps(x),
        }
    }

    /// R_F of a state slice, NED, ft.
    pub fn position_ned_ft(x: &[f64]) -> Vec3 {
        Vec3::new(x[0], x[1], x[2])
    }

    /// Attitude of a state slice.
    pub fn attitude(x: &[f64]) -> EulerAngles {
        EulerAngles::new(x[3], x[4], x[5])
    }

    /// Euler-angle rates [φ̇, θ̇, ψ̇] turning the attitude toward `heading_velocity_ned_fps`
    /// (the velocity the attitude follows; zero speed holds the attitude).
    pub fn attitude_rates(&self, x: &[f64], heading_velocity_ned_fps: &Vec3) -> Vec3 {
        let att = Self::attitude(x);
        let speed = heading_velocity_ned_fps.norm();
        if speed <= 1e-9 {
            return Vec3::new(-att.phi_rad / self.attitude_lag_s, 0.0, 0.0);
        }
        let v = heading_velocity_ned_fps;
        let gamma = (-v.z / speed).clamp(-1.0, 1.0).asin();
        let chi = v.y.atan2(v.x);
        let psi_rate = wrap_angle_rad(chi - att.psi_rad) / self.attitude_lag_s;
        let theta_rate = (gamma - att.theta_rad) / self.attitude_lag_s;
        let bank = (psi_rate * speed / GRAVITY_FPS2).atan();
        let phi_rate = (bank - att.phi_rad) / self.attitude_lag_s;
        Vec3::new(phi_rate, theta_rate, psi_rate)
    }

    /// Body rates [p, q, r] from Euler-angle rates: H = P⁻¹ (SPEC §7).
    pub fn body_rates(attitude: &EulerAngles, euler_rates: &Vec3) -> Vec3 {
        let (sf, cf) = attitude.phi_rad.sin_cos();
        let (st, ct) = attitude.theta_rad.sin_cos();
        let h = Mat3::new(1.0, 0.0, -st, 0.0, cf, sf * ct, 0.0, -sf, cf * ct);
        h * euler_rates
    }

    /// Writes ẋ: Ṙ_F = V_F, the attitude rates toward the heading velocity (see
    /// [`Self::heading_velocity_ned_fps`]) and, when it integrates accelerations, V̇_F = a_F.
    /// A command of the kind the follower does not realise is a wiring error: it then holds
    /// its velocity.
    pub fn derivative(
        &self,
        x: &[f64],
        command: &FollowerCommand,
        held_velocity_ned_fps: &Vec3,
        dx: &mut [f64],
    ) {
        debug_assert!(matches!(
            (self.realises, command),
            (Realises::Velocity, FollowerCommand::Velocity(_))
                | (Realises::Acceleration, FollowerCommand::Acceleration(_))
        ));
        let velocity = self.velocity_ned_fps(x, command);
        dx[0..3].copy_from_slice(velocity.as_slice());
        let heading = self.heading_velocity_ned_fps(x, held_velocity_ned_fps);
        let rates = self.attitude_rates(x, &heading);
        dx[3..6].copy_from_slice(rates.as_slice());
        if self.realises == Realises::Acceleration {
            let accel = match command {
                FollowerCommand::Acceleration(a) => *a,
                FollowerCommand::Velocity(_) => Vec3::zeros(),
            };
            dx[VELOCITY..VELOCITY + 3].copy_from_slice(accel.as_slice());
        }
    }

    /// Wraps roll and yaw into (-π, π] after a step.
    pub fn normalize(x: &mut [f64]) {
        x[3] = wrap_angle_rad(x[3]);
        x[5] = wrap_angle_rad(x[5]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_is_in_range() {
        for a in [-10.0, -PI, -1.0, 0.0, 1.0, PI, 7.0] {
            let w = wrap_angle_rad(a);
            assert!(w > -PI - 1e-15 && w <= PI + 1e-15, "{a} -> {w}");
            let turns = (a - w) / (2.0 * PI);
            assert!((turns - turns.round()).abs() < 1e-12, "{a} -> {w}");
        }
    }

    /// H inverts P: P H = I.
    #[test]
    fn body_rates_invert_euler_rate_matrix() {
        let att = EulerAngles::new(0.4, -0.3, 1.2);
        let rates = Vec3::new(0.1, -0.2, 0.3);
        let pqr = KinematicFollower::body_rates(&att, &rates);
        let back = att.rates_from_body_rates_matrix() * pqr;
        assert!((back - rates).norm() < 1e-12);
    }

    /// Turning right at constant speed: the attitude converges to the velocity direction and
    /// banks right.
    #[test]
    fn attitude_follows_velocity() {
        let follower = KinematicFollower {
            attitude_lag_s: 0.05,
            realises: Realises::Velocity,
        };
        let mut x = follower.initial_state(&Vec3::zeros(), &EulerAngles::default(), &Vec3::zeros());
        let v = Vec3::new(30.0, 40.0, -5.0);
        let dt = 0.001;
        let mut dx = [0.0; POSE_LEN];
        for _ in 0..1000 {
            follower.derivative(&x, &FollowerCommand::Velocity(v), &v, &mut dx);
            for (xi, di) in x.iter_mut().zip(dx.iter()) {
                *xi += dt * di;
            }
        }
        let att = KinematicFollower::attitude(&x);
        assert!((att.psi_rad - 40f64.atan2(30.0)).abs() < 1e-6);
        assert!((att.theta_rad - (5.0 / v.norm()).asin()).abs() < 1e-6);
        assert!(
            att.phi_rad.abs() < 1e-6,
            "bank decays once the turn is over"
        );
    }

    /// Realising accelerations: V_F integrates a_F, R_F integrates V_F, and the attitude turns
    /// to the follower's own velocity whatever velocity is held.
    #[test]
    fn acceleration_is_integrated() {
        let follower = KinematicFollower {
            attitude_lag_s: 0.05,
            realises: Realises::Acceleration,
        };
        let v0 = Vec3::new(50.0, 0.0, 0.0);
        let mut x = follower.initial_state(&Vec3::zeros(), &EulerAngles::default(), &v0);
        assert_eq!(x.len(), follower.state_len());
        let a = Vec3::new(0.0, 2.0, 0.0);
        let dt = 0.001;
        let mut dx = vec![0.0; follower.state_len()];
        let bogus_held = Vec3::new(0.0, -50.0, 0.0);
        for _ in 0..1000 {
            follower.derivative(&x, &FollowerCommand::Acceleration(a), &bogus_held, &mut dx);
            for (xi, di) in x.iter_mut().zip(dx.iter()) {
                *xi += dt * di;
            }
        }
        let command = FollowerCommand::Acceleration(a);
        let v = follower.velocity_ned_fps(&x, &command);
        assert!((v - Vec3::new(50.0, 2.0, 0.0)).norm() < 1e-9, "{v:?}");
        // Explicit Euler: y = Σ dt · 2 k dt for k < 1000 = 0.999 ft.
        assert!((KinematicFollower::position_ned_ft(&x).y - 0.999).abs() < 1e-9);
        let psi = KinematicFollower::attitude(&x).psi_rad;
        assert!(psi > 0.0 && psi < 2f64.atan2(50.0), "ψ = {psi}");
    }
}
