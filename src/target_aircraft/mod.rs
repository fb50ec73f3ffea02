//! The target as a real aircraft (`target.model = "aircraft"`; docs/equations.md, The target
//! as an aircraft): a second instance of the 6-DOF aircraft of [`crate::world::aircraft`]
//! flown by its own Chapter 7 flight controller along a reference motion, any
//! [`TargetModel`]. The plant-and-controller pair is the follower's [`AircraftFollower`],
//! reused whole: its trim, its turbulence held over a step, its control and plant steps and
//! its bounds.
//!
//! - Command: V_c = V_ref(t) + k (R_ref(t) - R(t)), k = `target.track_gain_per_s`, flown
//!   through (7.1)-(7.33) as the follower flies its V_F: the reference's velocity, and a pull
//!   back onto its track so that the lag of the aircraft's velocity does not add up.
//! - Start: at R_ref(0), trimmed in straight and level flight (the steady air of
//!   `[atmosphere]`, no Δ perturbations) at the reference's horizontal velocity at t = 0
//!   through that air (less the steady wind), so that over the ground it flies the
//!   reference's; its controller at rest there. A reference that starts climbing or descending is
//!   joined by the command's feedback.
//! - Air: the run's `[atmosphere]`, with a Dryden stream of its own (`run.seed` ^
//!   [`TARGET_DRYDEN_SEED_SALT`]) advanced at the target's position and airspeed.
//! - Time: [`TargetModel::advance`] integrates the target's state over the run's step with
//!   its own RK4, before the follower's step; within the step [`TargetModel::state`]
//!   interpolates between the step's ends ([`interpolate`]).

pub mod interpolate;

use crate::follower::{AircraftActuation, AircraftFollower, AircraftSetupError, FollowerConfig};
use crate::frames::Vec3;
use crate::guidance::signals::{CommandKind, FollowerCommand};
use crate::integrate::Rk4;
use crate::scenario::check::InvalidValue;
use crate::scenario::{
    AIRCRAFT_MAX_SPEED_FPS, AIRCRAFT_MIN_SPEED_FPS, AtmosphereConfig, FollowerModel,
    FollowerSection, TargetSection,
};
use crate::world::aircraft::state::VELOCITY_BODY_FPS;
use crate::world::aircraft::{AirData, AircraftFileError, AircraftState, TrimError};
use crate::world::target::{TargetDiverged, TargetFlight, TargetModel, TargetState};
use interpolate::StepEnd;

/// Mixed into `[run] seed` for the target aircraft's Dryden turbulence, so that its gusts are
/// not the follower's ("target" in ASCII).
pub const TARGET_DRYDEN_SEED_SALT: u64 = 0x0000_7461_7267_6574;

/// Farthest the target aircraft may be from its reference, ft: beyond it its state has run
/// away (finite, but far past any flight), and the run ends `diverged` naming it. The bound
/// the run puts on the range (docs/design.md, How a run ends).
pub const MAX_OFF_TRACK_FT: f64 = 1e6;
/// Fastest the target aircraft may fly, ft/s: nearly ten times the speed of sound, beyond
/// any airframe's data this simulator flies (35-100 ft/s trims); a state past it has run away
/// within a step, before its position shows it.
pub const MAX_SPEED_FPS: f64 = 1e4;

/// Why the target aircraft could not be set up.
#[derive(Debug, thiserror::Error)]
pub enum TargetAircraftError {
    /// Its data file is unreadable or invalid.
    #[error("target.aircraft: {0}")]
    AircraftData(AircraftFileError),
    /// A value its plant, controller or air rejected.
    #[error("target aircraft: {0}")]
    Invalid(InvalidValue),
    /// The reference's horizontal speed at t = 0 is not one it can be trimmed at.
    #[error(
        "target.motion: the target aircraft starts trimmed in straight and level flight at \
         its motion's horizontal speed through the air at t = 0, {speed_fps:.2} ft/s: allowed \
         [{AIRCRAFT_MIN_SPEED_FPS}, {AIRCRAFT_MAX_SPEED_FPS}] ft/s"
    )]
    InitialSpeed {
        /// ‖(V_ref,N, V_ref,E)‖ at t = 0, ft/s.
        speed_fps: f64,
    },
    /// No straight and level trim at that speed.
    #[error("target aircraft: no level trim at its motion's speed at t = 0: {0}")]
    Trim(TrimError),
    /// The trimmed state has no air data (cannot happen with a valid trim).
    #[error("target aircraft: the trimmed state has no valid attitude")]
    TrimState,
}

