//! The angle of attack the target's airframe needs, for the airframe size model's inferred
//! attitude (`estimator.airframe_angle_of_attack = "trim"`): an aircraft in coordinated flight
//! does not point its nose along its velocity but α above it, the α whose lift carries its
//! weight times the load factor at its airspeed.
//!
//! α is tabulated once per run from the target's aircraft data (`target.aircraft`) by trimming
//! it in straight and level flight ([`trim_level_flight`]) at airspeeds every
//! [`SPEED_STEP_FPS`] from [`SPEED_MIN_FPS`] to [`SPEED_MAX_FPS`], in the air of
//! `[atmosphere]` at the target's starting height; airspeeds that do not trim (beyond the
//! stall, or short of throttle) take the nearest trimmed one's α. In a turn or a pull-up of
//! load factor n the lift must be n times the weight, which level flight gives at the
//! airspeed V/√n: α(V, n) = α_trim(V/√n) (the elevator's and thrust's small shares of the
//! lift aside).
//!
//! The airspeed is the estimated ground velocity less the scenario's steady wind
//! (`atmosphere.wind_ned_fps`, which the follower's air data measure on average; the gusts of
//! either aircraft are not known to the estimator), the load factor the specific force across
//! that velocity over g.

use crate::frames::{GRAVITY_FPS2, Vec3};
use crate::world::aircraft::{Aircraft, TrimRequest, trim_level_flight};
use crate::world::atmosphere::AtmosphereSample;

/// The slowest airspeed tabulated, ft/s.
pub const SPEED_MIN_FPS: f64 = 20.0;
/// The fastest airspeed tabulated, ft/s.
pub const SPEED_MAX_FPS: f64 = 200.0;
/// The table's airspeed step, ft/s.
pub const SPEED_STEP_FPS: f64 = 2.5;
/// The load factors α is looked up for are held to [1/LOAD_LIMIT, LOAD_LIMIT] (a noisy
/// acceleration estimate near zero g or beyond 4 g says nothing about the lift).
const LOAD_LIMIT: f64 = 4.0;

/// α over airspeed for one airframe in one air mass.
#[derive(Debug, Clone, PartialEq)]
pub struct AlphaSchedule {
    /// α at SPEED_MIN_FPS + i SPEED_STEP_FPS, rad.
    alphas_rad: Vec<f64>,
    /// The steady wind the airspeed is reckoned against, NED, ft/s.
    wind_ned_fps: Vec3,
}

impl AlphaSchedule {
    /// The schedule of `aircraft` trimmed in `air` (gusts ignored) at `position_ned_ft`;
    /// `None` when it trims at no tabulated airspeed.
    pub fn of_aircraft(
        aircraft: &Aircraft,
        air: &AtmosphereSample,
        position_ned_ft: &Vec3,
    ) -> Option<Self> {
        let nodes = ((SPEED_MAX_FPS - SPEED_MIN_FPS) / SPEED_STEP_FPS).round() as usize + 1;
        let trimmed: Vec<Option<f64>> = (0..nodes)
            .map(|i| {
                let request = TrimRequest {
                    airspeed_fps: SPEED_MIN_FPS + i as f64 * SPEED_STEP_FPS,
                    position_ned_ft: *position_ned_ft,
                    heading_rad: 0.0,
                    air: *air,
                };
                trim_level_flight(aircraft, &request)
                    .ok()
                    .map(|t| t.alpha_rad)
            })
            .collect();
        let known: Vec<(usize, f64)> = trimmed
            .iter()
            .enumerate()
            .filter_map(|(i, a)| a.map(|a| (i, a)))
            .collect();
        let nearest = |i: usize| {
            known
                .iter()
                .min_by_key(|(j, _)| j.abs_diff(i))
                .map(|(_, a)| *a)
        };
        let alphas_rad = (0..nodes).map(nearest).collect::<Option<Vec<f64>>>()?;
        Some(Self {
            alphas_rad,
            wind_ned_fps: air.wind_ned_fps,
        })
    }

