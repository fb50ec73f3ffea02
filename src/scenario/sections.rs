//! The scenario's sections: schema, defaults (the seed's values where it gives them) and
//! validation. Every struct rejects unknown keys.

use serde::{Deserialize, Serialize};

use super::check::{self, Check};
use super::excitation::{ExcitationMode, ExcitationSection};

/// `[run]`: time base and bookkeeping.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RunSection {
    /// Simulated duration, s.
    pub duration_s: f64,
    /// Fixed integration step, s.
    pub dt_s: f64,
    /// Seed of the run's one random-number generator.
    pub seed: u64,
    /// Ticks between telemetry rows (1 = every tick).
    pub log_every: u32,
    /// A camera run whose target has gone unmeasured for longer than this stops with status
    /// `lost`, s (0: never). Brief losses (a fixed camera's target crossing the image's edge
    /// for a few frames, a 2 s occlusion and the gimbal's search that finds the target within
    /// about 1 s after it) are survived: the guidance coasts on its estimator. 5 s leaves
    /// room above those 3 s; a target gone longer is not coming back by itself.
    pub stop_after_lost_s: f64,
    /// The seed of the air's Dryden stream where it is not the run's own `seed`: the group's
    /// `run.seed`, for a follower of a group in one air mass (`group.gusts = "shared"`). Set
    /// by the group, not a file key.
    #[serde(skip)]
    pub shared_air_seed: Option<u64>,
}

impl Default for RunSection {
    fn default() -> Self {
        Self {
            duration_s: 140.0,
            dt_s: 0.001,
            seed: 1,
            log_every: 10,
            stop_after_lost_s: 5.0,
            shared_air_seed: None,
        }
    }
}

impl RunSection {
    /// The seed of the Dryden stream the follower flies through (and a target sharing its
    /// air, `target.gusts = "shared"`): the group's in a shared air mass, else `seed`.
    pub fn air_seed(&self) -> u64 {
        self.shared_air_seed.unwrap_or(self.seed)
    }

    fn validate(&self) -> Check {
        check::in_closed("run.duration_s", self.duration_s, 1e-3, 1e5)?;
        check::in_closed("run.dt_s", self.dt_s, 1e-5, 0.1)?;
        check::require(
            self.dt_s <= self.duration_s,
            "run.dt_s",
            self.dt_s,
            format!("<= run.duration_s = {}", self.duration_s),
        )?;
        check::int_in("run.log_every", i64::from(self.log_every), 1, 1_000_000)?;
        check::in_closed("run.stop_after_lost_s", self.stop_after_lost_s, 0.0, 1e5)
    }

    /// Number of ticks of the whole run.
    pub fn total_ticks(&self) -> u64 {
        (self.duration_s / self.dt_s).round() as u64
    }
}

/// The follower's dynamics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FollowerModel {
    /// The guidance command is realised exactly (seed Chapters 4-6).
    Kinematic,
    /// The 6-DOF aircraft (`assets/aircraft/follower.toml`) flown by the Chapter 7 flight
    /// controller (`[autopilot]`) in the air of `[atmosphere]` (seed Chapter 7).
    Aircraft,
}

/// Slowest start of the 6-DOF follower, ft/s: 1.25 times its stall speed (about 28 ft/s at
/// sea level with the Aerosonde lift curve on the seed's wing).
pub const AIRCRAFT_MIN_SPEED_FPS: f64 = 35.0;
/// Fastest start of the 6-DOF follower, ft/s (trimmed with throttle and elevator inside their
/// limits; the seed flies 35-60 ft/s).
pub const AIRCRAFT_MAX_SPEED_FPS: f64 = 100.0;
/// Largest integration step with the 6-DOF follower, s: its roll mode has a time constant
/// near 10-17 ms and its servos 25 ms.
pub const AIRCRAFT_MAX_DT_S: f64 = 0.005;

