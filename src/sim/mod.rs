//! The simulation: owns every stage and wires one tick in a fixed order (DESIGN §1). It is the
//! one place that reads modes across stages: [`Simulation::new`] decides them and hands each
//! stage its own configuration.
//!
//! Continuous state, integrated as one vector by RK4 (one slice per stage):
//! `[follower | command frame | guidance law]`. The target's motion is closed-form.
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

mod layout;

use crate::estimation::{
    Estimator, FilterReading, GuidanceMeasurement, KalmanTracker, LawEstimates, MeasurementHold,
    TargetEstimate, TargetMotionEstimate, TargetTracker,
};
use crate::follower::AircraftSetupError;
use crate::follower::aircraft::DRYDEN_SEED_SALT;
use crate::follower::{Actuation, AircraftActuation, FlightEnvelope, Follower, FollowerConfig};
use crate::frames::{EulerAngles, Mat3, Vec3};
use crate::guidance::command::{self, CommandInput, FormationCommand};
use crate::guidance::excitation::Excitation;
use crate::guidance::law::{GuidanceLaw, GuidanceSetupError};
use crate::guidance::signals::{CommandKind, FollowerCommand, GuidanceInput, GuidanceOutput};
use crate::integrate::Rk4;
use crate::render::GpuContext;
use crate::scenario::{
    EstimatorKind, ExcitationUnits, FollowerModel, GimbalKind, GuidanceLawKind, Mission, Scenario,
    SensorMode, TargetMotion,
};
use crate::sensing::gimbal::{GIMBAL_STATE_NAMES, Gimbal, GimbalAngles};
use crate::sensing::losses::{LossEpisode, LossLog};
use crate::sensing::{
    CameraSensor, CaptureGeometry, FollowerPose, FrameRecord, NoisySensor, Sensor, SensorConfig,
    SensorError,
};
use crate::world::target::{TargetModel, TargetMotionModel, TargetState};
use layout::StateLayout;
use std::cell::Cell;
use std::time::{Duration, Instant};

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

/// Everything about one instant, for telemetry and statistics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Snapshot {
    /// Time, s.
    pub t_s: f64,
    /// Target state.
    pub target: TargetState,
    /// R_F, NED, ft.
    pub follower_position_ned_ft: Vec3,
    /// V_F, NED, ft/s.
    pub follower_velocity_ned_fps: Vec3,
    /// Follower attitude.
    pub follower_attitude: EulerAngles,
    /// R = R_T - R_F, NED, ft.
    pub relative_ned_ft: Vec3,
    /// The user's command R_c without excitation, NED, ft.
    pub command_ned_ft: Vec3,
    /// The command with excitation R*_c, NED, ft (scaled excitation times b̂).
    pub excited_command_ned_ft: Vec3,
    /// Excitation amplitude a(t), in the excitation's units.
    pub excitation_amplitude: f64,
    /// The r the guidance was given (None while it has nothing).
    pub r_measured: Option<Vec3>,
    /// b̂, ft.
    pub b_hat_ft: f64,
    /// d̂, in the law's own terms.
    pub target_motion: TargetMotionEstimate,
    /// The filter's estimate now, when the run has a filter (flying on it or beside the
    /// adaptive law).
    pub filter: FilterReading,
    /// Guidance output.
    pub guidance: GuidanceOutput,
    /// The last camera frame's measurement and truth (camera runs).
    pub frame: Option<FrameRecord>,
    /// The gimbal's angles and command now (gimballed cameras).
    pub gimbal: Option<GimbalReading>,
    /// The 6-DOF follower's air data, actuators and flight controller (aircraft runs).
    pub aircraft: Option<AircraftActuation>,
}

impl Snapshot {
    /// The commanded (and, kinematic follower, realised) acceleration a_F, NED, ft/s²: only
    /// the acceleration law commands one.
    pub fn follower_accel_ned_fps2(&self) -> Option<Vec3> {
        match self.guidance.command {
            FollowerCommand::Acceleration(a) => Some(a),
            FollowerCommand::Velocity(_) => None,
        }
    }
}

