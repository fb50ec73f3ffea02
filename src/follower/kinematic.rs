//! The kinematic follower of the seed's Chapters 4-6: it realises the guidance command exactly,
//! a commanded velocity (Chapter 4, 6.2: Ṙ_F = V_F) or a commanded inertial acceleration
//! (Chapter 5, 6.3: Ṙ_F = V_F, V̇_F = a_F). It has no attitude dynamics of its own; its camera
//! needs an attitude, so the body x axis turns to the direction of a velocity v (θ → γ,
//! ψ → χ) and the wings to the coordinated-turn bank φ = atan(ψ̇ V / g) (Remark 9),
//! through first-order lags of time constant τ.
//!
//! v is a state: when the follower realises accelerations it is V_F itself; when it realises
//! velocities it lags the commanded V_F by τ (v̇ = (V_F - v)/τ). Every attitude rate is then a
//! function of the state alone. Were the attitude rates computed from the commanded V_F, the
//! body-frame command (3.13)-(3.14), whose derivative needs those rates, would feed V_F back
//! into itself within one step; at 33 ft and 100 ft/s that algebraic loop has a gain above one
//! through the roll rate and V_F flips sign every tick (measured).
//!
//! State slice: `[R_F (3), φ, θ, ψ, v (3)]`.

use crate::frames::{EulerAngles, GRAVITY_FPS2, Vec3, wrap_angle_rad};
use crate::guidance::signals::{CommandKind, FollowerCommand};

/// Length of the kinematic follower's state slice.
pub const STATE_LEN: usize = 9;
/// Offset of v in the state slice.
const VELOCITY: usize = 6;

/// A follower that flies the guidance command exactly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KinematicFollower {
    /// Attitude lag τ, s.
    pub attitude_lag_s: f64,
    /// The command it realises: Ṙ_F = V_F, or Ṙ_F = V_F and V̇_F = a_F.
    pub realises: CommandKind,
}

impl KinematicFollower {
    /// Length of the state slice.
    pub fn state_len(&self) -> usize {
        STATE_LEN
    }

    /// Initial state from a position, an attitude and the velocity v(0) (V_F(0) for a
    /// follower that realises accelerations).
    pub fn initial_state(
        &self,
        position_ned_ft: &Vec3,
        attitude: &EulerAngles,
        velocity_ned_fps: &Vec3,
    ) -> Vec<f64> {
        let mut x = position_ned_ft.as_slice().to_vec();
        x.extend([attitude.phi_rad, attitude.theta_rad, attitude.psi_rad]);
        x.extend(velocity_ned_fps.iter());
        x
    }

    /// V_F, NED, ft/s: the commanded velocity, or the velocity state when the follower
    /// integrates accelerations.
    pub fn velocity_ned_fps(&self, x: &[f64], command: &FollowerCommand) -> Vec3 {
        match (self.realises, command) {
            (CommandKind::Velocity, FollowerCommand::Velocity(v)) => *v,
            _ => Self::heading_velocity_ned_fps(x),
        }
    }

    /// Sets v (e.g. to the first commanded V_F of a follower that realises velocities).
    pub fn set_heading_velocity(x: &mut [f64], velocity_ned_fps: &Vec3) {
        x[VELOCITY..VELOCITY + 3].copy_from_slice(velocity_ned_fps.as_slice());
    }

    /// v, the velocity the attitude follows, NED, ft/s.
    pub fn heading_velocity_ned_fps(x: &[f64]) -> Vec3 {
        Vec3::new(x[VELOCITY], x[VELOCITY + 1], x[VELOCITY + 2])
    }

    /// R_F of a state slice, NED, ft.
    pub fn position_ned_ft(x: &[f64]) -> Vec3 {
        Vec3::new(x[0], x[1], x[2])
    }

    /// Attitude of a state slice.
    pub fn attitude(x: &[f64]) -> EulerAngles {
        EulerAngles::new(x[3], x[4], x[5])
    }

