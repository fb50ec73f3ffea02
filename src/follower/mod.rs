//! The follower stage as the simulation sees it (`[follower] model`): the
//! kinematic follower of the seed's Chapters 4-6 ([`KinematicFollower`]), or the 6-DOF
//! aircraft flown by the Chapter 7 flight controller ([`AircraftFollower`]). Which kind of
//! command it is given (V_F or a_F) is decided by the simulation and handed in with its
//! configuration ([`FollowerConfig`]).
//!
//! Both own a slice of the simulation's state and answer the same questions: where the
//! follower is, how it is oriented (camera = body), how it turns, how fast it goes. Each RK4
//! stage runs two steps, timed apart by the simulation: [`Follower::control`] (the flight
//! controller's decision: nothing for the kinematic follower) and [`Follower::plant`] (the
//! equations of motion under that decision).

pub mod aircraft;
pub mod envelope;
pub mod kinematic;

pub use aircraft::{AircraftActuation, AircraftFollower, AircraftSetupError, SlotLine};
pub use envelope::{FlightEnvelope, LimitTicks};
pub use kinematic::KinematicFollower;

use crate::frames::{EulerAngles, Vec3};
use crate::guidance::signals::{CommandKind, FollowerCommand, FollowerFeedback};
use crate::scenario::{AtmosphereConfig, AutopilotSection, FollowerModel, FollowerSection};

/// Everything the follower stage is built from.
#[derive(Debug, Clone, Copy)]
pub struct FollowerConfig<'a> {
    /// `[follower]`.
    pub follower: &'a FollowerSection,
    /// `[autopilot]` (6-DOF follower).
    pub autopilot: &'a AutopilotSection,
    /// `[atmosphere]` (6-DOF follower).
    pub atmosphere: &'a AtmosphereConfig,
    /// Seed of the turbulence's random stream (6-DOF follower).
    pub turbulence_seed: u64,
    /// The kind of command the guidance law gives.
    pub command_kind: CommandKind,
}

/// The follower of a run.
#[derive(Debug, Clone)]
pub enum Follower {
    /// Realises the guidance command exactly (seed Chapters 4-6).
    Kinematic(KinematicFollower),
    /// 6-DOF aircraft and flight controller (seed Chapter 7).
    Aircraft(Box<AircraftFollower>),
}

/// What the follower's control step decided at one instant.
///
/// Returned by value from every RK4 stage; boxing the aircraft's decision would allocate four
/// times a tick, so the size difference between the variants is kept.
#[derive(Debug, Clone, Copy, PartialEq)]
#[allow(clippy::large_enum_variant)]
pub enum Actuation {
    /// The kinematic follower realises the guidance command itself.
    Kinematic(FollowerCommand),
    /// The flight controller's decision (`None` when the plant's state is not usable).
    Aircraft(Option<AircraftActuation>),
}

impl Actuation {
    /// The flight controller's decision, when there is one.
    pub fn aircraft(&self) -> Option<&AircraftActuation> {
        match self {
            Self::Aircraft(a) => a.as_ref(),
            Self::Kinematic(_) => None,
        }
    }
}

impl Follower {
    /// The follower a configuration describes and its initial state slice.
    pub fn new(config: &FollowerConfig) -> Result<(Self, Vec<f64>), AircraftSetupError> {
        let f = config.follower;
        match f.model {
            FollowerModel::Kinematic => {
                let follower = KinematicFollower {
                    attitude_lag_s: f.attitude_lag_s,
                    realises: config.command_kind,
                };
                let [phi, theta, psi] = f.initial_attitude_deg.map(f64::to_radians);
                let x = follower.initial_state(
                    &Vec3::from(f.initial_position_ft),
                    &EulerAngles::new(phi, theta, psi),
                    &Vec3::from(f.initial_velocity_fps),
                );
                Ok((Self::Kinematic(follower), x))
            }
            FollowerModel::Aircraft => {
                let (follower, x) = AircraftFollower::new(config)?;
                Ok((Self::Aircraft(Box::new(follower)), x))
            }
        }
    }

    /// R_F, NED, ft.
    pub fn position_ned_ft(&self, x: &[f64]) -> Vec3 {
        match self {
            Self::Kinematic(_) => KinematicFollower::position_ned_ft(x),
            Self::Aircraft(_) => AircraftFollower::position_ned_ft(x),
        }
    }

    /// The follower's attitude (camera = body).
    pub fn attitude(&self, x: &[f64]) -> EulerAngles {
        match self {
            Self::Kinematic(_) => KinematicFollower::attitude(x),
            Self::Aircraft(_) => AircraftFollower::attitude(x),
        }
    }

    /// Body rates [p, q, r], rad/s: from the kinematic follower's attitude rates, or the
    /// aircraft's own rate states.
    pub fn body_rates(&self, x: &[f64]) -> Vec3 {
        match self {
            Self::Kinematic(k) => k.body_rates(x),
            Self::Aircraft(_) => AircraftFollower::body_rates(x),
        }
    }

