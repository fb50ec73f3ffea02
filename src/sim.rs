//! The simulation: owns every stage and wires one tick in a fixed order (DESIGN §1).
//!
//! Continuous state, integrated as one vector by RK4:
//! `[follower | command frame (ψ_c) | guidance law]`, the follower's slice being the
//! kinematic follower's `(R_F, φ, θ, ψ, v)` or the 6-DOF aircraft's
//! `[plant | autopilot | V_F (acceleration law)]` (see [`Follower`]).
//! The stages are swappable: the guidance law (`velocity` | `acceleration`, see
//! [`GuidanceLaw`]) commands the follower with a [`FollowerCommand`] that the follower stage
//! realises (the kinematic follower exactly; the aircraft through its flight controller).
//! The target's motion is closed-form. With the `perfect` and `noisy` sensors r = R/b is
//! evaluated at every RK4 stage (the seed's continuous-time loop), the noisy sensor adding
//! the noise it drew at the start of the tick; a camera's measurement is held over the step.
//!
//! One tick: (1) the sensor may draw noise or deliver a camera measurement (taken from the
//! truth at the start of the tick); the aircraft's turbulence advances and is held over the
//! step; (2) RK4 advances follower and guidance together, each stage evaluating guidance,
//! control and plant in that order (timed apart); (3) projection bounds, angle wrapping and
//! quaternion norm are enforced; (4) the excitation records the tracking error and the
//! aircraft's flight envelope the instant; (5) divergence and interception are checked.

use crate::follower::{Actuation, AircraftActuation, FlightEnvelope, Follower};
use crate::frames::{EulerAngles, Vec3};
use crate::guidance::command::{self, FormationCommand};
use crate::guidance::excitation::Excitation;
use crate::guidance::law::{GuidanceInput, GuidanceLaw, GuidanceOutput};
use crate::integrate::Rk4;
use crate::noisy_sensor::NoisySensor;
use crate::scenario::{ExcitationError, ExcitationUnits, Mission, Scenario, SensorMode};
use crate::sensor::{CameraSensor, CaptureGeometry, FrameRecord};
use crate::world::kinematic::FollowerCommand;
use crate::world::target::{TargetMotionModel, TargetState};
use std::cell::Cell;
use std::time::{Duration, Instant};

/// Why a simulation could not start or go on.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimError {
    /// A state became non-finite or absurdly large.
    #[error("the run diverged at t = {t_s:.3} s: {what}")]
    Diverged {
        /// Time of detection, s.
        t_s: f64,
        /// What went wrong.
        what: String,
    },
    /// A stage could not be built from the scenario.
    #[error("cannot set up the simulation: {0}")]
    Setup(String),
    /// The camera failed to take or measure a frame.
    #[error("camera failure at t = {t_s:.3} s: {what}")]
    Camera {
        /// Time of the frame, s.
        t_s: f64,
        /// What failed.
        what: String,
    },
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
    /// The r the guidance was given (None while the sensor has nothing).
    pub r_measured: Option<Vec3>,
    /// b̂, ft.
    pub b_hat_ft: f64,
    /// d̂ in the law's units: 1/s (velocity law), ft/s (acceleration law), see
    /// [`GuidanceLaw::d_hat`].
    pub d_hat: Vec3,
    /// Guidance output.
    pub guidance: GuidanceOutput,
    /// The last camera frame's measurement and truth (camera runs).
    pub frame: Option<FrameRecord>,
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

/// Where the guidance's r comes from during a step.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Measurement {
    /// r = R/b from the stage's state (seed Chapters 4-5), plus the noisy sensor's held noise
    /// (Chapter 6).
    Continuous,
    /// A sampled measurement held until the next one arrives; None while the target is lost.
    Held(Option<HeldMeasurement>),
    /// No measurement has arrived yet: the guidance has not started and the follower cruises
    /// at b̂(0) d̂(0) (velocity law) or keeps V_F(0) (acceleration law).
    AwaitingFirst,
}

/// A camera measurement as the guidance holds it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct HeldMeasurement {
    /// r* of the frame.
    r: Vec3,
    /// When the frame was taken, s.
    t_s: f64,
    /// Where the follower was then, NED, ft.
    follower_position_ned_ft: Vec3,
}

