//! The simulation: owns every stage and wires one tick in a fixed order (DESIGN §1).
//!
//! Continuous state, integrated as one vector by RK4: `[R_F (3) | guidance state]`. The target's
//! motion is closed-form. With the `perfect` sensor r = R/b is evaluated at every RK4 stage
//! (the seed's continuous-time loop).

use crate::frames::{EulerAngles, Vec3, attitude_along_velocity};
use crate::guidance::excitation::Excitation;
use crate::guidance::velocity::{VelocityGuidance, VelocityGuidanceInput, VelocityGuidanceOutput};
use crate::integrate::Rk4;
use crate::scenario::{ExcitationUnits, Mission, Scenario};
use crate::world::target::{TargetMotionModel, TargetState};

/// Offset of the guidance slice in the state vector (after R_F).
const GUIDANCE: usize = 3;

/// Why a run stopped before its end.
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
    /// Follower attitude (kinematic: nose along V_F).
    pub follower_attitude: EulerAngles,
    /// R = R_T - R_F, NED, ft.
    pub relative_ned_ft: Vec3,
    /// The user's command R_c without excitation, NED, ft.
    pub command_ned_ft: Vec3,
    /// The command with excitation R*_c, NED, ft (scaled excitation times b̂).
    pub excited_command_ned_ft: Vec3,
    /// Excitation amplitude a(t), in the excitation's units.
    pub excitation_amplitude: f64,
    /// The measured r.
    pub r_measured: Vec3,
    /// b̂, ft.
    pub b_hat_ft: f64,
    /// d̂, 1/s.
    pub d_hat: Vec3,
    /// Guidance output.
    pub guidance: VelocityGuidanceOutput,
}

/// A running simulation.
#[derive(Debug, Clone)]
pub struct Simulation {
    scenario: Scenario,
    target: TargetMotionModel,
    guidance: VelocityGuidance,
    excitation: Excitation,
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
    pub fn new(scenario: &Scenario) -> Self {
        let target = TargetMotionModel::from_section(&scenario.target);
        let guidance = VelocityGuidance::new(&scenario.guidance, None);
        let excitation = Excitation::new(&scenario.excitation, scenario.run.dt_s);
        let follower0 = Vec3::from(scenario.follower.initial_position_ft);
        let r0 = (target.position_ned_ft(0.0) - follower0) / scenario.target.size_ft;
        let mut state = follower0.as_slice().to_vec();
        state.extend(guidance.initial_state(&r0));
        Self {
            rk4: Rk4::new(state.len()),
            scratch: vec![0.0; state.len()],
            scenario: scenario.clone(),
            target,
            guidance,
            excitation,
            state,
            tick: 0,
            total_ticks: scenario.run.total_ticks(),
            min_range_ft: r0.norm() * scenario.target.size_ft,
            intercept_time_s: None,
        }
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

    /// The user's command R_c (zero for interception).
    fn command_ned_ft(&self) -> Vec3 {
        match self.scenario.guidance.mission {
            Mission::Formation => Vec3::from(self.scenario.guidance.command_ft),
            Mission::Intercept => Vec3::zeros(),
        }
    }

    /// ẋ of the whole state and the guidance output at (t, x).
    fn derivative(&self, t_s: f64, x: &[f64], dx: &mut [f64]) -> VelocityGuidanceOutput {
        let follower = Vec3::new(x[0], x[1], x[2]);
        let relative = self.target.position_ned_ft(t_s) - follower;
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
            r_measured: relative / self.scenario.target.size_ft,
            command_ned_ft: self.command_ned_ft(),
            command_rate_ned_fps: Vec3::zeros(),
            excitation_ned_ft,
            excitation_rate_ned_fps,
            excitation_scaled,
            excitation_scaled_rate,
        };
        let out = self
            .guidance
            .derivative(&x[GUIDANCE..], &input, &mut dx[GUIDANCE..]);
        dx[0..3].copy_from_slice(out.velocity_cmd_ned_fps.as_slice());
        out
    }

    /// The state of every stage now.
    pub fn snapshot(&self) -> Snapshot {
        let t_s = self.time_s();
        let mut dx = vec![0.0; self.state.len()];
        let out = self.derivative(t_s, &self.state, &mut dx);
        let follower = Vec3::new(self.state[0], self.state[1], self.state[2]);
        let target = self.target.state(t_s);
        let guidance_state = &self.state[GUIDANCE..];
        let command = self.command_ned_ft();
        let velocity = out.velocity_cmd_ned_fps;
        let b_hat_ft = VelocityGuidance::b_hat_ft(guidance_state);
        Snapshot {
            t_s,
            target,
            follower_position_ned_ft: follower,
            follower_velocity_ned_fps: velocity,
            follower_attitude: attitude_along_velocity(&velocity, 0.0).unwrap_or_default(),
            relative_ned_ft: target.position_ned_ft - follower,
            command_ned_ft: command,
            excited_command_ned_ft: command + self.excitation_offset_ned_ft(t_s, b_hat_ft),
            excitation_amplitude: self.excitation.amplitude(),
            r_measured: (target.position_ned_ft - follower) / self.scenario.target.size_ft,
            b_hat_ft,
            d_hat: VelocityGuidance::d_hat(guidance_state),
            guidance: out,
        }
    }

    /// Advances one tick.
    pub fn step(&mut self) -> Result<StepOutcome, SimError> {
        if self.tick >= self.total_ticks {
            return Ok(StepOutcome::Finished);
        }
        let t_s = self.time_s();
        let dt_s = self.scenario.run.dt_s;
        let mut state = std::mem::take(&mut self.state);
        let mut rk4 = std::mem::replace(&mut self.rk4, Rk4::new(0));
        rk4.step(t_s, dt_s, &mut state, |t, x, dx| {
            self.derivative(t, x, dx);
        });
        self.rk4 = rk4;
        self.guidance.enforce_bounds(&mut state[GUIDANCE..]);
        self.state = state;
        self.tick += 1;
        let t_end_s = self.time_s();

        if let Some(i) = self.state.iter().position(|v| !v.is_finite()) {
            return Err(SimError::Diverged {
                t_s: t_end_s,
                what: format!("state element {i} is {}", self.state[i]),
            });
        }
        let follower = Vec3::new(self.state[0], self.state[1], self.state[2]);
        let relative = self.target.position_ned_ft(t_end_s) - follower;
        let range_ft = relative.norm();
        self.min_range_ft = self.min_range_ft.min(range_ft);
        if range_ft > 1e6 {
            return Err(SimError::Diverged {
                t_s: t_end_s,
                what: format!("range {range_ft:.3e} ft exceeds 1e6 ft"),
            });
        }
        let mut scratch = std::mem::take(&mut self.scratch);
        let out = self.derivative(t_end_s, &self.state, &mut scratch);
        self.scratch = scratch;
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

    /// The excitation offset in ft as the guidance sees it (scaled offsets times b̂).
    fn excitation_offset_ned_ft(&self, t_s: f64, b_hat_ft: f64) -> Vec3 {
        let (offset, _) = self.excitation.offset(t_s);
        match self.excitation.units() {
            ExcitationUnits::Ft => offset,
            ExcitationUnits::Scaled => offset * b_hat_ft,
        }
    }
}
