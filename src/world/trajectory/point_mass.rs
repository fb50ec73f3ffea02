//! The kinematic point mass that waypoint and random trajectories fly (docs/equations.md,
//! Trajectory sources for the target): airspeed V, heading χ and climb rate ḣ, each following
//! its command inside the target's limits with continuous rates, so that the track's velocity
//! and acceleration are continuous; integrated by RK4 and sampled into a [`SampledTrack`].

use super::sampled::{Knot, SampledTrack};
use crate::frames::{GRAVITY_FPS2, Vec3};
use crate::integrate::Rk4;
use crate::scenario::TargetSection;

/// Integration step of the point mass, s: a hundredth of a second resolves the fastest of
/// its responses (a quarter of `target.response_time_s` ≥ 0.025 s) with RK4.
const INTEGRATION_STEP_S: f64 = 0.01;
/// Integration steps between stored knots: knots 0.1 s apart, interpolated by quintics, are
/// within millimetres of the integrated track and keep the longest run (10⁵ s) under 100 MB.
const STEPS_PER_KNOT: usize = 10;

/// State layout: north, east, down (ft), airspeed V (ft/s), heading χ (rad), climb rate ḣ
/// (ft/s, up), bank φ (rad), along-track acceleration V̇ (ft/s²), vertical acceleration ḧ
/// (ft/s², up).
const STATE_LEN: usize = 9;
const SPEED: usize = 3;
const HEADING: usize = 4;
const CLIMB: usize = 5;
const BANK: usize = 6;
const ACCEL: usize = 7;
const VERTICAL_ACCEL: usize = 8;

/// What the point mass may do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Limits {
    /// Largest bank, rad.
    pub bank_max_rad: f64,
    /// Largest climb or descent rate, ft/s.
    pub climb_rate_max_fps: f64,
    /// Largest along-track acceleration, ft/s².
    pub accel_max_fps2: f64,
    /// Largest vertical acceleration, ft/s².
    pub vertical_accel_max_fps2: f64,
    /// Largest roll rate, rad/s.
    pub roll_rate_max_rps: f64,
    /// Time constant of the speed, climb-rate and heading responses, s.
    pub response_time_s: f64,
}

impl Limits {
    /// The `[target]` limits with a bank and climb rate of the motion's own.
    pub fn of(target: &TargetSection, bank_max_deg: f64, climb_rate_max_fps: f64) -> Self {
        Self {
            bank_max_rad: bank_max_deg.to_radians(),
            climb_rate_max_fps,
            accel_max_fps2: target.accel_max_fps2,
            vertical_accel_max_fps2: target.vertical_accel_max_fps2,
            roll_rate_max_rps: target.roll_rate_max_dps.to_radians(),
            response_time_s: target.response_time_s,
        }
    }
}

/// What the point mass is told to fly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Command {
    /// Airspeed, ft/s.
    pub speed_fps: f64,
    /// Bank, rad (clamped to the limit).
    pub bank_rad: f64,
    /// Climb rate, ft/s, positive up (clamped to the limit).
    pub climb_rate_fps: f64,
}

/// The point mass's state, read by the one who commands it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct PointMass {
    x: [f64; STATE_LEN],
}

impl PointMass {
    /// Straight and level at `position`, airspeed `speed_fps`, heading `heading_rad`.
    pub fn level(position_ned_ft: Vec3, speed_fps: f64, heading_rad: f64) -> Self {
        let mut x = [0.0; STATE_LEN];
        x[..3].copy_from_slice(position_ned_ft.as_slice());
        x[SPEED] = speed_fps;
        x[HEADING] = heading_rad;
        Self { x }
    }

    /// R, NED, ft.
    pub fn position_ned_ft(&self) -> Vec3 {
        Vec3::new(self.x[0], self.x[1], self.x[2])
    }

    /// Airspeed V, ft/s.
    pub fn speed_fps(&self) -> f64 {
        self.x[SPEED]
    }

    /// Heading χ, rad (not wrapped).
    pub fn heading_rad(&self) -> f64 {
        self.x[HEADING]
    }

    /// The knot at `t_s`: position, velocity and its exact derivative.
    fn knot(&self, t_s: f64) -> Knot {
        let x = &self.x;
        let (speed, heading, climb) = (x[SPEED], x[HEADING], x[CLIMB]);
        let horizontal = (speed * speed - climb * climb).max(0.0).sqrt();
        let horizontal_rate = if horizontal > 0.0 {
            (speed * x[ACCEL] - climb * x[VERTICAL_ACCEL]) / horizontal
        } else {
            0.0
        };
        let turn_rate = GRAVITY_FPS2 * x[BANK].tan() / speed;
        let (sin, cos) = heading.sin_cos();
        Knot {
            t_s,
            position_ned_ft: self.position_ned_ft(),
            velocity_ned_fps: Vec3::new(horizontal * cos, horizontal * sin, -climb),
            accel_ned_fps2: Vec3::new(
                horizontal_rate * cos - horizontal * sin * turn_rate,
                horizontal_rate * sin + horizontal * cos * turn_rate,
                -x[VERTICAL_ACCEL],
            ),
        }
    }
}