impl HeldMeasurement {
    /// The measurement brought forward to time `t_s` (when `compensate` is set): the frame is
    /// a frame period plus the latency old, and in that time r has moved by the follower's own
    /// displacement, known from its navigation, over b̂, and by the target's drift d̂ (t - t_k)
    /// when the law estimates it (velocity law):
    /// r ≈ r*(t_k) - (R_F(t) - R_F(t_k))/b̂ + d̂ (t - t_k). The seed assumed continuous,
    /// instantaneous measurements; without this the stale r* biases the adaptation every
    /// frame.
    fn at(
        &self,
        t_s: f64,
        follower_position_ned_ft: &Vec3,
        b_hat_ft: f64,
        drift: Option<Vec3>,
        compensate: bool,
    ) -> Vec3 {
        if !compensate {
            return self.r;
        }
        let own = (follower_position_ned_ft - self.follower_position_ned_ft) / b_hat_ft;
        self.r - own + drift.unwrap_or_else(Vec3::zeros) * (t_s - self.t_s)
    }
}

/// Wall time spent in each stage of the continuous loop, summed over the run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StageTimes {
    /// Measurement hold, formation command, excitation and guidance law.
    pub guidance: Duration,
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

/// Offsets of the stages' slices in the state vector.
#[derive(Debug, Clone, Copy, PartialEq)]
struct StateLayout {
    /// Start of the command slice (the follower's slice is before it).
    command: usize,
    /// Start of the guidance slice.
    guidance: usize,
}

/// A running simulation.
#[derive(Debug)]
pub struct Simulation {
    scenario: Scenario,
    target: TargetMotionModel,
    follower: Follower,
    /// The 6-DOF follower's extremes and limit hits (aircraft runs).
    envelope: Option<FlightEnvelope>,
    command: FormationCommand,
    guidance: GuidanceLaw,
    excitation: Excitation,
    measurement: Measurement,
    noisy: Option<NoisySensor>,
    camera: Option<CameraSensor>,
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
    /// Builds every stage from a validated scenario.
    pub fn new(scenario: &Scenario) -> Result<Self, SimError> {
        let target = TargetMotionModel::from_section(&scenario.target);
        let (guidance, notes) =
            GuidanceLaw::from_scenario(scenario).map_err(|e| SimError::Setup(e.to_string()))?;
        let excitation = Excitation::new(&scenario.excitation, scenario.run.dt_s);
        let (follower, mut state) =
            Follower::new(scenario).map_err(|e| SimError::Setup(e.to_string()))?;
        let follower0 = follower.position_ned_ft(&state);
        let attitude0 = follower.attitude(&state);
        let relative0 = target.position_ned_ft(0.0) - follower0;
        let r0 = relative0 / scenario.target.size_ft;
        let camera = match scenario.sensor.mode {
            SensorMode::Perfect | SensorMode::Noisy => None,
            SensorMode::Camera => {
                Some(CameraSensor::new(scenario).map_err(|e| SimError::Setup(e.to_string()))?)
            }
        };
        let mut noisy =
            (scenario.sensor.mode == SensorMode::Noisy).then(|| NoisySensor::new(scenario));
        let measurement = match camera {
            None => Measurement::Continuous,
            Some(_) => Measurement::AwaitingFirst,
        };
        // The filters start at the first measurement, r*(0) with a noisy sensor.
        let r_first = match noisy.as_mut() {
            Some(sensor) => {
                let body_from_ned = attitude0.body_from_ned();
                sensor.draw(&relative0, &body_from_ned);
                sensor.measure(&relative0, &body_from_ned).unwrap_or(r0)
            }
            None => r0,
        };
        let layout = StateLayout {
            command: state.len(),
            guidance: state.len() + command::STATE_LEN,
        };
        state.extend(FormationCommand::initial_state(&attitude0));
        state.extend(guidance.initial_state(&r_first));
        let mut sim = Self {
            rk4: Rk4::new(state.len()),
            scratch: vec![0.0; state.len()],
            scenario: scenario.clone(),
            target,
            envelope: follower.aircraft().map(|_| FlightEnvelope::default()),
            follower,
            command: FormationCommand::new(&scenario.guidance),
            guidance,
            excitation,
            measurement,
            noisy,
            camera,
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
        let at = sim.layout.command;
        sim.follower
            .align_with_first_command(&mut sim.state[..at], &first);
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
        self.camera.as_ref()
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

    /// The noisy sensor, in noisy runs.
    pub fn noisy_sensor(&self) -> Option<&NoisySensor> {
        self.noisy.as_ref()
    }

    /// What the stages' set-up had to say, for the run's log (e.g. a Riccati observer gain
    /// that fell back to the fixed gain).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    // The follower stage as the rest of the tick sees it: its slice of the state, position,
    // attitude, body rates and velocity (see [`Follower`]).

    /// The follower's slice of a state.
    fn follower_x<'a>(&self, x: &'a [f64]) -> &'a [f64] {
        &x[..self.layout.command]
    }