/// `[follower]`: the aircraft carrying the camera.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FollowerSection {
    /// Dynamics model.
    pub model: FollowerModel,
    /// R_F(0) in NED, ft.
    pub initial_position_ft: [f64; 3],
    /// Initial roll, pitch, yaw, deg.
    pub initial_attitude_deg: [f64; 3],
    /// Kinematic follower: time constant with which the attitude turns to the velocity
    /// direction (θ → γ, ψ → χ, φ → coordinated-turn bank), s.
    pub attitude_lag_s: f64,
    /// V_F(0) in NED, ft/s, for a follower that integrates a commanded acceleration
    /// (`guidance.law = "acceleration"`); the velocity law commands V_F directly and ignores
    /// it. Default: the seed target's initial velocity. The aircraft starts trimmed in
    /// straight and level flight at this speed (air-relative) and on its course, whatever
    /// the law; its roll, pitch and yaw are then the trim's and `initial_attitude_deg` is not
    /// used.
    pub initial_velocity_fps: [f64; 3],
    /// Beyond the seed (whose aircraft has none): a speed brake on the 6-DOF follower, its
    /// drag coefficient ΔC_D at full deflection (referred to the wing area), 0 for none. The
    /// flight controller deploys it where it would command less than idle thrust, and its
    /// steepest descent then includes it. Without one the follower descends at most at its
    /// idle glide, about 7° (L/D ≈ 8) at 60 ft/s, and an updraft it cannot glide through
    /// leaves it above a descending target.
    pub speed_brake_c_drag: f64,
    /// The 6-DOF follower's aircraft data file (`follower.model = "aircraft"`): mass,
    /// geometry, aerodynamic and propulsion data in the schema of the shipped
    /// `assets/aircraft/follower.toml` (the seed's aircraft, the default). A relative path is
    /// looked up from the scenario file's folder.
    pub aircraft: String,
}

/// The default `follower.aircraft`: the seed's aircraft, shipped in `assets/` and built into
/// the program.
pub const DEFAULT_AIRCRAFT: &str = "assets/aircraft/follower.toml";

impl Default for FollowerSection {
    fn default() -> Self {
        Self {
            model: FollowerModel::Kinematic,
            initial_position_ft: [0.0; 3],
            initial_attitude_deg: [0.0; 3],
            attitude_lag_s: 0.2,
            initial_velocity_fps: [50.0, 0.0, 0.0],
            speed_brake_c_drag: 0.0,
            aircraft: DEFAULT_AIRCRAFT.to_string(),
        }
    }
}

impl FollowerSection {
    fn validate(&self) -> Check {
        check::position_ft("follower.initial_position_ft", &self.initial_position_ft)?;
        check::finite_vec("follower.initial_attitude_deg", &self.initial_attitude_deg)?;
        check::in_closed(
            "follower.initial_attitude_deg[1]",
            self.initial_attitude_deg[1],
            -89.0,
            89.0,
        )?;
        check::in_closed("follower.attitude_lag_s", self.attitude_lag_s, 1e-3, 10.0)?;
        check::finite_vec("follower.initial_velocity_fps", &self.initial_velocity_fps)?;
        check::in_closed(
            "follower.speed_brake_c_drag",
            self.speed_brake_c_drag,
            0.0,
            1.0,
        )?;
        check::require(
            !self.aircraft.is_empty(),
            "follower.aircraft",
            "\"\"".to_string(),
            "the path of an aircraft data file".to_string(),
        )?;
        if self.model == FollowerModel::Aircraft {
            let [n, e, d] = self.initial_velocity_fps;
            let speed = n.hypot(e);
            check::require(
                d == 0.0 && (AIRCRAFT_MIN_SPEED_FPS..=AIRCRAFT_MAX_SPEED_FPS).contains(&speed),
                "follower.initial_velocity_fps",
                format!("{:?}", self.initial_velocity_fps),
                format!(
                    "[n, e, 0] with a speed in [{AIRCRAFT_MIN_SPEED_FPS}, \
                     {AIRCRAFT_MAX_SPEED_FPS}] ft/s (follower.model = \"aircraft\" starts \
                     trimmed in straight and level flight)"
                ),
            )?;
        }
        Ok(())
    }
}