/// ẋ of the point mass under a command held over the step: the heading turns at g tan φ / V
/// ((7.14) read backwards: the coordinated turn at bank φ); the bank follows its command with
/// a time constant of a quarter of the response time and at most the roll rate; speed and
/// climb rate follow theirs as critically damped second-order responses whose accelerations
/// (states, so continuous) chase (command - value) / τ, clamped to the limits, with τ / 4.
fn derivative(x: &[f64], command: &Command, limits: &Limits, out: &mut [f64]) {
    let tau = limits.response_time_s;
    let fast = 0.25 * tau;
    let (speed, heading, climb) = (x[SPEED], x[HEADING], x[CLIMB]);
    let horizontal = (speed * speed - climb * climb).max(0.0).sqrt();
    out[0] = horizontal * heading.cos();
    out[1] = horizontal * heading.sin();
    out[2] = -climb;
    out[SPEED] = x[ACCEL];
    out[HEADING] = GRAVITY_FPS2 * x[BANK].tan() / speed;
    out[CLIMB] = x[VERTICAL_ACCEL];
    let bank = command
        .bank_rad
        .clamp(-limits.bank_max_rad, limits.bank_max_rad);
    let roll = limits.roll_rate_max_rps;
    out[BANK] = ((bank - x[BANK]) / fast).clamp(-roll, roll);
    let accel = limits.accel_max_fps2;
    let wanted = ((command.speed_fps - speed) / tau).clamp(-accel, accel);
    out[ACCEL] = (wanted - x[ACCEL]) / fast;
    let climb_max = limits.climb_rate_max_fps;
    let climb_cmd = command.climb_rate_fps.clamp(-climb_max, climb_max);
    let vertical = limits.vertical_accel_max_fps2;
    let wanted = ((climb_cmd - climb) / tau).clamp(-vertical, vertical);
    out[VERTICAL_ACCEL] = (wanted - x[VERTICAL_ACCEL]) / fast;
}

/// Flies the point mass from `start` to at least `duration_s` under `pilot`'s commands
/// (asked at every integration step, held over it) and samples the flown track.
pub(super) fn fly(
    start: PointMass,
    limits: &Limits,
    duration_s: f64,
    mut pilot: impl FnMut(f64, &PointMass) -> Command,
) -> SampledTrack {
    let knot_step_s = INTEGRATION_STEP_S * STEPS_PER_KNOT as f64;
    let knots_len = (duration_s / knot_step_s).ceil() as usize + 2;
    let mut rk4 = Rk4::new(STATE_LEN);
    let mut mass = start;
    let mut knots = Vec::with_capacity(knots_len);
    knots.push(mass.knot(0.0));
    for k in 1..knots_len {
        for i in 0..STEPS_PER_KNOT {
            let t_s = ((k - 1) * STEPS_PER_KNOT + i) as f64 * INTEGRATION_STEP_S;
            let command = pilot(t_s, &mass);
            rk4.step(t_s, INTEGRATION_STEP_S, &mut mass.x, |_, x, out| {
                derivative(x, &command, limits, out)
            });
        }
        knots.push(mass.knot(k as f64 * knot_step_s));
    }
    SampledTrack::flown(knots)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::target::TargetModel;

    fn limits() -> Limits {
        Limits::of(&TargetSection::default(), 30.0, 5.0)
    }

    /// Held at the bank limit, the point mass turns on the circle of radius V²/(g tan φ).
    #[test]
    fn steady_turn_radius() {
        let start = PointMass::level(Vec3::zeros(), 50.0, 0.0);
        let command = Command {
            speed_fps: 50.0,
            bank_rad: 1.0,
            climb_rate_fps: 0.0,
        };
        let track = fly(start, &limits(), 120.0, |_, _| command);
        let radius = 50.0 * 50.0 / (GRAVITY_FPS2 * 30f64.to_radians().tan());
        // Once rolled in, the track's curvature is the turn's.
        let s = track.state(60.0);
        let v = s.velocity_ned_fps;
        let curvature = v.cross(&s.accel_ned_fps2).norm() / v.norm().powi(3);
        assert!(
            (1.0 / curvature - radius).abs() < 1e-3 * radius,
            "{}",
            1.0 / curvature
        );
        assert!((s.attitude.phi_rad - 30f64.to_radians()).abs() < 1e-6);
    }

    /// A step in every command is followed without overshoot and inside every rate limit.
    #[test]
    fn steps_respect_limits() {
        let l = limits();
        let start = PointMass::level(Vec3::zeros(), 40.0, 0.0);
        let command = Command {
            speed_fps: 60.0,
            bank_rad: -1.0,
            climb_rate_fps: 10.0,
        };
        let track = fly(start, &l, 40.0, |_, _| command);
        let mut previous_bank = 0.0;
        for i in 0..4000 {
            let s = track.state(i as f64 * 0.01);
            let v = s.velocity_ned_fps;
            assert!(v.norm() <= 60.0 + 1e-6 && -v.z <= 5.0 + 1e-6, "{v:?}");
            let along = v.dot(&s.accel_ned_fps2) / v.norm();
            assert!(along.abs() <= l.accel_max_fps2 + 1e-6, "{along}");
            assert!(s.accel_ned_fps2.z.abs() <= l.vertical_accel_max_fps2 + 1e-6);
            let bank = s.attitude.phi_rad;
            assert!(bank >= -l.bank_max_rad - 1e-9);
            assert!((bank - previous_bank).abs() <= l.roll_rate_max_rps * 0.01 + 1e-6);
            previous_bank = bank;
        }
    }
}
