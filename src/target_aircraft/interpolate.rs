//! The target aircraft between the ends of its step (docs/equations.md, The target as an
//! aircraft): the follower's RK4 asks where the target is at t, t + h/2 and t + h, and the
//! target has been integrated from t to t + h before.
//!
//! Position: the cubic Hermite polynomial through both ends' positions with both ends'
//! velocities as its slopes, exact for a cubic path and within O(h⁴) of a smooth one;
//! velocity: its derivative (so the two agree); acceleration: linear between the ends'; the
//! attitude of the nearer end (of the later one halfway, a difference of one step's rotation,
//! under 0.01° at the target's rates). Outside the step the nearer end moves on at its own
//! velocity.

use crate::frames::Vec3;
use crate::world::target::TargetState;

/// The target's state at one end of its step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepEnd {
    /// Time, s.
    pub t_s: f64,
    /// The state there.
    pub state: TargetState,
}

/// The target's state at `t_s` between `start` and `end` (see the module's documentation).
pub fn between(start: &StepEnd, end: &StepEnd, t_s: f64) -> TargetState {
    let h_s = end.t_s - start.t_s;
    if t_s >= end.t_s || h_s <= 0.0 {
        return carried(end, t_s);
    }
    if t_s <= start.t_s {
        return carried(start, t_s);
    }
    let s = (t_s - start.t_s) / h_s;
    let (p0, v0) = (start.state.position_ned_ft, start.state.velocity_ned_fps);
    let (p1, v1) = (end.state.position_ned_ft, end.state.velocity_ned_fps);
    let (s2, s3) = (s * s, s * s * s);
    let position_ned_ft = p0 * (2.0 * s3 - 3.0 * s2 + 1.0)
        + v0 * (h_s * (s3 - 2.0 * s2 + s))
        + p1 * (3.0 * s2 - 2.0 * s3)
        + v1 * (h_s * (s3 - s2));
    let velocity_ned_fps = (p1 - p0) * ((6.0 * s - 6.0 * s2) / h_s)
        + v0 * (3.0 * s2 - 4.0 * s + 1.0)
        + v1 * (3.0 * s2 - 2.0 * s);
    let accel_ned_fps2 = start.state.accel_ned_fps2 * (1.0 - s) + end.state.accel_ned_fps2 * s;
    let nearer = if s < 0.5 { start } else { end };
    TargetState {
        position_ned_ft,
        velocity_ned_fps,
        accel_ned_fps2,
        attitude: nearer.state.attitude,
    }
}

/// `at`'s state carried to `t_s` at its own velocity.
fn carried(at: &StepEnd, t_s: f64) -> TargetState {
    let moved: Vec3 = at.state.velocity_ned_fps * (t_s - at.t_s);
    TargetState {
        position_ned_ft: at.state.position_ned_ft + moved,
        ..at.state
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::EulerAngles;

    /// A cubic path p(t) = a + b t + c t² + d t³ per axis.
    fn cubic(t: f64) -> (Vec3, Vec3, Vec3) {
        let (a, b) = (Vec3::new(200.0, 50.0, 30.0), Vec3::new(50.0, -3.0, 1.0));
        let (c, d) = (Vec3::new(0.7, 2.0, -0.4), Vec3::new(-0.3, 0.5, 0.2));
        (
            a + b * t + c * (t * t) + d * (t * t * t),
            b + c * (2.0 * t) + d * (3.0 * t * t),
            c * 2.0 + d * (6.0 * t),
        )
    }

    fn end_at(t_s: f64, roll_rad: f64) -> StepEnd {
        let (position_ned_ft, velocity_ned_fps, accel_ned_fps2) = cubic(t_s);
        StepEnd {
            t_s,
            state: TargetState {
                position_ned_ft,
                velocity_ned_fps,
                accel_ned_fps2,
                attitude: EulerAngles::new(roll_rad, 0.0, 0.0),
            },
        }
    }

    /// A cubic path is reproduced exactly inside the step, position and velocity, and the
    /// acceleration (linear in t for a cubic) too.
    #[test]
    fn cubic_path_is_exact() {
        let (start, end) = (end_at(1.0, 0.1), end_at(1.5, 0.2));
        for s in [0.0, 0.1, 0.25, 0.5, 0.9, 1.0] {
            let t = 1.0 + 0.5 * s;
            let got = between(&start, &end, t);
            let (p, v, a) = cubic(t);
            assert!((got.position_ned_ft - p).norm() < 1e-9, "s = {s}");
            assert!((got.velocity_ned_fps - v).norm() < 1e-9, "s = {s}");
            assert!((got.accel_ned_fps2 - a).norm() < 1e-9, "s = {s}");
        }
    }

    /// The attitude is the nearer end's.
    #[test]
    fn attitude_of_the_nearer_end() {
        let (start, end) = (end_at(0.0, 0.1), end_at(1.0, 0.2));
        assert_eq!(between(&start, &end, 0.4).attitude.phi_rad, 0.1);
        assert_eq!(between(&start, &end, 0.6).attitude.phi_rad, 0.2);
    }

    /// Past either end, and in a step of no length, the nearer end moves on at its velocity.
    #[test]
    fn outside_the_step_the_end_moves_on() {
        let (start, end) = (end_at(0.0, 0.1), end_at(1.0, 0.2));
        let later = between(&start, &end, 1.5);
        let expected = end.state.position_ned_ft + end.state.velocity_ned_fps * 0.5;
        assert!((later.position_ned_ft - expected).norm() < 1e-12);
        assert_eq!(later.attitude.phi_rad, 0.2);
        let earlier = between(&start, &end, -1.0);
        let expected = start.state.position_ned_ft - start.state.velocity_ned_fps;
        assert!((earlier.position_ned_ft - expected).norm() < 1e-12);
        let same = between(&end, &end, 1.0);
        assert_eq!(same, end.state);
    }
}