/// Which guidance law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GuidanceLawKind {
    /// Velocity command, (4.3)-(4.5); with `estimator`, (6.10)-(6.17).
    Velocity,
    /// Acceleration command, (5.2)-(5.41) and Remark 6; with noise, (6.39)-(6.42). Gains in
    /// `[acceleration]`.
    Acceleration,
}

/// Where the velocity law's estimator gain L_v comes from (Section 6.2.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EstimatorGainMode {
    /// L_v = `estimator_gain` I (the seed's 1.7 I).
    Fixed,
    /// L_v from the steady-state error covariance (6.33)-(6.36), with the noise intensity
    /// `estimator_noise_psd` and the disturbance intensity `estimator_process_psd` (see
    /// `guidance::velocity::steady_state_estimator_gain`).
    Covariance,
}

/// Formation (hold R_c) or interception (R_c = 0, stop inside a radius).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Mission {
    /// Keep the relative position at the command.
    Formation,
    /// Drive the relative position to zero, (4.40).
    Intercept,
}

/// Frame the formation command is given in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CommandFrame {
    /// R_c fixed in NED (the seed's simulations).
    Inertial,
    /// Range, bearing and elevation in the follower's body frame, (3.13)-(3.14).
    Body,
    /// Range, bearing and elevation in a level frame that follows the follower's heading
    /// with the lag `command_heading_lag_s` (see `guidance::command`).
    Heading,
    /// `command_ft` in the frame of the target's estimated velocity (x along it, y right, z
    /// down), which follows the estimate with the lag `command_target_lag_s`
    /// (docs/equations.md, Formation command in the target's velocity frame).
    Target,
}

