//! The simulation: owns every stage and wires one tick in a fixed order (DESIGN §1).
//!
//! Continuous state, integrated as one vector by RK4:
//! `[follower (R_F, φ, θ, ψ) | command frame (ψ_c) | guidance]`.
//! The target's motion is closed-form. With the `perfect` sensor r = R/b is evaluated at every
//! RK4 stage (the seed's continuous-time loop); a sampled sensor's measurement is held over
//! the step.
//!
//! One tick: (1) the sensor may deliver a measurement (taken from the truth at the start of
//! the tick); (2) RK4 advances follower and guidance together; (3) projection bounds and angle
//! wrapping are enforced; (4) the excitation records the tracking error; (5) divergence and
//! interception are checked.

use crate::frames::{EulerAngles, Mat3, Vec3};
use crate::guidance::command::{self, FormationCommand};
use crate::guidance::excitation::Excitation;
use crate::guidance::velocity::{
    VelocityEstimator, VelocityGuidance, VelocityGuidanceInput, VelocityGuidanceOutput,
};
use crate::integrate::Rk4;
use crate::scenario::{ExcitationUnits, Mission, Scenario, SensorMode};
use crate::sensor::{CameraSensor, CaptureGeometry, FrameRecord};
use crate::world::kinematic::{self, KinematicFollower};
use crate::world::target::{TargetMotionModel, TargetState};
use std::time::{Duration, Instant};

/// Offset of the command slice in the state vector.
const COMMAND: usize = kinematic::STATE_LEN;
/// Offset of the guidance slice in the state vector.
const GUIDANCE: usize = COMMAND + command::STATE_LEN;

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
    /// d̂, 1/s.
    pub d_hat: Vec3,
    /// Guidance output.
    pub guidance: VelocityGuidanceOutput,
    /// The last camera frame's measurement and truth (camera runs).
    pub frame: Option<FrameRecord>,
}

/// Where the guidance's r comes from during a step.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Measurement {
    /// r = R/b from the stage's state (seed Chapters 4-5).
    Continuous,
    /// A sampled measurement held until the next one arrives; None while the target is lost.
    Held(Option<HeldMeasurement>),
    /// No measurement has arrived yet: the guidance has not started and the follower cruises
    /// at b̂(0) d̂(0).
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
    /// displacement, known from its navigation, over b̂, and by the target's drift d̂ (t - t_k):
    /// r ≈ r*(t_k) - (R_F(t) - R_F(t_k))/b̂ + d̂ (t - t_k). The seed assumed continuous,
    /// instantaneous measurements; without this the stale r* biases the adaptation every frame.
    fn at(
        &self,
        t_s: f64,
        follower_position_ned_ft: &Vec3,
        b_hat_ft: f64,
        d_hat: &Vec3,
        compensate: bool,
    ) -> Vec3 {
        if !compensate {
            return self.r;
        }
        self.r - (follower_position_ned_ft - self.follower_position_ned_ft) / b_hat_ft
            + d_hat * (t_s - self.t_s)
    }
}

