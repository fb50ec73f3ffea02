//! The 6-DOF follower (seed Chapter 7): the plant of [`crate::world::aircraft`] flown by the
//! flight controller of [`crate::control`] in the air of [`crate::world::atmosphere`].
//!
//! State slice: `[plant (STATE_LEN) | autopilot (AUTOPILOT_STATE_LEN) | V_F (3, acceleration
//! law only)]`. The velocity law commands V_F itself (4.3); for the acceleration law the slice
//! integrates V_F = V_F(0) + ∫ a_F, V_F(0) the trimmed aircraft's inertial velocity.
//! In both cases the autopilot flies V_F (7.1)-(7.33).
//!
//! The aircraft starts trimmed in straight and level flight (`trim_level_flight`) at the
//! airspeed ‖`follower.initial_velocity_fps`‖ on its course, trimmed in the steady air without
//! the Δ perturbations (the controller's nominal model does not know them); the controller's
//! filters start at rest on that flight condition. Once per tick [`AircraftFollower::begin_step`]
//! advances the Dryden turbulence and holds the air sample over the RK4 step; Δ perturbations
//! act on the plant only.

use super::FollowerConfig;
use crate::control::{
    AUTOPILOT_STATE_LEN, Autopilot, AutopilotInput, AutopilotOutput, SlotAxis, WeaveGeometry,
    slot_weave_side, weave_side,
};
use crate::frames::{EulerAngles, Vec3};
use crate::guidance::signals::{CommandKind, FollowerCommand, FollowerFeedback};
use crate::navigation::OwnStateErrors;
use crate::scenario::check::InvalidValue;
use crate::world::aircraft::{
    AirData, Aircraft, AircraftFileError, AircraftParams, AircraftState, Controls, STATE_LEN,
    TrimError, TrimRequest, trim_level_flight,
};
use crate::world::atmosphere::{Atmosphere, AtmosphereSample};

/// Offset of the autopilot's state in the follower's slice.
const AUTOPILOT: usize = STATE_LEN;
/// Offset of the integrated V_F (acceleration law) in the follower's slice.
const VELOCITY_CMD: usize = AUTOPILOT + AUTOPILOT_STATE_LEN;
/// Offset of the body rates p, q, r in the plant's state.
const BODY_RATES: usize = crate::world::aircraft::state::BODY_RATES_RPS;

/// Mixed into `[run] seed` for the Dryden turbulence's own random stream, so that it is not
/// the noisy sensor's or the camera noise's stream ("dryden" in ASCII).
pub const DRYDEN_SEED_SALT: u64 = 0x0000_6472_7964_656e;

/// Why the 6-DOF follower could not be set up.
#[derive(Debug, thiserror::Error)]
pub enum AircraftSetupError {
    /// The aircraft data file is unreadable or invalid.
    #[error("{0}")]
    AircraftData(#[from] AircraftFileError),
    /// A value the plant, the controller or the atmosphere rejected.
    #[error("{0}")]
    Invalid(InvalidValue),
    /// No straight and level trim at the scenario's speed.
    #[error("follower.initial_velocity_fps: {0}")]
    Trim(TrimError),
    /// The trimmed state has no air data (cannot happen with a valid trim).
    #[error("the trimmed state has no valid attitude")]
    TrimState,
}

impl From<InvalidValue> for AircraftSetupError {
    fn from(e: InvalidValue) -> Self {
        Self::Invalid(e)
    }
}

/// The slot's line as the follower's estimate places it: through the slot along the
/// target's estimated horizontal velocity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlotLine {
    /// Its course, rad.
    pub track_rad: f64,
    /// The follower's offset to its right, ft.
    pub cross_track_ft: f64,
    /// How far the target is ahead of the slot along its track, ft.
    pub slot_lead_ft: f64,
    /// How far the target is to the right of the slot across its track, ft.
    pub slot_offset_ft: f64,
    /// How far the follower is ahead of its slot along the track, (R_c - R̂)·u, ft.
    pub ahead_of_slot_ft: f64,
    /// The target's estimated turn rate, rad/s, positive to the right.
    pub turn_rate_rps: f64,
}