    /// R_F of a state, NED, ft.
    fn follower_position_ned_ft(&self, x: &[f64]) -> Vec3 {
        self.follower.position_ned_ft(self.follower_x(x))
    }

    /// The follower's attitude in a state (camera = body).
    fn follower_attitude(&self, x: &[f64]) -> EulerAngles {
        self.follower.attitude(self.follower_x(x))
    }

    /// The follower's body rates [p, q, r] in a state, rad/s.
    fn follower_body_rates(&self, x: &[f64]) -> Vec3 {
        self.follower.body_rates(self.follower_x(x))
    }

    /// R = R_T - R_F at time `t_s` for a state, NED, ft.
    fn relative_ned_ft(&self, t_s: f64, x: &[f64]) -> Vec3 {
        self.target.position_ned_ft(t_s) - self.follower_position_ned_ft(x)
    }

    /// V_F of the follower at the current state for the guidance output `out`.
    fn follower_velocity(&self, out: &GuidanceOutput) -> Vec3 {
        self.follower
            .velocity_ned_fps(self.follower_x(&self.state), &out.command)
    }

    /// The continuous measurement at (t, x): r = R/b (perfect) or r* (noisy, with the held
    /// noise).
    fn continuous_measurement(&self, t_s: f64, x: &[f64]) -> Option<Vec3> {
        let relative = self.relative_ned_ft(t_s, x);
        match &self.noisy {
            None => Some(relative / self.scenario.target.size_ft),
            Some(sensor) => {
                let body_from_ned = self.follower_attitude(x).body_from_ned();
                sensor.measure(&relative, &body_from_ned)
            }
        }
    }

    /// Draws the noisy sensor's next noise sample if one is due at this tick (the first was
    /// drawn at set-up).
    fn draw_noise(&mut self) {
        let tick = self.tick;
        if tick == 0 {
            return;
        }
        let relative = self.relative_ned_ft(self.time_s(), &self.state);
        let body_from_ned = self.follower_attitude(&self.state).body_from_ned();
        if let Some(sensor) = self.noisy.as_mut().filter(|s| s.is_sample_tick(tick)) {
            sensor.draw(&relative, &body_from_ned);
        }
    }

    /// A held camera measurement brought forward to (t, x) (see [`HeldMeasurement::at`]).
    fn bring_forward(&self, m: &HeldMeasurement, t_s: f64, x: &[f64]) -> Vec3 {
        let guidance_x = &x[self.layout.guidance..];
        m.at(
            t_s,
            &self.follower_position_ned_ft(x),
            self.guidance.b_hat_ft(guidance_x),
            self.guidance.scaled_target_velocity(guidance_x),
            self.scenario.camera.compensate_delay,
        )
    }

    /// Where follower and target are now, as a camera frame would see them.
    pub fn capture_geometry(&self) -> CaptureGeometry {
        let t_s = self.time_s();
        CaptureGeometry {
            relative_ned_ft: self.relative_ned_ft(t_s, &self.state),
            follower_position_ned_ft: self.follower_position_ned_ft(&self.state),
            follower_attitude: self.follower_attitude(&self.state),
            target_attitude: self.target.state(t_s).attitude,
        }
    }

