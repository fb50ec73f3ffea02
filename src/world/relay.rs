//! An aircraft seen through a relay of its truth (group runs, docs/design.md, Group
//! tracking): the group writes the tracked aircraft's state at each tick (a follower flown by
//! another simulation, or a target the group moves), and the tracking follower's simulation
//! reads it as its [`TargetModel`], carried over the step with constant acceleration. Only
//! the renderer and the truth outputs read it; the follower's guidance sees pixels alone.

use crate::frames::Vec3;
use crate::world::target::{TargetModel, TargetState};
use std::sync::{Arc, Mutex, PoisonError};

/// The writing end: the tracked aircraft's state at a time.
#[derive(Debug, Clone)]
pub struct Relay(Arc<Mutex<(f64, TargetState)>>);

impl Relay {
    /// A relay holding `state` at `t_s`.
    pub fn new(t_s: f64, state: TargetState) -> Self {
        Self(Arc::new(Mutex::new((t_s, state))))
    }

    /// Holds `state` at `t_s` from now on.
    pub fn set(&self, t_s: f64, state: TargetState) {
        *self.0.lock().unwrap_or_else(PoisonError::into_inner) = (t_s, state);
    }

    /// The reading end, a target model for the tracking follower's simulation.
    pub fn target(&self) -> Box<dyn TargetModel> {
        Box::new(RelayedTarget(self.clone()))
    }
}

/// The tracked aircraft as a target model: the relayed state, carried to any time with its
/// velocity and acceleration (within a frame interval of the state's time).
#[derive(Debug)]
struct RelayedTarget(Relay);

impl TargetModel for RelayedTarget {
    fn state(&self, t_s: f64) -> TargetState {
        let (t_ref_s, state) = *self.0.0.lock().unwrap_or_else(PoisonError::into_inner);
        carried(&state, t_s - t_ref_s)
    }
}

/// `state` carried `tau_s` on with constant acceleration (attitude held).
pub fn carried(state: &TargetState, tau_s: f64) -> TargetState {
    let a: Vec3 = state.accel_ned_fps2;
    TargetState {
        position_ned_ft: state.position_ned_ft
            + state.velocity_ned_fps * tau_s
            + a * (0.5 * tau_s * tau_s),
        velocity_ned_fps: state.velocity_ned_fps + a * tau_s,
        ..*state
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::EulerAngles;

    /// The reader sees what the writer set, carried to the time asked for.
    #[test]
    fn relayed_state_is_carried_with_its_acceleration() {
        let state = TargetState {
            position_ned_ft: Vec3::new(10.0, 0.0, -5.0),
            velocity_ned_fps: Vec3::new(50.0, 2.0, 0.0),
            accel_ned_fps2: Vec3::new(0.0, 4.0, 0.0),
            attitude: EulerAngles::new(0.1, 0.0, 0.2),
        };
        let relay = Relay::new(1.0, state);
        let target = relay.target();
        let at = target.state(1.5);
        assert!((at.position_ned_ft - Vec3::new(35.0, 1.5, -5.0)).norm() < 1e-12);
        assert!((at.velocity_ned_fps - Vec3::new(50.0, 4.0, 0.0)).norm() < 1e-12);
        relay.set(
            2.0,
            TargetState {
                position_ned_ft: Vec3::zeros(),
                ..state
            },
        );
        assert!(target.state(2.0).position_ned_ft.norm() < 1e-12);
    }
}
