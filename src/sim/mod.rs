//! The simulation: owns every stage and wires one tick in a fixed order (docs/design.md, One
//! tick). It is the one place that reads modes across stages: [`Simulation::new`] builds each
//! stage from its own section and makes every pairing across stages (`src/sim/build.rs`).
//!
//! Continuous state, integrated as one vector by RK4 (one slice per stage):
//! `[follower | gimbal | command frame | guidance law]`. The target advances by its own
//! model ([`TargetModel`]) before each step.
//!
//! One tick (the sensors have already acted for it, see below): (1) the aircraft's turbulence
//! advances and is held over the step; (2) RK4 advances follower, command frame and guidance
//! together, each stage evaluating, in this order, the measurement the estimator stage gives
//! the guidance, the guidance law, the flight control and the plant (timed apart); (3)
//! projection bounds, angle wrapping and quaternion norm are enforced; (4) divergence is
//! checked, the excitation records the tracking error and the aircraft's flight envelope the
//! instant, interception and the end of the run are decided; (5) the sensors act for the new
//! tick: the noisy sensor may draw its noise, the camera may take a frame and deliver one to
//! the guidance. A snapshot between ticks therefore shows what the guidance works with.

mod build;
mod evaluate;
pub mod group;
mod layout;
mod navigate;
mod record;
mod run;
mod sense;

pub use record::{GimbalReading, Snapshot, StageTimes};
pub use run::{RunEnd, RunTick};

use build::{
    capture_geometry, estimation_stage, excitation_instrument, excitation_view_bound, first_r,
    follower_of, gimbal_of, mounted_camera, target_of,
};
use evaluate::Evaluation;
use navigate::{OwnSensing, encoder_reading};

use crate::estimation::instrument::ExcitationInstrument;
use crate::estimation::{Estimator, GuidanceMeasurement, LawEstimates, TargetMotionEstimate};
use crate::follower::AircraftSetupError;
use crate::follower::{FlightEnvelope, Follower};
use crate::frames::Vec3;
use crate::guidance::command::{self, FormationCommand};
use crate::guidance::excitation::Excitation;
use crate::guidance::law::{GuidanceLaw, GuidanceSetupError};
use crate::integrate::Rk4;
use crate::render::GpuContext;
use crate::scenario::{FollowerModel, Mission, Scenario};
use crate::sensing::gimbal::{GIMBAL_STATE_NAMES, Gimbal, GimbalAngles};
use crate::sensing::losses::{LossEpisode, LossLog};
use crate::sensing::{
    CameraSensor, CaptureGeometry, NoisySensor, OtherAircraft, Sensor, SensorConfig, SensorError,
};
use crate::target_aircraft::TargetAircraftError;
use crate::world::target::{TargetModel, TargetState};
use crate::world::trajectory::TrackError;
use layout::StateLayout;
use std::cell::Cell;
use std::time::Instant;