    /// Takes a camera frame at this tick if one is due and holds its (delayed) measurement.
    fn sense(&mut self) -> Result<(), SimError> {
        self.draw_noise();
        let tick = self.tick;
        let t_s = self.time_s();
        if !self.camera.as_ref().is_some_and(|c| c.is_frame_tick(tick)) {
            return Ok(());
        }
        let geometry = self.capture_geometry();
        let Some(camera) = self.camera.as_mut() else {
            return Ok(());
        };
        let held = camera
            .capture(t_s, &geometry)
            .map_err(|e| SimError::Camera {
                t_s,
                what: e.to_string(),
            })?;
        let Some(record) = held else {
            return Ok(());
        };
        let r = record.r_measured.map(|r| HeldMeasurement {
            r,
            t_s: record.t_s,
            follower_position_ned_ft: record.follower_position_ned_ft,
        });
        if let (Measurement::AwaitingFirst, Some(first)) = (self.measurement, r) {
            // The guidance starts on its first measurement, brought forward to now.
            let r0 = self.bring_forward(&first, t_s, &self.state);
            let at = self.layout.guidance;
            self.guidance.start_at(&mut self.state[at..], &r0);
        }
        if r.is_some() || self.measurement != Measurement::AwaitingFirst {
            self.measurement = Measurement::Held(r);
        }
        Ok(())
    }

    /// The user's command R_c and Ṙ_c (NED, ft and ft/s) for the follower and command
    /// slices of a state (see [`FormationCommand`]).
    fn command(&self, x: &[f64]) -> (Vec3, Vec3) {
        let attitude = self.follower_attitude(x);
        let omega = self.follower_body_rates(x);
        self.command.command(
            &x[self.layout.command..self.layout.guidance],
            &attitude,
            &omega,
        )
    }

    /// The guidance input at (t, x) for a measurement: command, its rate and the excitation.
    fn guidance_input(&self, t_s: f64, x: &[f64], r_measured: Option<Vec3>) -> GuidanceInput {
        let (command_ned_ft, command_rate_ned_fps) = self.command(x);
        let (offset, offset_rate) = self.excitation.offset(t_s);
        let zero = Vec3::zeros();
        let (
            (excitation_ned_ft, excitation_rate_ned_fps),
            (excitation_scaled, excitation_scaled_rate),
        ) = match self.excitation.units() {
            ExcitationUnits::Ft => ((offset, offset_rate), (zero, zero)),
            ExcitationUnits::Scaled => ((zero, zero), (offset, offset_rate)),
        };
        GuidanceInput {
            r_measured,
            command_ned_ft,
            command_rate_ned_fps,
            excitation_ned_ft,
            excitation_rate_ned_fps,
            excitation_scaled,
            excitation_scaled_rate,
            follower_velocity_ned_fps: self.follower.realised_velocity_ned_fps(self.follower_x(x)),
            follower_velocity_shortfall_ned_fps: self
                .follower
                .velocity_shortfall_ned_fps(self.follower_x(x)),
        }
    }