impl SlotLine {
    /// Whether the slot lies behind the target (at least as far behind as beside it), where
    /// a follower that overtakes runs onto the target's track and S-turns are flown; a
    /// follower beside its target moves ahead of its slot instead, where a leg across the
    /// slot's line would carry it under or into the target.
    pub fn behind_the_target(&self) -> bool {
        self.slot_lead_ft >= self.slot_offset_ft.abs()
    }
}

/// What the flight controller decided at one instant, with what it saw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftActuation {
    /// V_F the autopilot flies, NED, ft/s.
    pub velocity_cmd_ned_fps: Vec3,
    /// Air data of the plant (true values, turbulence included).
    pub air_data: AirData,
    /// Actuator positions.
    pub actuators: Controls,
    /// Turbulent gust velocity held over the step, body axes, ft/s.
    pub gust_body_fps: Vec3,
    /// The controller's commands and signals.
    pub autopilot: AutopilotOutput,
}

/// The 6-DOF aircraft and its flight controller.
#[derive(Debug, Clone)]
pub struct AircraftFollower {
    aircraft: Aircraft,
    autopilot: Autopilot,
    atmosphere: Atmosphere,
    /// The air held over the current step.
    air: AtmosphereSample,
    /// V_F is integrated from a_F (acceleration law).
    integrates_acceleration: bool,
    /// Time flown, s (the S-turns' clock).
    flown_s: f64,
    /// S-turn period, s (0: none).
    weave_period_s: f64,
    /// The S-turns by geometry (half width 0: none; then the clock's).
    weave_geometry: WeaveGeometry,
    /// The side of the S-turn by geometry, +1 right or -1 left ([`slot_weave_side`]).
    slot_weave_side: f64,
    /// The slot's line held for the step (`None`: unknown).
    slot_line: Option<SlotLine>,
    /// What the navigation and air data read above the truth over the current step (`None`:
    /// perfect), for the wind estimate.
    own_state_errors: Option<OwnStateErrors>,
}

impl AircraftFollower {
    /// The follower of a configuration and its initial state (trimmed, controller at rest).
    pub fn new(config: &FollowerConfig) -> Result<(Self, Vec<f64>), AircraftSetupError> {
        let params = AircraftParams::from_scenario_path(&config.follower.aircraft)?
            .with_speed_brake(config.follower.speed_brake_c_drag);
        let aircraft = Aircraft::new(params.clone())?;
        let autopilot = Autopilot::new(&params, config.autopilot)?;
        let atmosphere = Atmosphere::new(config.atmosphere, config.turbulence_seed)?;
        let start = Vec3::from(config.follower.initial_position_ft);
        let [north, east, _] = config.follower.initial_velocity_fps;
        let steady = atmosphere.steady_sample(&start);
        let trim = trim_level_flight(
            &aircraft,
            &TrimRequest {
                airspeed_fps: north.hypot(east),
                position_ned_ft: start,
                heading_rad: east.atan2(north),
                air: AtmosphereSample {
                    drag_factor: 1.0,
                    moment_bias_body_lbf_ft: Vec3::zeros(),
                    ..steady
                },
            },
        )
        .map_err(AircraftSetupError::Trim)?;
        let mut x = trim.state.pack().to_vec();
        let data = aircraft
            .air_data(&x, &steady)
            .ok_or(AircraftSetupError::TrimState)?;
        x.extend(autopilot.initial_state(&data));
        let integrates_acceleration = config.command_kind == CommandKind::Acceleration;
        if integrates_acceleration {
            x.extend(data.velocity_ned_fps.iter());
        }
        Ok((
            Self {
                aircraft,
                autopilot,
                atmosphere,
                air: steady,
                integrates_acceleration,
                flown_s: 0.0,
                weave_period_s: config.autopilot.weave_period_s,
                weave_geometry: WeaveGeometry {
                    half_width_ft: config.autopilot.weave_half_width_ft,
                    outside_turn_rps: config.autopilot.weave_outside_turn_dps.to_radians(),
                },
                slot_weave_side: 1.0,
                slot_line: None,
                own_state_errors: None,
            },
            x,
        ))
    }