/// A running simulation.
#[derive(Debug)]
pub struct Simulation {
    scenario: Scenario,
    target: TargetMotionModel,
    follower: KinematicFollower,
    command: FormationCommand,
    guidance: VelocityGuidance,
    excitation: Excitation,
    measurement: Measurement,
    camera: Option<CameraSensor>,
    /// Wall time spent integrating (guidance, follower), s.
    integrate_time: Duration,
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
        let g = &scenario.guidance;
        let estimator = if g.estimator {
            Some(
                VelocityEstimator::new(g.k, Mat3::identity() * g.estimator_gain)
                    .map_err(|e| SimError::Setup(format!("velocity estimator: {e}")))?,
            )
        } else {
            None
        };
        let guidance = VelocityGuidance::new(g, estimator);
        let excitation = Excitation::new(&scenario.excitation, scenario.run.dt_s);
        let follower = KinematicFollower {
            attitude_lag_s: scenario.follower.attitude_lag_s,
        };
        let follower0 = Vec3::from(scenario.follower.initial_position_ft);
        let [phi, theta, psi] = scenario.follower.initial_attitude_deg.map(f64::to_radians);
        let attitude0 = EulerAngles::new(phi, theta, psi);
        let r0 = (target.position_ned_ft(0.0) - follower0) / scenario.target.size_ft;
        let camera = match scenario.sensor.mode {
            SensorMode::Perfect => None,
            SensorMode::Camera => {
                Some(CameraSensor::new(scenario).map_err(|e| SimError::Setup(e.to_string()))?)
            }
        };
        let measurement = match camera {
            None => Measurement::Continuous,
            Some(_) => Measurement::AwaitingFirst,
        };
        let mut state =
            KinematicFollower::initial_state(&follower0, &attitude0, &Vec3::zeros()).to_vec();
        state.extend(FormationCommand::initial_state(&attitude0));
        state.extend(guidance.initial_state(&r0));
        let mut sim = Self {
            rk4: Rk4::new(state.len()),
            scratch: vec![0.0; state.len()],
            scenario: scenario.clone(),
            target,
            follower,
            command: FormationCommand::new(g),
            guidance,
            excitation,
            measurement,
            camera,
            integrate_time: Duration::ZERO,
            state,
            tick: 0,
            total_ticks: scenario.run.total_ticks(),
            min_range_ft: r0.norm() * scenario.target.size_ft,
            intercept_time_s: None,
        };
        let v0 = sim.evaluate().velocity_cmd_ned_fps;
        KinematicFollower::set_heading_velocity(&mut sim.state[..COMMAND], &v0);
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

    /// Wall time spent integrating follower and guidance so far.
    pub fn integrate_time(&self) -> Duration {
        self.integrate_time
    }

    /// Where follower and target are now, as a camera frame would see them.
    pub fn capture_geometry(&self) -> CaptureGeometry {
        let t_s = self.time_s();
        let follower_x = &self.state[..GUIDANCE];
        CaptureGeometry {
            relative_ned_ft: self.target.position_ned_ft(t_s)
                - KinematicFollower::position_ned_ft(follower_x),
            follower_position_ned_ft: KinematicFollower::position_ned_ft(follower_x),
            follower_attitude: KinematicFollower::attitude(follower_x),
            target_attitude: self.target.state(t_s).attitude,
        }
    }