impl From<AircraftSetupError> for TargetAircraftError {
    fn from(e: AircraftSetupError) -> Self {
        match e {
            AircraftSetupError::AircraftData(e) => Self::AircraftData(e),
            AircraftSetupError::Invalid(e) => Self::Invalid(e),
            AircraftSetupError::Trim(e) => Self::Trim(e),
            AircraftSetupError::TrimState => Self::TrimState,
        }
    }
}

/// A step's end: the state, and the air data the flight reports there.
#[derive(Debug, Clone, Copy, PartialEq)]
struct FlownEnd {
    end: StepEnd,
    air: AirData,
}

/// The target aircraft: its plant and controller, its reference and the ends of its last step.
#[derive(Debug)]
pub struct TargetAircraft {
    reference: Box<dyn TargetModel>,
    flyer: AircraftFollower,
    track_gain_per_s: f64,
    rk4: Rk4,
    /// Plant and controller state at `end`.
    x: Vec<f64>,
    /// Scratch for ẋ at a step's end.
    dx: Vec<f64>,
    start: FlownEnd,
    end: FlownEnd,
}

impl TargetAircraft {
    /// The target `[target]` describes, flying `reference` in the air of `atmosphere` with the
    /// turbulence stream `turbulence_seed`; trimmed at t = 0 (see the module's documentation).
    pub fn new(
        section: &TargetSection,
        atmosphere: &AtmosphereConfig,
        turbulence_seed: u64,
        reference: Box<dyn TargetModel>,
    ) -> Result<Self, TargetAircraftError> {
        let at_start = reference.state(0.0);
        // Its velocity through the air: the reference's less the steady wind.
        let [north, east, _] = at_start.velocity_ned_fps.into();
        let [wind_north, wind_east, _] = atmosphere.wind_ned_fps;
        let (north, east) = (north - wind_north, east - wind_east);
        let speed_fps = north.hypot(east);
        if !(AIRCRAFT_MIN_SPEED_FPS..=AIRCRAFT_MAX_SPEED_FPS).contains(&speed_fps) {
            return Err(TargetAircraftError::InitialSpeed { speed_fps });
        }
        let airframe = FollowerSection {
            model: FollowerModel::Aircraft,
            initial_position_ft: at_start.position_ned_ft.into(),
            initial_velocity_fps: [north, east, 0.0],
            aircraft: section.aircraft.clone(),
            ..FollowerSection::default()
        };
        let (flyer, x) = AircraftFollower::new(&FollowerConfig {
            follower: &airframe,
            autopilot: &section.autopilot,
            atmosphere,
            turbulence_seed,
            command_kind: CommandKind::Velocity,
        })?;
        let mut dx = vec![0.0; x.len()];
        let k = section.track_gain_per_s;
        let first = flown_end(&flyer, reference.as_ref(), k, 0.0, &x, &mut dx)
            .ok_or(TargetAircraftError::TrimState)?;
        Ok(Self {
            reference,
            flyer,
            track_gain_per_s: k,
            rk4: Rk4::new(x.len()),
            x,
            dx,
            start: first,
            end: first,
        })
    }

    /// The step's end at `t_end_s`, once the state is known to be flying: finite, with a
    /// usable attitude, within [`MAX_OFF_TRACK_FT`] of the reference and below
    /// [`MAX_SPEED_FPS`].
    fn checked_end(&mut self, t_end_s: f64) -> Result<FlownEnd, TargetDiverged> {
        let diverged = |what: String| TargetDiverged { what };
        if let Some(i) = self.x.iter().position(|v| !v.is_finite()) {
            return Err(diverged(format!(
                "{} is {}",
                Self::state_name(i),
                self.x[i]
            )));
        }
        let (flyer, reference) = (&self.flyer, self.reference.as_ref());
        let k = self.track_gain_per_s;
        let end = flown_end(flyer, reference, k, t_end_s, &self.x, &mut self.dx)
            .ok_or_else(|| diverged("target aircraft: its attitude quaternion is zero".into()))?;
        let off_track_ft =
            (end.end.state.position_ned_ft - reference.position_ned_ft(t_end_s)).norm();
        if off_track_ft > MAX_OFF_TRACK_FT {
            return Err(diverged(format!(
                "target aircraft: {off_track_ft:.3e} ft from its reference, beyond \
                 {MAX_OFF_TRACK_FT:e} ft"
            )));
        }
        let speed_fps = end.end.state.velocity_ned_fps.norm();
        if speed_fps > MAX_SPEED_FPS {
            return Err(diverged(format!(
                "target aircraft: speed {speed_fps:.3e} ft/s, beyond {MAX_SPEED_FPS:e} ft/s"
            )));
        }
        Ok(end)
    }