/// `[guidance]`: law, mission, gains and projection bounds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GuidanceSection {
    /// Guidance law.
    pub law: GuidanceLawKind,
    /// Formation or interception.
    pub mission: Mission,
    /// Frame of the formation command.
    pub command_frame: CommandFrame,
    /// R_c, ft: in NED (inertial frame) or in the target's velocity frame (target frame).
    pub command_ft: [f64; 3],
    /// Commanded range, ft (formation, body frame).
    pub command_range_ft: f64,
    /// Commanded bearing λ_c, deg, positive right (body frame).
    pub command_bearing_deg: f64,
    /// Commanded elevation ϑ_c, deg, positive up (body frame).
    pub command_elevation_deg: f64,
    /// Heading frame: time constant with which it follows the follower's heading, s.
    pub command_heading_lag_s: f64,
    /// Target frame: time constant with which it follows the estimated target velocity's
    /// heading and flight-path angle, s.
    pub command_target_lag_s: f64,
    /// Target frame with the Kalman estimate: it follows the velocity predicted this far
    /// ahead, d̂ + â τ_lead, s (τ_lead = τ cancels the lag of a steady turn).
    pub command_target_lead_s: f64,
    /// Target frame with the Kalman estimate: it follows the estimated target velocity once
    /// the σ of its heading is below this, deg, and holds still before.
    pub command_target_heading_sigma_deg: f64,
    /// Drive the law with the Chapter 6 state estimator (6.10)-(6.17).
    pub estimator: bool,
    /// Fixed estimator gain L_v = estimator_gain I, 1/s (seed: 1.7).
    pub estimator_gain: f64,
    /// Fixed L_v, or L_v from the steady-state covariance (6.36).
    pub estimator_gain_mode: EstimatorGainMode,
    /// Covariance design: intensity q (1/s) of the disturbance δ(t) = V_T/b - d of
    /// ṙ = d + δ - V_F/b (4.1), treated as white noise, per axis.
    pub estimator_process_psd: f64,
    /// Covariance design: intensity K_nr (s, scaled units² · s) of the measurement noise n_r
    /// of r* = r + n_r (6.9), per axis; for noise of variance σ² held over T_s it is σ² T_s.
    pub estimator_noise_psd: f64,
    /// q_v of Q_v = q_v I in the Lyapunov equation (6.17) whose P_v weighs the adaptive laws
    /// (6.16): the seed leaves it free; 2k makes them weigh e as (4.5) does.
    pub estimator_lyapunov_weight: f64,
    /// Tracking gain k, (4.3).
    pub k: f64,
    /// Velocity law with the 6-DOF follower: the gain k_F on the tracking error in
    /// V_F = b̂ (k_F e + d̂ - ṙ_c), 1/s; the adaptation and the estimator keep k (compensated
    /// error, see `guidance::velocity`). The seed's k = 3.5 through the aircraft's second of
    /// velocity lag oscillates; 0.5 is stable with margin (measured: 0.8 limit-cycles).
    pub k_aircraft: f64,
    /// Beyond the seed, for the law on the Kalman estimate: the target's estimated
    /// acceleration is fed forward over this lead, V_F += b̂ â τ, s (0: none).
    pub velocity_lead_s: f64,
    /// Beyond the seed, for the law on the Kalman estimate: k_I of the integral term
    /// V_F += k_I ∫ b̂ (r̂ - r_c) dt, 1/s² (0: none, the seed's law). It removes the slot
    /// error a steady shortfall of the realised velocity leaves, e = shortfall / k_F, whatever
    /// its source (navigation's attitude error, air-data biases, the airframe model's trim):
    /// docs/equations.md, The slot error's integral.
    pub integral_gain_per_s2: f64,
    /// The integral term's bound per axis, ft/s: its integration stops on an axis whose term
    /// has reached it and whose error would grow it further (anti-windup).
    pub integral_limit_fps: f64,
    /// Adaptation gain σ of b̂, (4.5).
    pub sigma: f64,
    /// Adaptation gain G of d̂ (G = gamma_d I), (4.5).
    pub gamma_d: f64,
    /// b̂(0), ft.
    pub b0_ft: f64,
    /// Lower projection bound of b̂, ft (Ω_0 = [b_min, b_max]).
    pub b_min_ft: f64,
    /// Upper projection bound of b̂, ft.
    pub b_max_ft: f64,
    /// Projection tolerance ε_b of f_b (Appendix A), ft².
    pub b_epsilon_ft2: f64,
    /// d̂(0), 1/s.
    pub d0_per_s: [f64; 3],
    /// Projection bound of ‖d̂‖, 1/s.
    pub d_max_per_s: f64,
    /// Projection tolerance ε_d of f_d, 1/s².
    pub d_epsilon: f64,
    /// Pole of the command-shaping filter ṙ_cf = -p (r_cf - r̂_c), rad/s; 0 turns it off.
    pub shaping_pole_rps: f64,
    /// The fastest the shaping filter may move the commanded point toward the slot, ft/s
    /// (b̂ ‖p (R_c/b̂ - r_cf)‖); 0: no limit (the seed's filter).
    pub approach_speed_max_fps: f64,
    /// Interception is declared when ‖R‖ falls below this, ft.
    pub intercept_radius_ft: f64,
}

impl Default for GuidanceSection {
    fn default() -> Self {
        Self {
            law: GuidanceLawKind::Velocity,
            mission: Mission::Formation,
            command_frame: CommandFrame::Inertial,
            command_ft: [32.0, 8.0, 0.0],
            command_range_ft: 33.0,
            command_bearing_deg: 14.0,
            command_elevation_deg: 0.0,
            command_heading_lag_s: 3.0,
            command_target_lag_s: 2.0,
            command_target_lead_s: 0.0,
            command_target_heading_sigma_deg: 5.0,
            estimator: false,
            estimator_gain: 1.7,
            estimator_gain_mode: EstimatorGainMode::Fixed,
            estimator_process_psd: 0.01,
            estimator_noise_psd: 1.8e-5,
            estimator_lyapunov_weight: 1.0,
            k: 3.5,
            k_aircraft: 0.5,
            velocity_lead_s: 0.0,
            integral_gain_per_s2: 0.0,
            integral_limit_fps: 5.0,
            sigma: 39.0,
            gamma_d: 40.0,
            b0_ft: 4.0,
            b_min_ft: 1.0,
            b_max_ft: 30.0,
            b_epsilon_ft2: 1.0,
            d0_per_s: [12.5, 0.0, 0.0],
            d_max_per_s: 20.0,
            d_epsilon: 1.0,
            shaping_pole_rps: 0.1,
            approach_speed_max_fps: 0.0,
            intercept_radius_ft: 2.4,
        }
    }
}