    /// Euler-angle rates [φ̇, θ̇, ψ̇] turning the attitude toward v (zero speed holds the
    /// attitude and levels the wings).
    pub fn attitude_rates(&self, x: &[f64]) -> Vec3 {
        let att = Self::attitude(x);
        let v = Self::heading_velocity_ned_fps(x);
        let speed = v.norm();
        if speed <= 1e-9 {
            return Vec3::new(-att.phi_rad / self.attitude_lag_s, 0.0, 0.0);
        }
        let gamma = (-v.z / speed).clamp(-1.0, 1.0).asin();
        let chi = v.y.atan2(v.x);
        let psi_rate = wrap_angle_rad(chi - att.psi_rad) / self.attitude_lag_s;
        let theta_rate = (gamma - att.theta_rad) / self.attitude_lag_s;
        let bank = (psi_rate * speed / GRAVITY_FPS2).atan();
        let phi_rate = (bank - att.phi_rad) / self.attitude_lag_s;
        Vec3::new(phi_rate, theta_rate, psi_rate)
    }

    /// Body rates [p, q, r] of a state slice, from its Euler-angle rates: H = P⁻¹.
    pub fn body_rates(&self, x: &[f64]) -> Vec3 {
        Self::attitude(x).body_rates_from_rates_matrix() * self.attitude_rates(x)
    }

    /// Writes ẋ: Ṙ_F = V_F, the attitude rates toward v, and v̇: a_F when the follower
    /// integrates accelerations, (V_F - v)/τ when it realises velocities. A command of the
    /// kind the follower does not realise is a wiring error: it then holds its velocity.
    pub fn derivative(&self, x: &[f64], command: &FollowerCommand, dx: &mut [f64]) {
        debug_assert!(matches!(
            (self.realises, command),
            (CommandKind::Velocity, FollowerCommand::Velocity(_))
                | (CommandKind::Acceleration, FollowerCommand::Acceleration(_))
        ));
        let velocity = self.velocity_ned_fps(x, command);
        dx[0..3].copy_from_slice(velocity.as_slice());
        let rates = self.attitude_rates(x);
        dx[3..6].copy_from_slice(rates.as_slice());
        let v_rate = match (self.realises, command) {
            (CommandKind::Acceleration, FollowerCommand::Acceleration(a)) => *a,
            (CommandKind::Velocity, FollowerCommand::Velocity(v)) => {
                (v - Self::heading_velocity_ned_fps(x)) / self.attitude_lag_s
            }
            _ => Vec3::zeros(),
        };
        dx[VELOCITY..VELOCITY + 3].copy_from_slice(v_rate.as_slice());
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

    /// Flying a constant climbing right-hand velocity: the attitude converges to its
    /// direction and the wings level once the turn toward it is over.
    #[test]
    fn attitude_follows_velocity() {
        let follower = KinematicFollower {
            attitude_lag_s: 0.05,
            realises: CommandKind::Velocity,
        };
        let v = Vec3::new(30.0, 40.0, -5.0);
        let mut x = follower.initial_state(&Vec3::zeros(), &EulerAngles::default(), &Vec3::zeros());
        let dt = 0.001;
        let mut dx = [0.0; STATE_LEN];
        for _ in 0..2000 {
            follower.derivative(&x, &FollowerCommand::Velocity(v), &mut dx);
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

    /// Realising accelerations, V_F integrates a_F and the position integrates V_F.
    #[test]
    fn acceleration_is_integrated() {
        let follower = KinematicFollower {
            attitude_lag_s: 0.2,
            realises: CommandKind::Acceleration,
        };
        let v0 = Vec3::new(50.0, 0.0, 0.0);
        let x = follower.initial_state(&Vec3::zeros(), &EulerAngles::default(), &v0);
        let mut dx = [0.0; STATE_LEN];
        let a = Vec3::new(1.0, 2.0, -0.5);
        follower.derivative(&x, &FollowerCommand::Acceleration(a), &mut dx);
        assert_eq!(&dx[0..3], v0.as_slice());
        assert_eq!(&dx[6..9], a.as_slice());
    }
}