/// Why a simulation could not start or go on.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// A state became non-finite or absurdly large.
    #[error("the run diverged at t = {t_s:.3} s: {what}")]
    Diverged {
        /// Time of detection, s.
        t_s: f64,
        /// What went wrong.
        what: String,
    },
    /// The guidance law could not be built from the scenario.
    #[error("cannot set up the simulation: {0}")]
    Guidance(#[from] GuidanceSetupError),
    /// The follower could not be built from the scenario.
    #[error("cannot set up the simulation: {0}")]
    Follower(#[from] AircraftSetupError),
    /// The target's track could not be read.
    #[error("cannot set up the simulation: target.track: {0}")]
    Track(#[from] TrackError),
    /// The target aircraft could not be built from the scenario.
    #[error("cannot set up the simulation: {0}")]
    Target(#[from] TargetAircraftError),
    /// The sensor could not be built from the scenario.
    #[error("cannot set up the simulation: {0}")]
    Sensor(#[source] Box<SensorError>),
    /// The camera failed to take or measure a frame.
    #[error("camera failure at t = {t_s:.3} s: {source}")]
    Camera {
        /// Time of the frame, s.
        t_s: f64,
        /// What failed.
        #[source]
        source: Box<SensorError>,
    },
}

impl SimError {
    /// Whether the set-up failed for want of a graphics adapter: the machine's fault, not
    /// the scenario's.
    pub fn is_missing_adapter(&self) -> bool {
        matches!(self, Self::Sensor(e) if matches!(**e, SensorError::Gpu(_)))
    }
}

/// What a step ended in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StepOutcome {
    /// Keep going.
    Running,
    /// ‖R‖ fell below the interception radius at this time.
    Intercepted {
        /// Time of interception, s.
        t_s: f64,
    },
    /// The scenario's duration is reached.
    Finished,
}

/// A running simulation.
#[derive(Debug)]
pub struct Simulation {
    scenario: Scenario,
    target: Box<dyn TargetModel>,
    follower: Follower,
    /// The 6-DOF follower's extremes and limit hits (aircraft runs).
    envelope: Option<FlightEnvelope>,
    command: FormationCommand,
    guidance: GuidanceLaw,
    excitation: Excitation,
    sensor: Sensor,
    /// What the follower's own sensors read of its state (`[navigation]`), and its camera's
    /// true and nominal mounts.
    own: OwnSensing,
    /// The camera's pan/tilt gimbal, when it rides one.
    gimbal: Option<Gimbal>,
    estimator: Estimator,
    /// With `estimator.size_from = "excitation"`, the size read from the excitation.
    instrument: Option<ExcitationInstrument>,
    /// The runs of frames that did not measure the target.
    losses: LossLog,
    /// The runs of frames whose measurement was not of the target, by the truth (false
    /// locks; camera runs).
    false_locks: LossLog,
    layout: StateLayout,
    /// What the stages' set-up had to say (estimator gain, observer-gain fallback).
    notes: Vec<String>,
    /// Wall time per stage (a `Cell`: the stages are timed inside `derivative(&self)`).
    stage_times: Cell<StageTimes>,
    rk4: Rk4,
    state: Vec<f64>,
    /// Scratch for derivative evaluations outside the integrator.
    scratch: Vec<f64>,
    tick: u64,
    total_ticks: u64,
    min_range_ft: f64,
    intercept_time_s: Option<f64>,
    /// Added to the guidance's command before the follower flies it (set from outside, e.g.
    /// by a learning agent; see [`Self::set_command_offset`]).
    command_offset: Option<Vec3>,
}

impl Simulation {
    /// Builds every stage from a validated scenario, deciding here, once, every mode that
    /// spans stages: which command the follower is given (the law's), whether the laws
    /// compensate for a follower that does not realise it (the 6-DOF aircraft), and where
    /// the guidance's measurement comes from (a continuous sensor or held camera frames).
    /// The sensors act for tick 0 before it returns.
    pub fn new(scenario: &Scenario) -> Result<Self, SimError> {
        Self::on_gpu(scenario, None)
    }

    /// [`Self::new`], with a camera rendering on `gpu` when given (a device shared by the
    /// runs of a sweep) and on a device of its own otherwise.
    pub fn on_gpu(scenario: &Scenario, gpu: Option<&GpuContext>) -> Result<Self, SimError> {
        let mut sim = Self::with_target_unsensed(scenario, gpu, target_of(scenario)?)?;
        sim.sense_first()?;
        Ok(sim)
    }

    /// [`Self::on_gpu`] with the target `target` instead of the one `[target]` describes
    /// (a group's relayed aircraft, `sim::group`), before its sensors act at t = 0: the group
    /// first places every other aircraft in its camera ([`Self::set_other_aircraft`]), then
    /// calls [`Self::sense_first`].
    pub(crate) fn with_target_unsensed(
        scenario: &Scenario,
        gpu: Option<&GpuContext>,
        target: Box<dyn TargetModel>,
    ) -> Result<Self, SimError> {
        let g = &scenario.guidance;
        let (follower, follower_x) = follower_of(scenario)?;
        let compensate = scenario.follower.model == FollowerModel::Aircraft;
        let mut sensor = Sensor::new(&SensorConfig::of(scenario, g.command_length_ft()), gpu)
            .map_err(|e| SimError::Sensor(Box::new(e)))?;
        let (estimator, guidance, notes) =
            estimation_stage(scenario, compensate, sensor.is_continuous())?;
        let gimbal = gimbal_of(scenario, target.as_ref());
        let body_from_ned = follower.attitude(&follower_x).body_from_ned();
        let gimbal_x = gimbal
            .as_ref()
            .map_or(vec![], |g| g.initial_state(&body_from_ned).to_vec());
        let own = OwnSensing::new(scenario, &follower.attitude(&follower_x));
        let camera_from_body = mounted_camera(&own.mount, gimbal.as_ref(), &gimbal_x);
        let truth = capture_geometry(
            target.as_ref(),
            &follower,
            &follower_x,
            0.0,
            &camera_from_body,
        );
        let geometry = own.navigated(truth, gimbal.as_ref(), &gimbal_x);
        sensor.draw_initial_noise(&geometry);
        let command = FormationCommand::new(g);
        let body_rates_rps = follower.body_rates(&follower_x);
        let r_first = first_r(&sensor, &geometry, &command, body_rates_rps, g.b0_ft);
        let layout = StateLayout::new(
            follower_x.len(),
            gimbal_x.len(),
            command::STATE_LEN,
            guidance.state_len(),
        );
        let mut state = follower_x;
        state.extend(gimbal_x);
        state.extend(FormationCommand::initial_state(&geometry.follower.attitude));
        state.extend(guidance.initial_state(&r_first));
        let mut sim = Self {
            rk4: Rk4::new(state.len()),
            scratch: vec![0.0; state.len()],
            scenario: scenario.clone(),
            target,
            envelope: follower.aircraft().map(|_| FlightEnvelope::default()),
            follower,
            command,
            guidance,
            excitation: Excitation::new(
                &scenario.excitation,
                scenario.run.dt_s,
                excitation_view_bound(scenario),
                scenario.guidance.b0_ft,
            ),
            sensor,
            own,
            gimbal,
            estimator,
            instrument: excitation_instrument(scenario),
            losses: LossLog::default(),
            false_locks: LossLog::default(),
            layout,
            notes,
            stage_times: Cell::new(StageTimes::default()),
            state,
            tick: 0,
            total_ticks: scenario.run.total_ticks(),
            min_range_ft: geometry.relative_ned_ft.norm(),
            intercept_time_s: None,
            command_offset: None,
        };
        sim.follower
            .hold_own_state_errors(sim.own.sensors.own_state_errors());
        let first = sim.evaluate().guidance.command;
        let follower_x = sim.layout.split_mut(&mut sim.state).follower;
        sim.follower.align_with_first_command(follower_x, &first);
        Ok(sim)
    }

    /// The sensors act at t = 0 (the first frame): the last step of setting up a simulation
    /// made by [`Self::with_target_unsensed`].
    pub(crate) fn sense_first(&mut self) -> Result<(), SimError> {
        self.sense()
    }

    /// Adds `offset` to the guidance's command from the next tick on, until it is changed
    /// (`None`: the guidance's command alone, as the scenario flies): a velocity offset, NED,
    /// ft/s, for the velocity law; an acceleration offset, NED, ft/s², for the acceleration
    /// law. The follower flies the sum (the 6-DOF follower through its flight controller);
    /// snapshots show it as the command.
    pub fn set_command_offset(&mut self, offset: Option<Vec3>) {
        self.command_offset = offset;
    }

    /// The offset added to the guidance's command (see [`Self::set_command_offset`]).
    pub fn command_offset(&self) -> Option<Vec3> {
        self.command_offset
    }

    /// The scenario this simulation runs.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// Current time, s.
    pub fn time_s(&self) -> f64 {
        self.tick as f64 * self.scenario.run.dt_s
    }

    /// Ticks taken so far.
    pub fn tick(&self) -> u64 {
        self.tick
    }

    /// Smallest ‖R‖ seen at any tick so far, ft.
    pub fn min_range_ft(&self) -> f64 {
        self.min_range_ft
    }

    /// When ‖R‖ first fell below the interception radius (interception missions), s.
    pub fn intercept_time_s(&self) -> Option<f64> {
        self.intercept_time_s
    }

    /// Ticks of the whole run.
    pub fn total_ticks(&self) -> u64 {
        self.total_ticks
    }

    /// The camera, in camera runs.
    pub fn camera(&self) -> Option<&CameraSensor> {
        self.sensor.camera()
    }

    /// The estimator stage.
    pub fn estimator(&self) -> &Estimator {
        &self.estimator
    }

    /// The runs of delivered frames that did not measure the target, in order.
    pub fn loss_episodes(&self) -> Vec<LossEpisode> {
        self.losses.episodes()
    }

    /// When the loss of the target going on now began (the time of its first unmeasured
    /// frame), s; None while the last frame measured it.
    pub fn unmeasured_since_s(&self) -> Option<f64> {
        self.losses.open_since_s()
    }

    /// The runs of delivered frames whose measurement was not of the target (false locks),
    /// in order.
    pub fn false_lock_episodes(&self) -> Vec<LossEpisode> {
        self.false_locks.episodes()
    }

    /// When the false lock going on now began (its first frame that measured something other
    /// than the target), s; None while the last measurement was of the target.
    pub fn off_target_since_s(&self) -> Option<f64> {
        self.false_locks.open_since_s()
    }

    /// Draws `others` with the target in the camera's frames from the next one on (camera
    /// runs; nothing otherwise).
    pub fn set_other_aircraft(&mut self, others: &[OtherAircraft]) {
        if let Some(camera) = self.sensor.camera_mut() {
            camera.set_other_aircraft(others);
        }
    }

    /// The follower's true state now, as another aircraft would track it (its acceleration
    /// left zero: the caller differences velocities).
    pub fn own_state(&self) -> TargetState {
        let x = self.layout.split(&self.state).follower;
        TargetState {
            position_ned_ft: self.follower.position_ned_ft(x),
            velocity_ned_fps: self.follower.track_ned_fps(x),
            accel_ned_fps2: Vec3::zeros(),
            attitude: self.follower.attitude(x),
        }
    }

    /// The noisy sensor, in noisy runs.
    pub fn noisy_sensor(&self) -> Option<&NoisySensor> {
        self.sensor.noisy()
    }

    /// Wall time spent per stage of the continuous loop so far.
    pub fn stage_times(&self) -> StageTimes {
        self.stage_times.get()
    }

    /// The 6-DOF follower's flight envelope so far (aircraft runs).
    pub fn flight_envelope(&self) -> Option<&FlightEnvelope> {
        self.envelope.as_ref()
    }

    /// The follower stage.
    pub fn follower(&self) -> &Follower {
        &self.follower
    }

    /// What the stages' set-up had to say, for the run's log (e.g. a Riccati observer gain
    /// that fell back to the fixed gain).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// Where follower and target are now, as a camera frame would see them.
    pub fn capture_geometry(&self) -> CaptureGeometry {
        self.geometry_at(self.time_s(), &self.state)
    }

    /// The gimbal's angles and command now (gimballed cameras).
    pub fn gimbal_reading(&self) -> Option<GimbalReading> {
        let gimbal = self.gimbal.as_ref()?;
        Some(GimbalReading {
            angles: GimbalAngles::of(&encoder_reading(
                &self.own.sensors,
                self.layout.split(&self.state).gimbal,
            )),
            command: self.gimbal_command(gimbal, self.time_s(), &self.state),
            roll_axis: gimbal.has_roll_axis(),
        })
    }

    /// The state of every stage now.
    pub fn snapshot(&self) -> Snapshot {
        let t_s = self.time_s();
        let mut dx = vec![0.0; self.state.len()];
        let Evaluation {
            guidance: out,
            actuation,
        } = self.derivative(t_s, &self.state, &mut dx);
        let slices = self.layout.split(&self.state);
        let (follower_x, command_x) = (slices.follower, slices.command);
        let follower = self.follower.position_ned_ft(follower_x);
        let target = self.target.state(t_s);
        let measurement = self.guidance_measurement(t_s, &self.state);
        let command_input = self.command_input(&self.state, &measurement);
        let (command, _) = self.command.command(command_x, &command_input);
        let g = &self.scenario.guidance;
        let estimates = self
            .estimates(&self.state, &measurement)
            .unwrap_or(LawEstimates {
                b_hat_ft: g.b0_ft,
                target_motion: TargetMotionEstimate::ScaledVelocity(Vec3::from(g.d0_per_s)),
            });
        let excitation = self.excitation_offset(t_s, command_x, &command_input);
        Snapshot {
            t_s,
            target,
            target_flight: self.target.flight(t_s),
            follower_position_ned_ft: follower,
            follower_velocity_ned_fps: self.follower.velocity_ned_fps(follower_x, &out.command),
            follower_attitude: self.follower.attitude(follower_x),
            relative_ned_ft: target.position_ned_ft - follower,
            command_ned_ft: command,
            excited_command_ned_ft: command + excitation.in_ft(estimates.b_hat_ft),
            excitation_amplitude: self.excitation.amplitude_at(t_s),
            r_measured: match measurement {
                GuidanceMeasurement::Now { r, .. } => r,
                GuidanceMeasurement::NotYet => None,
            },
            b_hat_ft: estimates.b_hat_ft,
            target_motion: estimates.target_motion,
            filter: self
                .estimator
                .filter_reading(t_s, &self.navigated_position_ned_ft(follower_x)),
            filter_nis: (self.estimator.filter()).and_then(|f| f.last_normalised_innovation()),
            navigation: self.navigation_reading(),
            guidance: out,
            frame: self.camera().and_then(CameraSensor::held_record),
            frame_trusted: self.camera().and_then(CameraSensor::held_trusted),
            gimbal: self.gimbal_reading(),
            aircraft: actuation.aircraft().copied(),
        }
    }

    /// Advances one tick.
    pub fn step(&mut self) -> Result<StepOutcome, SimError> {
        if self.tick >= self.total_ticks {
            return Ok(StepOutcome::Finished);
        }
        let integrate_started = Instant::now();
        let t_s = self.time_s();
        let dt_s = self.scenario.run.dt_s;
        if self.follower.aircraft().is_some_and(|a| a.weaves()) {
            let line = self.slot_line(t_s, &self.state);
            self.follower.hold_slot_line(line);
        }
        let follower_x = self.layout.split(&self.state).follower;
        self.follower.begin_step(follower_x, dt_s);
        self.advance_own_sensors(dt_s);
        self.target
            .advance(t_s, dt_s)
            .map_err(|diverged| SimError::Diverged {
                t_s: t_s + dt_s,
                what: diverged.what,
            })?;
        let mut state = std::mem::take(&mut self.state);
        let mut rk4 = std::mem::replace(&mut self.rk4, Rk4::new(0));
        rk4.step(t_s, dt_s, &mut state, |t, x, dx| {
            self.derivative(t, x, dx);
        });
        self.rk4 = rk4;
        let slices = self.layout.split_mut(&mut state);
        self.follower.normalize(slices.follower);
        if let Some(gimbal) = &self.gimbal {
            gimbal.normalize(slices.gimbal);
        }
        FormationCommand::normalize(slices.command);
        self.guidance.enforce_bounds(slices.guidance);
        self.state = state;
        self.tick += 1;
        let outcome = self.after_step();
        let mut times = self.stage_times.get();
        times.integration += integrate_started.elapsed();
        self.stage_times.set(times);
        if let Ok(StepOutcome::Running) = outcome {
            self.sense()?;
        }
        outcome
    }

    /// Checks, records and decides after a step: divergence, range, the excitation's error
    /// energy, the flight envelope, interception and the end of the run.
    fn after_step(&mut self) -> Result<StepOutcome, SimError> {
        let t_end_s = self.time_s();
        if let Some(i) = self.state.iter().position(|v| !v.is_finite()) {
            return Err(SimError::Diverged {
                t_s: t_end_s,
                what: format!("{} is {}", self.state_name(i), self.state[i]),
            });
        }
        let follower_x = self.layout.split(&self.state).follower;
        let range_ft = (self.target.position_ned_ft(t_end_s)
            - self.follower.position_ned_ft(follower_x))
        .norm();
        self.min_range_ft = self.min_range_ft.min(range_ft);
        if range_ft > 1e6 {
            return Err(SimError::Diverged {
                t_s: t_end_s,
                what: format!("range {range_ft:.3e} ft exceeds 1e6 ft"),
            });
        }
        let Evaluation {
            guidance: out,
            actuation,
        } = self.evaluate();
        if let (Some(envelope), Some(aircraft)) = (self.envelope.as_mut(), actuation.aircraft()) {
            envelope.record(t_end_s, aircraft);
        }
        let size_ft = self.size_uncertainty_ft();
        self.excitation
            .record_errors(t_end_s, &out.excitation_errors, size_ft);
        let g = &self.scenario.guidance;
        if g.mission == Mission::Intercept && range_ft < g.intercept_radius_ft {
            self.intercept_time_s = Some(t_end_s);
            return Ok(StepOutcome::Intercepted { t_s: t_end_s });
        }
        Ok(if self.tick >= self.total_ticks {
            StepOutcome::Finished
        } else {
            StepOutcome::Running
        })
    }
}

impl Simulation {
    /// The filter's (b̂, σ_b), ft, that the excitation follows: with the instrument, σ_b is no
    /// smaller than the instrument's (b̂ itself before it reads one), so the follower swings
    /// until the reading that does not take the leader's motion as independent of its own is
    /// sure of the size.
    fn size_uncertainty_ft(&self) -> Option<(f64, f64)> {
        let estimate = self.estimator.filter()?.posterior()?;
        let (size_ft, sigma_ft) = (estimate.b_hat_ft, estimate.b_sigma_reducible_ft);
        let instrument_sigma_ft = self
            .instrument
            .as_ref()
            .map(|i| i.estimate().map_or(size_ft, |reading| reading.sigma_ft));
        Some((
            size_ft,
            instrument_sigma_ft.map_or(sigma_ft, |s| s.max(sigma_ft)),
        ))
    }

    /// What element `i` of the state vector is, named by its stage ("autopilot: RBF weight
    /// 3 of the pitch channel").
    fn state_name(&self, i: usize) -> String {
        let names = layout::Slices {
            follower: self.follower.state_names(),
            gimbal: self
                .gimbal
                .as_ref()
                .map_or(vec![], |_| GIMBAL_STATE_NAMES.map(String::from).to_vec()),
            command: command::STATE_NAMES.map(String::from).to_vec(),
            guidance: self.guidance.state_names(),
        };
        self.layout.describe(i, &names)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A state that turns NaN is named by its stage and quantity, not by its index.
    #[test]
    fn divergence_names_the_stage_and_quantity() {
        let text = "[follower]\nmodel = \"aircraft\"\n[run]\ndt_s = 0.002\n";
        let scenario = Scenario::from_toml_str(text, std::path::Path::new("s.toml"), &[])
            .expect("valid scenario");
        let mut sim = Simulation::new(&scenario).expect("set-up");
        let name = "autopilot: RBF weight 3 of the pitch channel";
        let i = sim
            .follower
            .state_names()
            .iter()
            .position(|n| n == name)
            .expect("the weight is named");
        sim.state[i] = f64::NAN;
        let message = sim.after_step().expect_err("diverged").to_string();
        assert!(message.contains(&format!("{name} is NaN")), "{message}");
        let i = sim.layout.split(&sim.state).follower.len() + command::STATE_LEN;
        sim.state.fill(0.0);
        sim.state[i] = f64::INFINITY;
        let message = sim.after_step().expect_err("diverged").to_string();
        assert!(
            message.contains("guidance: b̂ (target size estimate), ft is inf"),
            "{message}"
        );
    }

    /// The instrument reads along E, or across the slot's line of sight with
    /// `estimator.instrument_axis = "across_slot"`: E less its part along R_c.
    #[test]
    fn the_instrument_reads_across_the_slot_when_asked() {
        let direction_for = |axis: &str| {
            let text = format!(
                "[estimator]\nkind = \"kalman\"\n\
                 instrument_axis = \"{axis}\"\n[guidance]\ncommand_frame = \"target\"\n\
                 command_ft = [32.0, 8.0, -8.0]\n\
                 [excitation]\nframe = \"target\"\ndirection = [0.0, 1.0, 0.0]\n"
            );
            let scenario = Scenario::from_toml_str(&text, std::path::Path::new("s.toml"), &[])
                .expect("valid scenario");
            let sim = Simulation::new(&scenario).expect("set-up");
            (
                sim.instrument_direction_ned(),
                sim.excitation_direction_ned(),
                sim.snapshot().command_ned_ft,
            )
        };
        let (along, e, _) = direction_for("excitation");
        assert!((along - e).norm() < 1e-12, "{along} against E {e}");
        let (across, e, slot) = direction_for("across_slot");
        let sight = slot.normalize();
        assert!(
            across.dot(&sight).abs() < 1e-12,
            "{across} against R_c {slot}"
        );
        assert!(
            (across + sight * e.dot(&sight) - e).norm() < 1e-12,
            "{across}"
        );
        assert!((across.norm() - 0.972).abs() < 1e-3, "{across}");
    }
}