impl GuidanceSection {
    /// The length of the formation command, ft: ‖R_c‖ for the inertial frame, the commanded
    /// range otherwise.
    pub fn command_length_ft(&self) -> f64 {
        match self.command_frame {
            CommandFrame::Inertial | CommandFrame::Target => {
                crate::frames::Vec3::from(self.command_ft).norm()
            }
            _ => self.command_range_ft,
        }
    }

    fn validate(&self) -> Check {
        self.validate_command()?;
        self.validate_estimator()?;
        self.validate_adaptation()?;
        check::in_closed(
            "guidance.shaping_pole_rps",
            self.shaping_pole_rps,
            0.0,
            100.0,
        )?;
        check::in_closed("guidance.velocity_lead_s", self.velocity_lead_s, 0.0, 100.0)?;
        check::in_closed(
            "guidance.integral_gain_per_s2",
            self.integral_gain_per_s2,
            0.0,
            10.0,
        )?;
        check::in_closed(
            "guidance.integral_limit_fps",
            self.integral_limit_fps,
            0.0,
            1e3,
        )?;
        check::in_closed(
            "guidance.approach_speed_max_fps",
            self.approach_speed_max_fps,
            0.0,
            1e4,
        )?;
        check::positive("guidance.intercept_radius_ft", self.intercept_radius_ft)
    }

    /// The formation command and its frames.
    fn validate_command(&self) -> Check {
        check::position_ft("guidance.command_ft", &self.command_ft)?;
        check::in_closed("guidance.command_range_ft", self.command_range_ft, 0.0, 1e5)?;
        check::in_closed(
            "guidance.command_bearing_deg",
            self.command_bearing_deg,
            -180.0,
            180.0,
        )?;
        check::in_closed(
            "guidance.command_elevation_deg",
            self.command_elevation_deg,
            -89.0,
            89.0,
        )?;
        check::in_closed(
            "guidance.command_heading_lag_s",
            self.command_heading_lag_s,
            0.01,
            1000.0,
        )?;
        check::in_closed(
            "guidance.command_target_lag_s",
            self.command_target_lag_s,
            0.01,
            1000.0,
        )?;
        check::in_closed(
            "guidance.command_target_lead_s",
            self.command_target_lead_s,
            0.0,
            1000.0,
        )?;
        check::in_closed(
            "guidance.command_target_heading_sigma_deg",
            self.command_target_heading_sigma_deg,
            0.0,
            180.0,
        )
    }

    /// The Chapter 6 estimator's design.
    fn validate_estimator(&self) -> Check {
        check::positive("guidance.estimator_gain", self.estimator_gain)?;
        check::positive("guidance.estimator_process_psd", self.estimator_process_psd)?;
        check::positive("guidance.estimator_noise_psd", self.estimator_noise_psd)?;
        check::positive(
            "guidance.estimator_lyapunov_weight",
            self.estimator_lyapunov_weight,
        )
    }