/// The gimbal's angles and its pointing law's command at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GimbalReading {
    /// The angles (as the encoders read them).
    pub angles: GimbalAngles,
    /// The pointing law's command.
    pub command: GimbalAngles,
}

/// Wall time spent in each stage of the continuous loop, summed over the run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StageTimes {
    /// Measurement, formation command, excitation and guidance law.
    pub guidance: Duration,
    /// The estimator's work at frames and samples (the Kalman filter's prediction and
    /// update); its prediction between them is in `guidance`.
    pub estimator: Duration,
    /// Flight controller (nothing for the kinematic follower).
    pub control: Duration,
    /// Follower's equations of motion.
    pub plant: Duration,
    /// Everything of the steps but the sensors: RK4 with the three stages above, the bounds,
    /// the excitation's record and the checks.
    pub integration: Duration,
}

/// One evaluation of the loop's continuous part at (t, x).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Evaluation {
    guidance: GuidanceOutput,
    actuation: Actuation,
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
    /// The camera's fixed mount on the body (or on the gimbal's base), L_CB.
    camera_mount: Mat3,
    /// The camera's pan/tilt gimbal, when it rides one.
    gimbal: Option<Gimbal>,
    estimator: Estimator,
    /// The runs of frames that did not measure the target.
    losses: LossLog,
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
        let g = &scenario.guidance;
        let command_kind = match g.law {
            GuidanceLawKind::Velocity => CommandKind::Velocity,
            GuidanceLawKind::Acceleration => CommandKind::Acceleration,
        };
        let (follower, follower_x) = Follower::new(&FollowerConfig {
            follower: &scenario.follower,
            autopilot: &scenario.autopilot,
            atmosphere: &scenario.atmosphere,
            turbulence_seed: scenario.run.seed ^ DRYDEN_SEED_SALT,
            command_kind,
        })?;
        let compensate = scenario.follower.model == FollowerModel::Aircraft;
        let (guidance, notes) = guidance_law(scenario, compensate)?;
        let mut sensor = Sensor::new(&SensorConfig::of(scenario, g.command_length_ft()), gpu)
            .map_err(|e| SimError::Sensor(Box::new(e)))?;
        let estimator = estimator_of(scenario, sensor.is_continuous());
        let target = target_of(scenario);
        let gimbal = (scenario.sensor.mode == SensorMode::Camera
            && scenario.camera.gimbal.kind == GimbalKind::PanTilt)
            .then(|| Gimbal::new(&scenario.camera.gimbal));
        let gimbal_x = gimbal
            .as_ref()
            .map_or(vec![], |g| g.initial_state().to_vec());
        let camera_mount = scenario.camera.camera_from_body();
        let camera_from_body = mounted_camera(&camera_mount, gimbal.as_ref(), &gimbal_x);
        let geometry = capture_geometry(
            target.as_ref(),
            &follower,
            &follower_x,
            0.0,
            &camera_from_body,
        );
        // The filters start at the first measurement: r*(0) with a noisy sensor, the true
        // r(0) otherwise (a camera restarts them at its first frame).
        sensor.draw_initial_noise(&geometry);
        let r0 = geometry.relative_ned_ft / scenario.target.size_ft;
        let r_first = sensor
            .continuous_measurement(&geometry.relative_ned_ft, &geometry.camera_from_ned())
            .unwrap_or(r0);
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
            command: FormationCommand::new(g),
            guidance,
            excitation: Excitation::new(
                &scenario.excitation,
                scenario.run.dt_s,
                excitation_cap(scenario),
            ),
            sensor,
            camera_mount,
            gimbal,
            estimator,
            losses: LossLog::default(),
            layout,
            notes,
            stage_times: Cell::new(StageTimes::default()),
            state,
            tick: 0,
            total_ticks: scenario.run.total_ticks(),
            min_range_ft: r0.norm() * scenario.target.size_ft,
            intercept_time_s: None,
        };
        let first = sim.evaluate().guidance.command;
        let follower_x = sim.layout.split_mut(&mut sim.state).follower;
        sim.follower.align_with_first_command(follower_x, &first);
        sim.sense()?;
        Ok(sim)
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
        let slices = self.layout.split(&self.state);
        capture_geometry(
            self.target.as_ref(),
            &self.follower,
            slices.follower,
            self.time_s(),
            &self.camera_from_body(slices.gimbal),
        )
    }

    /// The gimbal's angles and command now (gimballed cameras).
    pub fn gimbal_reading(&self) -> Option<GimbalReading> {
        let gimbal = self.gimbal.as_ref()?;
        Some(GimbalReading {
            angles: GimbalAngles::of(self.layout.split(&self.state).gimbal),
            command: self.gimbal_command(gimbal, self.time_s(), &self.state),
        })
    }

    /// L_CB for a gimbal slice: the gimbal's angles over the fixed mount.
    fn camera_from_body(&self, gimbal_x: &[f64]) -> Mat3 {
        mounted_camera(&self.camera_mount, self.gimbal.as_ref(), gimbal_x)
    }

    /// The gimbal's command at (t, x): toward where the estimator predicts the target is, and
    /// searching about it once the target has been missing (see [`Gimbal::command`]).
    fn gimbal_command(&self, gimbal: &Gimbal, t_s: f64, x: &[f64]) -> GimbalAngles {
        let slices = self.layout.split(x);
        let position = self.follower.position_ned_ft(slices.follower);
        let law = self.guidance.estimates(slices.guidance);
        let line_of_sight = self.estimator.predicted_r(t_s, &position, law);
        let base_from_ned =
            self.camera_mount * self.follower.attitude(slices.follower).body_from_ned();
        let missing_s = self.estimator.last_measured_s().map_or(0.0, |m| t_s - m);
        gimbal.command(slices.gimbal, line_of_sight, &base_from_ned, missing_s, t_s)
    }

    /// The sensors act at the current tick: a camera frame that reaches the guidance goes to
    /// the estimator (the first starts the law's filters), a continuous sensor's new sample
    /// to the Kalman filter when there is one.
    fn sense(&mut self) -> Result<(), SimError> {
        let t_s = self.time_s();
        let geometry = self.capture_geometry();
        let delivered =
            self.sensor
                .sample(self.tick, t_s, &geometry)
                .map_err(|e| SimError::Camera {
                    t_s,
                    source: Box::new(e),
                })?;
        let started = Instant::now();
        let velocity = geometry.navigation.velocity_ned_fps;
        let first = match delivered {
            Some(record) => {
                self.losses.record(record.t_s, record.r_measured.is_some());
                self.estimator.deliver(&record, &velocity)
            }
            None => {
                self.sample_continuous(&geometry, &velocity);
                false
            }
        };
        if first
            && let GuidanceMeasurement::Now { r: Some(r0), .. } =
                self.guidance_measurement(t_s, &self.state)
        {
            let guidance_x = self.layout.split_mut(&mut self.state).guidance;
            self.guidance.start_at(guidance_x, &r0);
        }
        let mut times = self.stage_times.get();
        times.estimator += started.elapsed();
        self.stage_times.set(times);
        Ok(())
    }

    /// A continuous sensor's sample for the Kalman filter, when this tick draws one.
    fn sample_continuous(&mut self, geometry: &CaptureGeometry, follower_velocity_ned_fps: &Vec3) {
        if self.estimator.filter().is_none() || !self.sensor.is_sample_tick(self.tick) {
            return;
        }
        let body_from_ned = geometry.camera_from_ned();
        let relative = &geometry.relative_ned_ft;
        if let Some(r_star) = self.sensor.continuous_measurement(relative, &body_from_ned) {
            let variance = self.sensor.continuous_variance(relative, &body_from_ned);
            self.estimator.sample(
                self.time_s(),
                &r_star,
                variance,
                &geometry.navigation.position_ned_ft,
                follower_velocity_ned_fps,
            );
        }
    }

    /// The measurement the estimator stage gives the guidance at (t, x).
    fn guidance_measurement(&self, t_s: f64, x: &[f64]) -> GuidanceMeasurement {
        let slices = self.layout.split(x);
        let position = self.follower.position_ned_ft(slices.follower);
        self.estimator.guidance_measurement(
            t_s,
            &position,
            self.guidance.estimates(slices.guidance),
            || {
                let relative = self.target.position_ned_ft(t_s) - position;
                let camera_from_ned = self.camera_from_body(slices.gimbal)
                    * self.follower.attitude(slices.follower).body_from_ned();
                self.sensor
                    .continuous_measurement(&relative, &camera_from_ned)
            },
        )
    }

    /// The estimates b̂ and d̂ the guidance flies on at (t, x): the adaptive law's own, or the
    /// Kalman filter's (`None` before its first measurement).
    fn estimates(&self, x: &[f64], measurement: &GuidanceMeasurement) -> Option<LawEstimates> {
        let guidance_x = self.layout.split(x).guidance;
        self.guidance.estimates(guidance_x).or(match measurement {
            GuidanceMeasurement::Now {
                estimate: Some(e), ..
            } => Some(LawEstimates {
                b_hat_ft: e.b_hat_ft,
                target_motion: TargetMotionEstimate::ScaledVelocity(e.d_per_s),
            }),
            _ => None,
        })
    }

    /// What the command frames follow at (t, x): the follower's attitude and rates, and the
    /// track of the target frame: the target's estimated velocity once it is trusted (the
    /// Kalman filter knows its heading; or the adaptive velocity law's d̂), none before (the
    /// frame holds). With the Kalman estimate the track leads by the frame's lag, d̂ + â τ, so that
    /// the frame does not trail a steadily turning target by its turn rate times τ.
    fn command_input(&self, x: &[f64], measurement: &GuidanceMeasurement) -> CommandInput {
        let follower_x = self.layout.split(x).follower;
        let g = &self.scenario.guidance;
        let heading_gate_rad = g.command_target_heading_sigma_deg.to_radians();
        let track_ned = match (measurement, self.estimator.filter()) {
            (
                GuidanceMeasurement::Now {
                    estimate: Some(e), ..
                },
                Some(tracker),
            ) if tracker.heading_sigma_rad() < heading_gate_rad => {
                Some(e.d_per_s + e.a_per_s2 * g.command_target_lead_s)
            }
            (_, None) => match self.estimates(x, measurement) {
                Some(LawEstimates {
                    target_motion: TargetMotionEstimate::ScaledVelocity(d),
                    ..
                }) => Some(d),
                _ => None,
            },
            _ => None,
        };
        CommandInput {
            attitude: self.follower.attitude(follower_x),
            body_rates_rps: self.follower.body_rates(follower_x),
            track_ned,
        }
    }

    /// The guidance input at (t, x) for a measurement: command, its rate, the excitation, the
    /// follower's navigation and the Kalman estimate.
    fn guidance_input(
        &self,
        t_s: f64,
        x: &[f64],
        command: &CommandInput,
        r_measured: Option<Vec3>,
        estimate: Option<TargetEstimate>,
    ) -> GuidanceInput {
        let slices = self.layout.split(x);
        let (follower_x, command_x) = (slices.follower, slices.command);
        let (command_ned_ft, command_rate_ned_fps) = self.command.command(command_x, command);
        GuidanceInput {
            r_measured,
            command_ned_ft,
            command_rate_ned_fps,
            command_frame_rate_rps: self.command.shaping_frame_rate_rps(command_x, command),
            excitation: self.excitation.command_offset(t_s),
            follower: self.follower.feedback(follower_x),
            estimate,
        }
    }

    /// ẋ of the whole state at (t, x), with what guidance and control decided there. The
    /// three stages are timed apart (see [`StageTimes`]).
    fn derivative(&self, t_s: f64, x: &[f64], dx: &mut [f64]) -> Evaluation {
        let started = Instant::now();
        let x_of = self.layout.split(x);
        let dx_of = self.layout.split_mut(dx);
        let measurement = self.guidance_measurement(t_s, x);
        let command = self.command_input(x, &measurement);
        self.command
            .derivative(x_of.command, &command, dx_of.command);
        if let Some(gimbal) = &self.gimbal {
            let pointing = self.gimbal_command(gimbal, t_s, x);
            gimbal.derivative(x_of.gimbal, &pointing, dx_of.gimbal);
        }
        let out = match measurement {
            GuidanceMeasurement::NotYet => self.guidance.idle(x_of.guidance, dx_of.guidance),
            GuidanceMeasurement::Now { r, estimate } => {
                let input = self.guidance_input(t_s, x, &command, r, estimate);
                self.guidance
                    .derivative(x_of.guidance, &input, dx_of.guidance)
            }
        };
        let guided = Instant::now();
        let actuation = self
            .follower
            .control(x_of.follower, &out.command, dx_of.follower);
        let controlled = Instant::now();
        self.follower
            .plant(x_of.follower, &actuation, dx_of.follower);
        let mut times = self.stage_times.get();
        times.guidance += guided - started;
        times.control += controlled - guided;
        times.plant += controlled.elapsed();
        self.stage_times.set(times);
        Evaluation {
            guidance: out,
            actuation,
        }
    }

    /// Guidance and control at the current state.
    fn evaluate(&mut self) -> Evaluation {
        let mut scratch = std::mem::take(&mut self.scratch);
        let out = self.derivative(self.time_s(), &self.state, &mut scratch);
        self.scratch = scratch;
        out
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
        let (command, _) = self
            .command
            .command(command_x, &self.command_input(&self.state, &measurement));
        let g = &self.scenario.guidance;
        let estimates = self
            .estimates(&self.state, &measurement)
            .unwrap_or(LawEstimates {
                b_hat_ft: g.b0_ft,
                target_motion: TargetMotionEstimate::ScaledVelocity(Vec3::from(g.d0_per_s)),
            });
        let excitation = self.excitation.command_offset(t_s);
        Snapshot {
            t_s,
            target,
            follower_position_ned_ft: follower,
            follower_velocity_ned_fps: self.follower.velocity_ned_fps(follower_x, &out.command),
            follower_attitude: self.follower.attitude(follower_x),
            relative_ned_ft: target.position_ned_ft - follower,
            command_ned_ft: command,
            excited_command_ned_ft: command + excitation.in_ft(estimates.b_hat_ft),
            excitation_amplitude: self.excitation.amplitude(),
            r_measured: match measurement {
                GuidanceMeasurement::Now { r, .. } => r,
                GuidanceMeasurement::NotYet => None,
            },
            b_hat_ft: estimates.b_hat_ft,
            target_motion: estimates.target_motion,
            filter: self.estimator.filter_reading(t_s, &follower),
            guidance: out,
            frame: self.camera().and_then(CameraSensor::last_record),
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
        let follower_x = self.layout.split(&self.state).follower;
        self.follower.begin_step(follower_x, dt_s);
        self.target.advance(t_s, dt_s);
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
        let size_sigma_ft = self
            .estimator
            .filter()
            .and_then(|t| t.posterior())
            .map(|e| e.b_sigma_ft);
        self.excitation
            .record_errors(t_end_s, &out.excitation_errors, size_sigma_ft);
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

/// The guidance law for the scenario's estimator: the seed's adaptive laws, or the velocity law
/// on the Kalman estimate; compensating for a follower that does not realise the command when
/// `compensate`.
fn guidance_law(
    scenario: &Scenario,
    compensate: bool,
) -> Result<(GuidanceLaw, Vec<String>), GuidanceSetupError> {
    let g = &scenario.guidance;
    match scenario.estimator.kind {
        EstimatorKind::Adaptive => GuidanceLaw::adaptive(g, &scenario.acceleration, compensate),
        EstimatorKind::Kalman => Ok((GuidanceLaw::on_estimate(g, compensate), Vec::new())),
    }
}

/// The cap the field of view puts on the excitation's amplitude with a camera
/// (`excitation.fov_fraction` of the half field of view along the excitation's direction at
/// the commanded range), in the excitation's units.
fn excitation_cap(scenario: &Scenario) -> Option<f64> {
    let e = &scenario.excitation;
    if scenario.sensor.mode != SensorMode::Camera || e.fov_fraction <= 0.0 {
        return None;
    }
    let camera = &scenario.camera;
    let focal_px = camera.focal_length_px();
    let direction = Vec3::from(e.direction).normalize();
    // The tangent of the half field of view the direction moves the target across: vertical
    // for its down part, horizontal for its level part (whatever the heading), the tighter.
    let tan_half_vertical = f64::from(camera.height_px) * 0.5 / focal_px;
    let tan_half_horizontal = f64::from(camera.width_px) * 0.5 / focal_px;
    let vertical = direction.z.abs();
    let level = direction.x.hypot(direction.y);
    let tan_allowed = [(vertical, tan_half_vertical), (level, tan_half_horizontal)]
        .iter()
        .filter(|(part, _)| *part > 1e-9)
        .map(|(part, tan_half)| tan_half / part)
        .fold(f64::INFINITY, f64::min);
    let cap_ft = e.fov_fraction * scenario.guidance.command_length_ft() * tan_allowed;
    Some(match e.units {
        ExcitationUnits::Ft => cap_ft,
        ExcitationUnits::Scaled => cap_ft / scenario.guidance.b0_ft,
    })
}

/// The estimator `[estimator] kind` asks for, fed by a continuous sensor or a camera; the
/// guidance law it pairs with is chosen beside it in [`Simulation::on_gpu`].
fn estimator_of(scenario: &Scenario, continuous_sensor: bool) -> Estimator {
    let e = &scenario.estimator;
    let g = &scenario.guidance;
    let filter = || -> Box<dyn TargetTracker> {
        Box::new(KalmanTracker::new(
            e,
            scenario.camera.focal_length_px(),
            g.b0_ft,
            (g.b_min_ft, g.b_max_ft),
        ))
    };
    match e.kind {
        EstimatorKind::Adaptive => Estimator::Adaptive {
            hold: MeasurementHold::new(continuous_sensor, scenario.camera.compensate_delay),
            beside: e.log_kalman.then(filter),
        },
        EstimatorKind::Kalman => Estimator::OnFilter(filter()),
    }
}

/// The target `[target]` describes.
fn target_of(scenario: &Scenario) -> Box<dyn TargetModel> {
    match scenario.target.motion {
        TargetMotion::SeedProfile | TargetMotion::Straight => {
            Box::new(TargetMotionModel::from_section(&scenario.target))
        }
    }
}

/// L_CB of a camera on its fixed mount, or on a gimbal (its angles in `gimbal_x`) over it.
fn mounted_camera(mount: &Mat3, gimbal: Option<&Gimbal>, gimbal_x: &[f64]) -> Mat3 {
    match gimbal {
        Some(_) => GimbalAngles::of(gimbal_x).camera_from_body() * mount,
        None => *mount,
    }
}

/// Where follower and target are at `t_s` for a follower slice.
fn capture_geometry(
    target: &dyn TargetModel,
    follower: &Follower,
    follower_x: &[f64],
    t_s: f64,
    camera_from_body: &Mat3,
) -> CaptureGeometry {
    let pose = FollowerPose {
        position_ned_ft: follower.position_ned_ft(follower_x),
        velocity_ned_fps: follower.track_ned_fps(follower_x),
        attitude: follower.attitude(follower_x),
        camera_from_body: *camera_from_body,
    };
    CaptureGeometry::exact(
        target.position_ned_ft(t_s) - pose.position_ned_ft,
        target.state(t_s).attitude,
        pose,
    )
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
}