    /// V_F, NED, ft/s: what the kinematic follower realises of `command`, or the aircraft's
    /// inertial velocity.
    pub fn velocity_ned_fps(&self, x: &[f64], command: &FollowerCommand) -> Vec3 {
        match self {
            Self::Kinematic(k) => k.velocity_ned_fps(x, command),
            Self::Aircraft(_) => AircraftFollower::velocity_ned_fps(x),
        }
    }

    /// The velocity the follower's track follows, from its own navigation, NED, ft/s: the
    /// aircraft's inertial velocity, or the kinematic follower's v (the velocity its
    /// attitude turns to).
    pub fn track_ned_fps(&self, x: &[f64]) -> Vec3 {
        match self {
            Self::Kinematic(_) => KinematicFollower::heading_velocity_ned_fps(x),
            Self::Aircraft(_) => AircraftFollower::velocity_ned_fps(x),
        }
    }

    /// How the follower flies its command, from its own navigation, when it does not simply
    /// realise it (the aircraft); `None` for the kinematic follower, whose velocity is the
    /// command.
    pub fn feedback(&self, x: &[f64]) -> Option<FollowerFeedback> {
        match self {
            Self::Kinematic(_) => None,
            Self::Aircraft(a) => Some(a.feedback(x)),
        }
    }

    /// At the start: a kinematic follower that realises velocities points its attitude along
    /// the first commanded V_F; the trimmed aircraft flies as it is.
    pub fn align_with_first_command(&self, x: &mut [f64], command: &FollowerCommand) {
        if let (Self::Kinematic(k), FollowerCommand::Velocity(v)) = (self, command)
            && k.realises == CommandKind::Velocity
        {
            KinematicFollower::set_heading_velocity(x, v);
        }
    }

    /// Before each step: the aircraft's air (turbulence) for the step.
    pub fn begin_step(&mut self, x: &[f64], dt_s: f64) {
        if let Self::Aircraft(a) = self {
            a.begin_step(x, dt_s);
        }
    }

    /// What the navigation and air data read above the truth over the coming step, for the
    /// aircraft's wind estimate (the kinematic follower has none).
    pub fn hold_own_state_errors(&mut self, errors: Option<crate::navigation::OwnStateErrors>) {
        if let Self::Aircraft(a) = self {
            a.hold_own_state_errors(errors);
        }
    }

    /// Before each step, when the aircraft's S-turns alternate by geometry: the slot's line
    /// from the estimate (`None`: unknown).
    pub fn hold_slot_line(&mut self, line: Option<SlotLine>) {
        if let Self::Aircraft(a) = self {
            a.hold_slot_line(line);
        }
    }

    /// The control step: the flight controller's ẋ and decision for the guidance `command`.
    pub fn control(&self, x: &[f64], command: &FollowerCommand, dx: &mut [f64]) -> Actuation {
        match self {
            Self::Kinematic(_) => Actuation::Kinematic(*command),
            Self::Aircraft(a) => Actuation::Aircraft(a.control(x, command, dx)),
        }
    }

    /// The plant step: the equations of motion's ẋ under `actuation`.
    pub fn plant(&self, x: &[f64], actuation: &Actuation, dx: &mut [f64]) {
        match (self, actuation) {
            (Self::Kinematic(k), Actuation::Kinematic(command)) => k.derivative(x, command, dx),
            (Self::Aircraft(a), Actuation::Aircraft(decision)) => {
                a.plant(x, decision.as_ref(), dx);
            }
            // A decision of the other model is a wiring error: nothing moves.
            _ => dx.fill(0.0),
        }
    }

    /// After a step: wraps angles (kinematic), renormalises the quaternion and bounds the
    /// controller's weights (aircraft).
    pub fn normalize(&self, x: &mut [f64]) {
        match self {
            Self::Kinematic(_) => KinematicFollower::normalize(x),
            Self::Aircraft(a) => a.normalize(x),
        }
    }

    /// The 6-DOF follower, if this is one.
    pub fn aircraft(&self) -> Option<&AircraftFollower> {
        match self {
            Self::Aircraft(a) => Some(a),
            Self::Kinematic(_) => None,
        }
    }

    /// The names of the state slice's elements (for messages): the kinematic follower's
    /// position, attitude and velocity; the aircraft's plant, its controller and the V_F it
    /// integrates (acceleration law).
    pub fn state_names(&self) -> Vec<String> {
        use crate::state_block::{NED, element_names};
        match self {
            Self::Kinematic(_) => element_names(
                "follower",
                &[
                    ("position, ft", NED),
                    ("attitude, rad", &["φ", "θ", "ψ"]),
                    ("velocity, ft/s", NED),
                ],
            ),
            Self::Aircraft(_) => {
                let mut names = crate::world::aircraft::state::state_names();
                names.extend(crate::control::autopilot_state_names());
                names.extend(element_names(
                    "autopilot",
                    &[("V_F integrated from a_F, ft/s", NED)],
                ));
                names
            }
        }
    }
}