    /// Gains, projection bounds and initial estimates of the adaptive laws.
    fn validate_adaptation(&self) -> Check {
        check::positive("guidance.k", self.k)?;
        check::in_closed("guidance.k_aircraft", self.k_aircraft, 1e-3, 100.0)?;
        check::non_negative("guidance.sigma", self.sigma)?;
        check::non_negative("guidance.gamma_d", self.gamma_d)?;
        check::positive("guidance.b_min_ft", self.b_min_ft)?;
        check::require(
            self.b_max_ft.is_finite() && self.b_max_ft > self.b_min_ft,
            "guidance.b_max_ft",
            self.b_max_ft,
            format!("a finite number > guidance.b_min_ft = {}", self.b_min_ft),
        )?;
        check::in_open(
            "guidance.b0_ft",
            self.b0_ft,
            self.b_min_ft,
            self.b_max_ft,
            &format!(
                "(guidance.b_min_ft = {}, guidance.b_max_ft = {}), exclusive",
                self.b_min_ft, self.b_max_ft
            ),
        )?;
        check::positive("guidance.b_epsilon_ft2", self.b_epsilon_ft2)?;
        check::finite_vec("guidance.d0_per_s", &self.d0_per_s)?;
        check::positive("guidance.d_max_per_s", self.d_max_per_s)?;
        let d0_norm = self.d0_per_s.iter().map(|x| x * x).sum::<f64>().sqrt();
        check::require(
            d0_norm <= self.d_max_per_s,
            "guidance.d0_per_s",
            format!("{:?} (norm {d0_norm})", self.d0_per_s),
            format!("norm <= guidance.d_max_per_s = {}", self.d_max_per_s),
        )?;
        check::positive("guidance.d_epsilon", self.d_epsilon)
    }
}

/// `[output]`: what a run writes besides telemetry and summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSection {
    /// Draw the seed's figure panels into `plots/`.
    pub plots: bool,
    /// Save every N-th camera frame to `frames/NNNNNN.png` (0: none): the whole image, drawn
    /// again after the frame was measured, so saving changes no measurement.
    pub frames_every: u32,
    /// Draw the measurement (centroid cross, maximal-length segment, status) on saved frames.
    pub overlay: bool,
}

impl Default for OutputSection {
    fn default() -> Self {
        Self {
            plots: true,
            frames_every: 0,
            overlay: true,
        }
    }
}

/// A whole scenario: one section per stage of the loop (docs/design.md, Scenarios).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct Scenario {
    /// Time base.
    pub run: RunSection,
    /// Target.
    pub target: super::TargetSection,
    /// Follower.
    pub follower: FollowerSection,
    /// Sensor.
    pub sensor: super::SensorSection,
    /// Guidance.
    pub guidance: GuidanceSection,
    /// Acceleration guidance gains (`guidance.law = "acceleration"`).
    pub acceleration: super::AccelerationSection,
    /// What infers range and size between sensing and guidance.
    pub estimator: super::EstimatorSection,
    /// Excitation.
    pub excitation: ExcitationSection,
    /// Camera (sensor `camera`).
    pub camera: super::CameraSection,
    /// The world behind the target (sensor `camera`).
    pub scene: super::SceneSection,
    /// The air the 6-DOF follower flies in (`follower.model = "aircraft"`).
    pub atmosphere: super::AtmosphereConfig,
    /// The 6-DOF follower's flight controller (`follower.model = "aircraft"`).
    pub autopilot: super::AutopilotSection,
    /// What the follower knows of its own state: navigation, air data, camera geometry.
    pub navigation: super::NavigationSection,
    /// Outputs.
    pub output: OutputSection,
}

impl Scenario {
    /// Whether the run commands a nonzero relative position (a formation with R_c ≠ 0).
    pub fn has_formation_command(&self) -> bool {
        let g = &self.guidance;
        g.mission == Mission::Formation
            && match g.command_frame {
                CommandFrame::Inertial | CommandFrame::Target => {
                    g.command_ft.iter().any(|v| *v != 0.0)
                }
                CommandFrame::Body | CommandFrame::Heading => g.command_range_ft > 0.0,
            }
    }

    /// A leader's swing the filter models at the follower's own excitation period would take
    /// the image's answer to the follower's own swing for the leader's (docs/equations.md,
    /// The leader's swing in its model).
    fn validate_leader_swing(&self) -> Check {
        let swing_s = self.estimator.leader_swing_period_s;
        check::require(
            swing_s == 0.0
                || self.excitation.mode == ExcitationMode::Off
                || swing_s != self.excitation.period_s,
            "estimator.leader_swing_period_s",
            swing_s,
            "another period than excitation.period_s (the follower's own swing)",
        )
    }