    /// Names the state's element `i` for a message ("target aircraft: body velocity, ft/s (w)").
    fn state_name(i: usize) -> String {
        let mut names = crate::world::aircraft::state::state_names();
        names.extend(crate::control::autopilot_state_names());
        let name = names.get(i).map_or("state", String::as_str);
        format!(
            "target aircraft: {}",
            name.strip_prefix("aircraft: ").unwrap_or(name)
        )
    }
}

/// ẋ of the target's plant and controller at (t, x) under V_c = V_ref + k (R_ref - R), and
/// the controller's decision.
fn flight_derivative(
    flyer: &AircraftFollower,
    reference: &dyn TargetModel,
    track_gain_per_s: f64,
    t_s: f64,
    x: &[f64],
    dx: &mut [f64],
) -> Option<AircraftActuation> {
    let wanted = reference.state(t_s);
    let off_track = wanted.position_ned_ft - AircraftFollower::position_ned_ft(x);
    let command = FollowerCommand::Velocity(wanted.velocity_ned_fps + off_track * track_gain_per_s);
    let actuation = flyer.control(x, &command, dx);
    flyer.plant(x, actuation.as_ref(), dx);
    actuation
}

/// The state and air data at a step's end (t, x), ẋ left in `dx`; `None` when the plant's
/// state has no usable attitude.
fn flown_end(
    flyer: &AircraftFollower,
    reference: &dyn TargetModel,
    track_gain_per_s: f64,
    t_s: f64,
    x: &[f64],
    dx: &mut [f64],
) -> Option<FlownEnd> {
    let air = flight_derivative(flyer, reference, track_gain_per_s, t_s, x, dx)?.air_data;
    let plant = AircraftState::unpack(x)?;
    let body_accel = Vec3::from_column_slice(&dx[VELOCITY_BODY_FPS..VELOCITY_BODY_FPS + 3]);
    // v̇_NED = R(q) (v̇_b + ω × v_b): the body-axis rate plus the turning of the axes.
    let accel_ned_fps2 =
        plant.attitude * (body_accel + plant.body_rates_rps.cross(&plant.velocity_body_fps));
    Some(FlownEnd {
        end: StepEnd {
            t_s,
            state: TargetState {
                position_ned_ft: plant.position_ned_ft,
                velocity_ned_fps: plant.velocity_ned_fps(),
                accel_ned_fps2,
                attitude: plant.euler(),
            },
        },
        air,
    })
}

impl TargetModel for TargetAircraft {
    fn advance(&mut self, t_s: f64, dt_s: f64) -> Result<(), TargetDiverged> {
        self.reference.advance(t_s, dt_s)?;
        self.flyer.begin_step(&self.x, dt_s);
        let (flyer, reference, k) = (&self.flyer, self.reference.as_ref(), self.track_gain_per_s);
        self.rk4.step(t_s, dt_s, &mut self.x, |t, x, dx| {
            flight_derivative(flyer, reference, k, t, x, dx);
        });
        self.flyer.normalize(&mut self.x);
        let end = self.checked_end(t_s + dt_s)?;
        self.start = std::mem::replace(&mut self.end, end);
        Ok(())
    }

    fn state(&self, t_s: f64) -> TargetState {
        interpolate::between(&self.start.end, &self.end.end, t_s)
    }