    /// ẋ of the whole state at (t, x), with what guidance and control decided there. The
    /// three stages are timed apart (see [`StageTimes`]).
    fn derivative(&self, t_s: f64, x: &[f64], dx: &mut [f64]) -> Evaluation {
        let started = Instant::now();
        let StateLayout { command, guidance } = self.layout;
        let (command_and_follower_x, guidance_x) = x.split_at(guidance);
        let (follower_x, command_x) = command_and_follower_x.split_at(command);
        let (command_and_follower_dx, guidance_dx) = dx.split_at_mut(guidance);
        let (follower_dx, command_dx) = command_and_follower_dx.split_at_mut(command);
        self.command
            .derivative(command_x, &self.follower_attitude(x), command_dx);
        let out = match self.measurement {
            Measurement::Continuous => {
                let r_measured = self.continuous_measurement(t_s, x);
                let input = self.guidance_input(t_s, x, r_measured);
                self.guidance.derivative(guidance_x, &input, guidance_dx)
            }
            Measurement::Held(held) => {
                let r_measured = held.map(|m| self.bring_forward(&m, t_s, x));
                let input = self.guidance_input(t_s, x, r_measured);
                self.guidance.derivative(guidance_x, &input, guidance_dx)
            }
            Measurement::AwaitingFirst => self.guidance.idle(guidance_x, guidance_dx),
        };
        let guided = Instant::now();
        let actuation = self.follower.control(follower_x, &out.command, follower_dx);
        let controlled = Instant::now();
        self.follower.plant(follower_x, &actuation, follower_dx);
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
        let guidance_x = &self.state[self.layout.guidance..];
        let follower = self.follower_position_ned_ft(&self.state);
        let target = self.target.state(t_s);
        let (command, _) = self.command(&self.state);
        let b_hat_ft = self.guidance.b_hat_ft(guidance_x);
        let (offset, _) = self.excitation.offset(t_s);
        let excitation_ned_ft = match self.excitation.units() {
            ExcitationUnits::Ft => offset,
            ExcitationUnits::Scaled => offset * b_hat_ft,
        };
        let relative = target.position_ned_ft - follower;
        Snapshot {
            t_s,
            target,
            follower_position_ned_ft: follower,
            follower_velocity_ned_fps: self.follower_velocity(&out),
            follower_attitude: self.follower_attitude(&self.state),
            relative_ned_ft: relative,
            command_ned_ft: command,
            excited_command_ned_ft: command + excitation_ned_ft,
            excitation_amplitude: self.excitation.amplitude(),
            r_measured: match self.measurement {
                Measurement::Continuous => self.continuous_measurement(t_s, &self.state),
                Measurement::Held(held) => held.map(|m| m.r),
                Measurement::AwaitingFirst => None,
            },
            b_hat_ft,
            d_hat: self.guidance.d_hat(guidance_x),
            guidance: out,
            frame: self.camera.as_ref().and_then(CameraSensor::last_record),
            aircraft: actuation.aircraft().copied(),
        }
    }

    /// Advances one tick.
    pub fn step(&mut self) -> Result<StepOutcome, SimError> {
        if self.tick >= self.total_ticks {
            return Ok(StepOutcome::Finished);
        }
        self.sense()?;
        let integrate_started = Instant::now();
        let t_s = self.time_s();
        let dt_s = self.scenario.run.dt_s;
        let at = self.layout.command;
        self.follower.begin_step(&self.state[..at], dt_s);
        let mut state = std::mem::take(&mut self.state);
        let mut rk4 = std::mem::replace(&mut self.rk4, Rk4::new(0));
        rk4.step(t_s, dt_s, &mut state, |t, x, dx| {
            self.derivative(t, x, dx);
        });
        self.rk4 = rk4;
        let (command_and_follower_x, guidance_x) = state.split_at_mut(self.layout.guidance);
        let (follower_x, command_x) = command_and_follower_x.split_at_mut(self.layout.command);
        self.follower.normalize(follower_x);
        FormationCommand::normalize(command_x);
        self.guidance.enforce_bounds(guidance_x);
        self.state = state;
        self.tick += 1;
        let outcome = self.after_step();
        let mut times = self.stage_times.get();
        times.integration += integrate_started.elapsed();
        self.stage_times.set(times);
        outcome
    }

    /// Checks, records and decides after a step: divergence, range, the excitation's error
    /// energy, the flight envelope, interception and the end of the run.
    fn after_step(&mut self) -> Result<StepOutcome, SimError> {
        let t_end_s = self.time_s();

        if let Some(i) = self.state.iter().position(|v| !v.is_finite()) {
            return Err(SimError::Diverged {
                t_s: t_end_s,
                what: format!("state element {i} is {}", self.state[i]),
            });
        }
        let range_ft = self.relative_ned_ft(t_end_s, &self.state).norm();
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
        let error = match self.scenario.excitation.error {
            ExcitationError::Measured => out.error,
            ExcitationError::Estimated => out.estimated_error,
        };
        self.excitation.record(t_end_s, error.norm_squared());

        if self.scenario.guidance.mission == Mission::Intercept
            && range_ft < self.scenario.guidance.intercept_radius_ft
        {
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