    /// α in level flight at `airspeed_fps`, rad, interpolated linearly (held beyond the
    /// table's ends).
    pub fn level_flight_alpha_rad(&self, airspeed_fps: f64) -> f64 {
        let x = ((airspeed_fps - SPEED_MIN_FPS) / SPEED_STEP_FPS).max(0.0);
        let last = self.alphas_rad.len() - 1;
        let i = (x.floor() as usize).min(last.saturating_sub(1));
        let frac = (x - i as f64).clamp(0.0, 1.0);
        let next = self.alphas_rad[(i + 1).min(last)];
        self.alphas_rad[i] + frac * (next - self.alphas_rad[i])
    }

    /// α of a target flying at `velocity_ned_fps` (over the ground) with acceleration
    /// `accel_ned_fps2`, rad (module docs); 0 when it is not moving through the air.
    pub fn alpha_rad(&self, velocity_ned_fps: &Vec3, accel_ned_fps2: &Vec3) -> f64 {
        let air_velocity = velocity_ned_fps - self.wind_ned_fps;
        let Some(forward) = air_velocity.try_normalize(1e-9) else {
            return 0.0;
        };
        let specific_force = accel_ned_fps2 - Vec3::new(0.0, 0.0, GRAVITY_FPS2);
        let across = specific_force - forward * specific_force.dot(&forward);
        let load = (across.norm() / GRAVITY_FPS2).clamp(1.0 / LOAD_LIMIT, LOAD_LIMIT);
        self.level_flight_alpha_rad(air_velocity.norm() / load.sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::aircraft::AircraftParams;

    fn schedule(wind_ned_fps: Vec3) -> AlphaSchedule {
        let aircraft =
            Aircraft::new(AircraftParams::seed_follower().expect("shipped data")).expect("valid");
        let air = AtmosphereSample {
            wind_ned_fps,
            ..AtmosphereSample::default()
        };
        AlphaSchedule::of_aircraft(&aircraft, &air, &Vec3::zeros()).expect("trims")
    }

    /// The shipped airframe (assets/aircraft/follower.toml) trims at 4.48° at 50 ft/s at sea
    /// level; slower it needs more (about 13° at 35 ft/s); below its stall the table holds the
    /// slowest trim's α; a 2 g turn at 50 ft/s needs the α of level flight at 50/√2 ft/s.
    #[test]
    fn trim_alpha_of_the_shipped_airframe() {
        let s = schedule(Vec3::zeros());
        let at_50 = s.level_flight_alpha_rad(50.0).to_degrees();
        assert!((at_50 - 4.48).abs() < 0.02, "{at_50}");
        let at_35 = s.level_flight_alpha_rad(35.0).to_degrees();
        assert!((11.0..15.0).contains(&at_35), "{at_35}");
        assert_eq!(
            s.level_flight_alpha_rad(1.0),
            s.level_flight_alpha_rad(20.0)
        );
        let v = Vec3::new(50.0, 0.0, 0.0);
        assert!((s.alpha_rad(&v, &Vec3::zeros()).to_degrees() - at_50).abs() < 1e-9);
        let bank = Vec3::new(0.0, 3f64.sqrt() * GRAVITY_FPS2, 0.0);
        let turning = s.alpha_rad(&v, &bank);
        let slower = s.level_flight_alpha_rad(50.0 / 2f64.sqrt());
        assert!((turning - slower).abs() < 1e-9, "{turning} {slower}");
    }

    /// Into a 15 ft/s headwind a target making 35 ft/s over the ground flies at 50 ft/s of
    /// airspeed.
    #[test]
    fn the_steady_wind_sets_the_airspeed() {
        let s = schedule(Vec3::new(-15.0, 0.0, 0.0));
        let over_ground = s.alpha_rad(&Vec3::new(35.0, 0.0, 0.0), &Vec3::zeros());
        assert!((over_ground - s.level_flight_alpha_rad(50.0)).abs() < 1e-12);
    }
}