    /// R_F of a follower slice, NED, ft.
    pub fn position_ned_ft(x: &[f64]) -> Vec3 {
        Vec3::new(x[0], x[1], x[2])
    }

    /// The aircraft's attitude (level when the quaternion is not usable: the simulation's
    /// divergence check reports that state).
    pub fn attitude(x: &[f64]) -> EulerAngles {
        AircraftState::unpack(x).map_or_else(EulerAngles::default, |s| s.euler())
    }

    /// Body rates p, q, r, rad/s.
    pub fn body_rates(x: &[f64]) -> Vec3 {
        Vec3::new(x[BODY_RATES], x[BODY_RATES + 1], x[BODY_RATES + 2])
    }

    /// The aircraft's inertial velocity, NED, ft/s.
    pub fn velocity_ned_fps(x: &[f64]) -> Vec3 {
        AircraftState::unpack(x).map_or_else(Vec3::zeros, |s| s.velocity_ned_fps())
    }

    /// The aircraft's velocity V_a and, when V_F is integrated here (acceleration law), the
    /// shortfall V_F - V_a (zero otherwise), NED, ft/s.
    pub fn feedback(&self, x: &[f64]) -> FollowerFeedback {
        let realised = Self::velocity_ned_fps(x);
        FollowerFeedback {
            realised_velocity_ned_fps: realised,
            velocity_shortfall_ned_fps: if self.integrates_acceleration {
                Vec3::new(x[VELOCITY_CMD], x[VELOCITY_CMD + 1], x[VELOCITY_CMD + 2]) - realised
            } else {
                Vec3::zeros()
            },
        }
    }

    /// Advances the turbulence by one tick at the aircraft's position and airspeed and holds
    /// the air sample over the coming step.
    pub fn begin_step(&mut self, x: &[f64], dt_s: f64) {
        let position = Self::position_ned_ft(x);
        let airspeed_fps = self
            .aircraft
            .air_data(x, &self.atmosphere.steady_sample(&position))
            .map_or(0.0, |d| d.airspeed_fps);
        self.air = self.atmosphere.sample(dt_s, &position, airspeed_fps);
        self.flown_s += dt_s;
    }

    /// Whether the S-turns alternate by geometry (`weave_half_width_ft` > 0).
    pub fn weaves_by_geometry(&self) -> bool {
        self.weave_geometry.half_width_ft > 0.0
    }

    /// Whether the follower flies S-turns (by the clock or by geometry): the simulation then
    /// hands in the slot's line each tick.
    pub fn weaves(&self) -> bool {
        self.weaves_by_geometry() || self.weave_period_s > 0.0
    }

    /// Before a step: the slot's line (`None` without an estimate: the side holds and the
    /// legs are placed about the command's course); the follower's offset from it reverses
    /// the S-turn by geometry beyond its half width, the target's turn keeps it to the
    /// outside ([`slot_weave_side`]), and a slot beside the target
    /// ([`SlotLine::behind_the_target`]) stops the S-turns.
    pub fn hold_slot_line(&mut self, line: Option<SlotLine>) {
        if let Some(l) = line.filter(|_| self.weaves_by_geometry()) {
            self.slot_weave_side = slot_weave_side(
                self.slot_weave_side,
                l.cross_track_ft,
                l.turn_rate_rps,
                &self.weave_geometry,
            );
        }
        self.slot_line = line;
    }

    /// Holds what the follower's navigation and air data read above the truth over the
    /// coming step (`None`: perfect).
    pub fn hold_own_state_errors(&mut self, errors: Option<OwnStateErrors>) {
        self.own_state_errors = errors;
    }