    /// Air data of the nearer end of the step (as the attitude), the reference at `t_s`.
    fn flight(&self, t_s: f64) -> Option<TargetFlight> {
        let halfway = 0.5 * (self.start.end.t_s + self.end.end.t_s);
        let air = if t_s < halfway { self.start } else { self.end }.air;
        Some(TargetFlight {
            airspeed_fps: air.airspeed_fps,
            alpha_rad: air.alpha_rad,
            beta_rad: air.beta_rad,
            reference_ned_ft: self.reference.position_ned_ft(t_s),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::target::TargetMotionModel;

    const DT_S: f64 = 0.002;

    fn seed_target(section: &TargetSection) -> Result<TargetAircraft, TargetAircraftError> {
        TargetAircraft::new(
            section,
            &AtmosphereConfig::default(),
            1,
            Box::new(TargetMotionModel::from_section(section).expect("a closed-form motion")),
        )
    }

    /// It starts where its reference does, trimmed level at its speed: velocity along the
    /// reference's, nose above it by α.
    #[test]
    fn starts_trimmed_on_the_reference() {
        let target = seed_target(&TargetSection::default()).expect("set-up");
        let s = target.state(0.0);
        assert_eq!(s.position_ned_ft, Vec3::new(200.0, 50.0, 30.0));
        assert!((s.velocity_ned_fps - Vec3::new(50.0, 0.0, 0.0)).norm() < 1e-6);
        let alpha_rad = target.flight(0.0).expect("flies").alpha_rad;
        assert!(alpha_rad > 2f64.to_radians(), "α = {alpha_rad}");
        assert!((s.attitude.theta_rad - alpha_rad).abs() < 1e-6);
        assert!(s.accel_ned_fps2.norm() < 1e-3, "{:?}", s.accel_ned_fps2);
    }

    /// The acceleration reported at a step's end is the rate of the velocity (central
    /// differences over the neighbouring steps), in the seed profile's first turn.
    #[test]
    fn acceleration_is_the_rate_of_velocity() {
        let mut target = seed_target(&TargetSection::default()).expect("set-up");
        let mut velocities = Vec::new();
        for i in 0..5000 {
            target.advance(i as f64 * DT_S, DT_S).expect("finite");
            velocities.push(target.state((i + 1) as f64 * DT_S).velocity_ned_fps);
        }
        let (mid, t_s) = (velocities.len() - 2, (velocities.len() - 1) as f64 * DT_S);
        let difference = (velocities[mid + 1] - velocities[mid - 1]) / (2.0 * DT_S);
        let reported =
            interpolate::between(&target.start.end, &target.end.end, t_s - DT_S).accel_ned_fps2;
        assert!(difference.norm() > 0.5, "not manoeuvring: {difference:?}");
        assert!(
            (reported - difference).norm() < 1e-3 * difference.norm().max(1.0),
            "{reported:?} vs {difference:?}"
        );
    }

    /// A state that turns NaN ends the step with an error naming the target aircraft.
    #[test]
    fn divergence_names_the_target_aircraft() {
        let mut target = seed_target(&TargetSection::default()).expect("set-up");
        target.x[VELOCITY_BODY_FPS + 2] = f64::NAN;
        let what = target.advance(0.0, DT_S).expect_err("diverged").what;
        assert!(what.starts_with("target aircraft: "), "{what}");
        assert!(what.ends_with(" is NaN"), "{what}");
        assert_eq!(
            TargetAircraft::state_name(VELOCITY_BODY_FPS + 2),
            "target aircraft: body velocity, ft/s (w)"
        );
    }

    /// In a steady crosswind the target aircraft flies its reference over the ground from the
    /// start (trimmed at its speed through the air, so that nothing is left for the track
    /// feedback to correct), and the motion carried by the air mass at its speed through the
    /// air, drifting with the wind. A trim in steady air is flown to rounding: measured within
    /// 1e-7 ft after 20 s, so 1e-3 ft; a trim at the ground speed would start 15 ft/s off.
    #[test]
    fn a_crosswind_is_flown_over_the_ground_or_drifted_with() {
        use crate::world::target::CarriedByAir;
        let wind_ned_fps = [0.0, 15.0, 0.0];
        let air = AtmosphereConfig {
            wind_ned_fps,
            ..AtmosphereConfig::default()
        };
        let section = TargetSection {
            motion: crate::scenario::TargetMotion::Straight,
            straight_velocity_fps: [50.0, 0.0, 0.0],
            ..TargetSection::default()
        };
        let motion = || Box::new(TargetMotionModel::from_section(&section).expect("closed form"));
        let flown = |reference: Box<dyn TargetModel>| {
            let mut target = TargetAircraft::new(&section, &air, 1, reference).expect("set-up");
            let steps = 10_000;
            for i in 0..steps {
                target.advance(i as f64 * DT_S, DT_S).expect("finite");
            }
            let t_s = steps as f64 * DT_S;
            (target.state(t_s), target.flight(t_s).expect("flies"), t_s)
        };
        let (state, flight, t_s) = flown(motion());
        let over_ground = Vec3::new(200.0 + 50.0 * t_s, 50.0, 30.0);
        assert!(
            (state.position_ned_ft - over_ground).norm() < 1e-3,
            "{state:?}"
        );
        let through_air_fps = 50f64.hypot(15.0);
        assert!(
            (flight.airspeed_fps - through_air_fps).abs() < 1e-3,
            "{flight:?}"
        );
        let (state, flight, t_s) = flown(Box::new(CarriedByAir::new(motion(), wind_ned_fps, None)));
        let carried = over_ground + Vec3::from(wind_ned_fps) * t_s;
        assert!((state.position_ned_ft - carried).norm() < 1e-3, "{state:?}");
        assert!((flight.airspeed_fps - 50.0).abs() < 1e-3, "{flight:?}");
    }

    /// A reference too slow to trim at is refused, naming its speed.
    #[test]
    fn a_reference_too_slow_is_refused() {
        let section = TargetSection {
            motion: crate::scenario::TargetMotion::Straight,
            straight_velocity_fps: [20.0, 0.0, -3.0],
            ..TargetSection::default()
        };
        let message = seed_target(&section).expect_err("refused").to_string();
        assert!(message.contains("20.00 ft/s"), "{message}");
    }
}
