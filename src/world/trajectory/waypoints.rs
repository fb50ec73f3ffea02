//! `target.motion = "waypoints"` (docs/equations.md, Trajectory sources for the target): the
//! point mass flies from `target.initial_position_ft` to each waypoint in turn, pointing its
//! heading at the waypoint through coordinated turns at up to `target.bank_limit_deg`,
//! climbing or descending to be at its height when it is reached, at the waypoint's speed. A waypoint is
//! reached when it is horizontally within the reach radius (see [`reach_radius_ft`]); the
//! next is then flown to. After the last the target rolls level and flies straight and level
//! on at the last speed.

use super::point_mass::{Command, Limits, PointMass, fly};
use super::sampled::SampledTrack;
use crate::frames::{GRAVITY_FPS2, Vec3, wrap_angle_rad};
use crate::scenario::TargetSection;
use std::f64::consts::FRAC_PI_2;

/// The horizontal distance within which a waypoint counts as reached, ft: the radius of the
/// smallest circle the pursuit can fly around a point, V / min(g tan φ_max / V, (π/2) / τ).
/// Its turn rate is the heading error over the response time τ, at most that of the bank
/// limit; a point abeam (heading error π/2) is circled at that radius, so a waypoint inside
/// it would be circled for ever and one outside it is flown to. It is the turn radius
/// V²/(g tan φ_max) unless τ is long.
pub fn reach_radius_ft(speed_fps: f64, bank_limit_rad: f64, response_time_s: f64) -> f64 {
    let turn_rate_rps =
        (GRAVITY_FPS2 * bank_limit_rad.tan() / speed_fps).min(FRAC_PI_2 / response_time_s);
    speed_fps / turn_rate_rps
}

/// What flies the point mass from waypoint to waypoint.
struct WaypointPilot {
    /// Position and speed of each waypoint.
    waypoints: Vec<(Vec3, f64)>,
    /// The waypoint flown to (`waypoints.len()` after the last).
    next: usize,
    limits: Limits,
}

impl WaypointPilot {
    /// The command at the point mass's state, after passing the waypoints it has reached.
    fn command(&mut self, mass: &PointMass) -> Command {
        let here = mass.position_ned_ft();
        let speed_fps = mass.speed_fps();
        let reach_ft = reach_radius_ft(
            speed_fps,
            self.limits.bank_max_rad,
            self.limits.response_time_s,
        );
        while self
            .waypoints
            .get(self.next)
            .is_some_and(|(at, _)| horizontal_ft(&(at - here)) <= reach_ft)
        {
            self.next += 1;
        }
        let Some((at, leg_speed_fps)) = self.waypoints.get(self.next) else {
            let last_speed_fps = self.waypoints.last().map_or(speed_fps, |w| w.1);
            return Command {
                speed_fps: last_speed_fps,
                bank_rad: 0.0,
                climb_rate_fps: 0.0,
            };
        };
        let to_go = at - here;
        let heading_error_rad = wrap_angle_rad(to_go.y.atan2(to_go.x) - mass.heading_rad());
        let turn_rate_rps = heading_error_rad / self.limits.response_time_s;
        // Climb so as to be at the waypoint's height when it is reached: the height to go
        // over the time to the reach circle, or over the response time once closer.
        let time_to_go_s =
            ((horizontal_ft(&to_go) - reach_ft) / speed_fps).max(self.limits.response_time_s);
        Command {
            speed_fps: *leg_speed_fps,
            bank_rad: (turn_rate_rps * speed_fps / GRAVITY_FPS2).atan(),
            climb_rate_fps: -to_go.z / time_to_go_s,
        }
    }
}

fn horizontal_ft(v: &Vec3) -> f64 {
    v.x.hypot(v.y)
}

/// The track `[target]` describes with `motion = "waypoints"`, flown to at least
/// `duration_s`. The target starts level at the first waypoint's speed, heading for it.
pub fn waypoint_track(target: &TargetSection, duration_s: f64) -> SampledTrack {
    let limits = Limits::of(target, target.bank_limit_deg, target.climb_rate_max_fps);
    let waypoints: Vec<(Vec3, f64)> = target
        .waypoints
        .iter()
        .map(|w| (Vec3::from(w.position_ft), w.speed_fps))
        .collect();
    let start = Vec3::from(target.initial_position_ft);
    // Validation gives at least one waypoint; without, the seed's start: north at 50 ft/s.
    let (first, speed_fps) = waypoints.first().copied().unwrap_or((start, 50.0));
    let to_first = first - start;
    let heading_rad = if horizontal_ft(&to_first) > 0.0 {
        to_first.y.atan2(to_first.x)
    } else {
        0.0
    };
    let mut pilot = WaypointPilot {
        waypoints,
        next: 0,
        limits,
    };
    fly(
        PointMass::level(start, speed_fps, heading_rad),
        &limits,
        duration_s,
        |_, mass| pilot.command(mass),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::{TargetMotion, Waypoint};
    use crate::world::target::TargetModel;

    fn section(waypoints: &[([f64; 3], f64)]) -> TargetSection {
        TargetSection {
            motion: TargetMotion::Waypoints,
            initial_position_ft: [0.0; 3],
            waypoints: waypoints
                .iter()
                .map(|(position_ft, speed_fps)| Waypoint {
                    position_ft: *position_ft,
                    speed_fps: *speed_fps,
                })
                .collect(),
            ..TargetSection::default()
        }
    }

    /// The reach radius is the turn radius at the bank limit unless the response is slow.
    #[test]
    fn reach_radius_is_turn_radius() {
        let bank = 30f64.to_radians();
        let turn = 2500.0 / (GRAVITY_FPS2 * bank.tan());
        assert!((reach_radius_ft(50.0, bank, 2.0) - turn).abs() < 1e-9);
        let slow = reach_radius_ft(50.0, bank, 10.0);
        assert!((slow - 50.0 * 10.0 / FRAC_PI_2).abs() < 1e-9);
    }

    /// A waypoint straight ahead is flown to in a straight line, then the target flies on.
    #[test]
    fn straight_ahead_then_on() {
        let track = waypoint_track(&section(&[([1000.0, 0.0, 0.0], 50.0)]), 60.0);
        for t in [10.0, 30.0, 50.0] {
            let s = track.state(t);
            assert!((s.position_ned_ft - Vec3::new(50.0 * t, 0.0, 0.0)).norm() < 1e-6);
        }
    }

    /// A waypoint behind the start is reached after a turn; so is the one after it.
    #[test]
    fn turns_back_for_a_waypoint_behind() {
        let wps = [([-500.0, 100.0, -40.0], 45.0), ([0.0, 600.0, 0.0], 55.0)];
        let track = waypoint_track(&section(&wps), 120.0);
        for (at, speed) in wps {
            let reach = reach_radius_ft(speed, 30f64.to_radians(), 2.0);
            let closest = (0..12_000)
                .map(|i| {
                    horizontal_ft(&(track.state(i as f64 * 0.01).position_ned_ft - Vec3::from(at)))
                })
                .fold(f64::INFINITY, f64::min);
            assert!(closest <= reach * 1.05, "{closest} > {reach}");
        }
    }
}