    /// The size from the excitation needs the Kalman filter (it takes the size), a camera
    /// (the instrument samples its frames) and an excitation.
    fn validate_size_from(&self) -> Check {
        check::require(
            self.estimator.size_from == super::SizeFrom::Filter
                || (self.estimator.kind == super::EstimatorKind::Kalman
                    && self.excitation.mode != ExcitationMode::Off
                    && self.sensor.mode == super::SensorMode::Camera),
            "estimator.size_from",
            "\"excitation\"",
            "\"filter\" without estimator.kind = \"kalman\", a camera and an excitation",
        )
    }

    /// Checks every value and every cross-key condition.
    pub fn validate(&self) -> Check {
        self.run.validate()?;
        self.target.validate()?;
        self.follower.validate()?;
        self.guidance.validate()?;
        self.acceleration.validate()?;
        self.estimator.validate()?;
        check::require(
            self.estimator.kind == super::EstimatorKind::Adaptive
                || self.guidance.law == GuidanceLawKind::Velocity,
            "estimator.kind",
            "\"kalman\"",
            "\"adaptive\" with guidance.law = \"acceleration\" (the Kalman filter feeds the \
             velocity law)",
        )?;
        self.excitation.validate(self.guidance.command_frame)?;
        self.validate_leader_swing()?;
        self.validate_size_from()?;
        check::require(
            !self.excitation.mode.follows_the_filter()
                || self.estimator.kind == super::EstimatorKind::Kalman
                || self.estimator.log_kalman,
            "excitation.mode",
            toml::Value::try_from(self.excitation.mode).map_or(String::new(), |v| v.to_string()),
            "another mode unless estimator.kind = \"kalman\" or estimator.log_kalman = true \
             (the amplitude follows the Kalman filter's σ_b)",
        )?;
        self.sensor
            .validate(self.run.dt_s, self.has_formation_command())?;
        self.camera.validate()?;
        self.scene.validate()?;
        if self.sensor.mode == super::SensorMode::Camera {
            self.camera.validate_rate(self.run.dt_s)?;
        }
        self.atmosphere.validate()?;
        self.autopilot.validate()?;
        if self.target.model == super::TargetModelKind::Aircraft {
            // As the follower's below: trimmed level through the air, and its fast modes.
            check::require(
                self.atmosphere.wind_ned_fps[2] == 0.0,
                "atmosphere.wind_ned_fps",
                format!("{:?}", self.atmosphere.wind_ned_fps),
                "[n, e, 0] with target.model = \"aircraft\" (no level trim in rising air)",
            )?;
            check::require(
                self.run.dt_s <= AIRCRAFT_MAX_DT_S,
                "run.dt_s",
                self.run.dt_s,
                format!("<= {AIRCRAFT_MAX_DT_S} s with target.model = \"aircraft\""),
            )?;
        }
        self.navigation.validate()?;
        if self.follower.model == FollowerModel::Aircraft {
            // The aircraft starts trimmed in straight and level flight through the air: an
            // air mass that rises or sinks has no such trim.
            check::require(
                self.atmosphere.wind_ned_fps[2] == 0.0,
                "atmosphere.wind_ned_fps",
                format!("{:?}", self.atmosphere.wind_ned_fps),
                "[n, e, 0] with follower.model = \"aircraft\" (no level trim in rising air)",
            )?;
            check::require(
                self.run.dt_s <= AIRCRAFT_MAX_DT_S,
                "run.dt_s",
                self.run.dt_s,
                format!(
                    "<= {AIRCRAFT_MAX_DT_S} s with follower.model = \"aircraft\" (its roll \
                     mode and servos are 10-25 ms fast)"
                ),
            )?;
        }
        Ok(())
    }
}