    /// The flight controller at (x, command): writes the autopilot's (and the V_F
    /// integrator's) ẋ and returns its decision; `None` (and zero rates) when the plant's
    /// state is not usable.
    pub fn control(
        &self,
        x: &[f64],
        command: &FollowerCommand,
        dx: &mut [f64],
    ) -> Option<AircraftActuation> {
        let plant = &x[..STATE_LEN];
        let (Some(state), Some(air_data)) = (
            AircraftState::unpack(plant),
            self.aircraft.air_data(plant, &self.air),
        ) else {
            dx[AUTOPILOT..].fill(0.0);
            return None;
        };
        let velocity_cmd_ned_fps = match command {
            FollowerCommand::Velocity(v) => *v,
            FollowerCommand::Acceleration(a) if self.integrates_acceleration => {
                dx[VELOCITY_CMD..VELOCITY_CMD + 3].copy_from_slice(a.as_slice());
                Vec3::new(x[VELOCITY_CMD], x[VELOCITY_CMD + 1], x[VELOCITY_CMD + 2])
            }
            // A law that commands accelerations without the integrator is a wiring error:
            // keep flying the present velocity.
            FollowerCommand::Acceleration(_) => air_data.velocity_ned_fps,
        };
        let input = AutopilotInput {
            velocity_cmd_ned_fps,
            sensed_air_data: self
                .own_state_errors
                .map_or(air_data, |e| e.sensed_air_data(&air_data)),
            air_data,
            actuators: state.actuators,
            weave_side: if self.slot_line.is_some_and(|l| !l.behind_the_target()) {
                0.0
            } else if self.weaves_by_geometry() {
                self.slot_weave_side
            } else {
                weave_side(self.flown_s, self.weave_period_s)
            },
            slot_line: self.slot_line.map(|l| SlotAxis {
                track_rad: l.track_rad,
                ahead_of_slot_ft: l.ahead_of_slot_ft,
            }),
        };
        let autopilot = self.autopilot.derivative(
            &x[AUTOPILOT..VELOCITY_CMD],
            &input,
            &mut dx[AUTOPILOT..VELOCITY_CMD],
        );
        Some(AircraftActuation {
            velocity_cmd_ned_fps,
            air_data,
            actuators: state.actuators,
            gust_body_fps: self.air.gust_body_fps,
            autopilot,
        })
    }

    /// The plant's ẋ under the controller's commands (zero without a decision).
    pub fn plant(&self, x: &[f64], actuation: Option<&AircraftActuation>, dx: &mut [f64]) {
        match actuation {
            Some(a) => self.aircraft.derivative(
                &x[..STATE_LEN],
                &a.autopilot.controls,
                &self.air,
                &mut dx[..STATE_LEN],
            ),
            None => dx[..STATE_LEN].fill(0.0),
        }
    }

    /// After a step: renormalises the quaternion, clamps the actuators and pulls the RBF
    /// weights back into their projection bounds.
    pub fn normalize(&self, x: &mut [f64]) {
        self.aircraft.normalize(&mut x[..STATE_LEN]);
        self.autopilot
            .enforce_bounds(&mut x[AUTOPILOT..VELOCITY_CMD]);
    }

    /// The aircraft's data (actuator limits for the summary).
    pub fn params(&self) -> &AircraftParams {
        self.aircraft.params()
    }
}

#[cfg(test)]
mod tests {
    use super::SlotLine;

    fn slot(lead_ft: f64, offset_ft: f64) -> SlotLine {
        SlotLine {
            track_rad: 0.0,
            cross_track_ft: 0.0,
            slot_lead_ft: lead_ft,
            slot_offset_ft: offset_ft,
            ahead_of_slot_ft: 0.0,
            turn_rate_rps: 0.0,
        }
    }

    #[test]
    fn s_turns_are_flown_behind_the_target_not_beside_it() {
        assert!(slot(32.0, 8.0).behind_the_target());
        assert!(slot(32.0, -8.0).behind_the_target());
        assert!(slot(30.0, 0.0).behind_the_target());
        assert!(!slot(0.0, 30.0).behind_the_target());
        assert!(!slot(0.0, -30.0).behind_the_target());
        assert!(!slot(-20.0, 0.0).behind_the_target());
    }
}