    /// Takes a camera frame at this tick if one is due and holds its (delayed) measurement.
    fn sense(&mut self) -> Result<(), SimError> {
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
            let guidance_x = &self.state[GUIDANCE..];
            let r0 = first.at(
                t_s,
                &KinematicFollower::position_ned_ft(&self.state[..COMMAND]),
                VelocityGuidance::b_hat_ft(guidance_x),
                &VelocityGuidance::d_hat(guidance_x),
                self.scenario.camera.compensate_delay,
            );
            self.guidance.start_at(&mut self.state[GUIDANCE..], &r0);
        }
        if r.is_some() || self.measurement != Measurement::AwaitingFirst {
            self.measurement = Measurement::Held(r);
        }
        Ok(())
    }

    /// The user's command R_c and Ṙ_c (NED, ft and ft/s) for the follower and command
    /// slices of a state (see [`FormationCommand`]).
    fn command(&self, x: &[f64]) -> (Vec3, Vec3) {
        let follower_x = &x[..COMMAND];
        let attitude = KinematicFollower::attitude(follower_x);
        let euler_rates = self.follower.attitude_rates(follower_x);
        let omega = KinematicFollower::body_rates(&attitude, &euler_rates);
        self.command
            .command(&x[COMMAND..GUIDANCE], &attitude, &omega)
    }

    /// ẋ of the whole state and the guidance output at (t, x).
    fn derivative(&self, t_s: f64, x: &[f64], dx: &mut [f64]) -> VelocityGuidanceOutput {
        let (command_and_follower_x, guidance_x) = x.split_at(GUIDANCE);
        let (follower_x, command_x) = command_and_follower_x.split_at(COMMAND);
        let (command_and_follower_dx, guidance_dx) = dx.split_at_mut(GUIDANCE);
        let (follower_dx, command_dx) = command_and_follower_dx.split_at_mut(COMMAND);
        self.command.derivative(
            command_x,
            &KinematicFollower::attitude(follower_x),
            command_dx,
        );
        let r_measured = match self.measurement {
            Measurement::Continuous => {
                let relative = self.target.position_ned_ft(t_s)
                    - KinematicFollower::position_ned_ft(follower_x);
                Some(relative / self.scenario.target.size_ft)
            }
            Measurement::Held(held) => held.map(|m| {
                m.at(
                    t_s,
                    &KinematicFollower::position_ned_ft(follower_x),
                    VelocityGuidance::b_hat_ft(guidance_x),
                    &VelocityGuidance::d_hat(guidance_x),
                    self.scenario.camera.compensate_delay,
                )
            }),
            Measurement::AwaitingFirst => {
                let out = self.guidance.idle(guidance_x, guidance_dx);
                self.follower
                    .derivative(follower_x, &out.velocity_cmd_ned_fps, follower_dx);
                return out;
            }
        };
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
        let input = VelocityGuidanceInput {
            r_measured,
            command_ned_ft,
            command_rate_ned_fps,
            excitation_ned_ft,
            excitation_rate_ned_fps,
            excitation_scaled,
            excitation_scaled_rate,
        };
        let out = self.guidance.derivative(guidance_x, &input, guidance_dx);
        self.follower
            .derivative(follower_x, &out.velocity_cmd_ned_fps, follower_dx);
        out
    }

    /// The guidance output at the current state.
    fn evaluate(&mut self) -> VelocityGuidanceOutput {
        let mut scratch = std::mem::take(&mut self.scratch);
        let out = self.derivative(self.time_s(), &self.state, &mut scratch);
        self.scratch = scratch;
        out
    }

    /// The state of every stage now.
    pub fn snapshot(&self) -> Snapshot {
        let t_s = self.time_s();
        let mut dx = vec![0.0; self.state.len()];
        let out = self.derivative(t_s, &self.state, &mut dx);
        let (follower_x, guidance_x) = self.state.split_at(GUIDANCE);
        let follower = KinematicFollower::position_ned_ft(follower_x);
        let target = self.target.state(t_s);
        let (command, _) = self.command(&self.state);
        let b_hat_ft = VelocityGuidance::b_hat_ft(guidance_x);
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
            follower_velocity_ned_fps: out.velocity_cmd_ned_fps,
            follower_attitude: KinematicFollower::attitude(follower_x),
            relative_ned_ft: relative,
            command_ned_ft: command,
            excited_command_ned_ft: command + excitation_ned_ft,
            excitation_amplitude: self.excitation.amplitude(),
            r_measured: match self.measurement {
                Measurement::Continuous => Some(relative / self.scenario.target.size_ft),
                Measurement::Held(held) => held.map(|m| m.r),
                Measurement::AwaitingFirst => None,
            },
            b_hat_ft,
            d_hat: VelocityGuidance::d_hat(guidance_x),
            guidance: out,
            frame: self.camera.as_ref().and_then(CameraSensor::last_record),
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
        let mut state = std::mem::take(&mut self.state);
        let mut rk4 = std::mem::replace(&mut self.rk4, Rk4::new(0));
        rk4.step(t_s, dt_s, &mut state, |t, x, dx| {
            self.derivative(t, x, dx);
        });
        self.rk4 = rk4;
        let (command_and_follower_x, guidance_x) = state.split_at_mut(GUIDANCE);
        let (follower_x, command_x) = command_and_follower_x.split_at_mut(COMMAND);
        KinematicFollower::normalize(follower_x);
        FormationCommand::normalize(command_x);
        self.guidance.enforce_bounds(guidance_x);
        self.state = state;
        self.tick += 1;
        self.integrate_time += integrate_started.elapsed();
        let t_end_s = self.time_s();

        if let Some(i) = self.state.iter().position(|v| !v.is_finite()) {
            return Err(SimError::Diverged {
                t_s: t_end_s,
                what: format!("state element {i} is {}", self.state[i]),
            });
        }
        let follower = KinematicFollower::position_ned_ft(&self.state[..GUIDANCE]);
        let range_ft = (self.target.position_ned_ft(t_end_s) - follower).norm();
        self.min_range_ft = self.min_range_ft.min(range_ft);
        if range_ft > 1e6 {
            return Err(SimError::Diverged {
                t_s: t_end_s,
                what: format!("range {range_ft:.3e} ft exceeds 1e6 ft"),
            });
        }
        let out = self.evaluate();
        self.excitation.record(t_end_s, out.error.norm_squared());

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
