//! What the simulation reports at one instant and over a run: the snapshot of every stage
//! (for telemetry, plots and statistics), the gimbal's reading and the wall time per stage.

use crate::estimation::{FilterReading, TargetMotionEstimate};
use crate::follower::AircraftActuation;
use crate::frames::{EulerAngles, Vec3};
use crate::guidance::signals::{FollowerCommand, GuidanceOutput};
use crate::sensing::gimbal::GimbalAngles;
use crate::sensing::{FollowerPose, FrameRecord};
use crate::world::target::{TargetFlight, TargetState};
use std::time::Duration;

/// Everything about one instant, for telemetry and statistics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Snapshot {
    /// Time, s.
    pub t_s: f64,
    /// Target state.
    pub target: TargetState,
    /// The target aircraft's air data and reference (`target.model = "aircraft"`).
    pub target_flight: Option<TargetFlight>,
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
    /// Excitation amplitude a(t) w(t) within its window, in the excitation's units.
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
    /// The filter's νᵀ S⁻¹ ν of the latest measurement it fused (None before the first, or
    /// without a filter).
    pub filter_nis: Option<f64>,
    /// Guidance output.
    pub guidance: GuidanceOutput,
    /// The measurement and truth of the frame the guidance holds (camera runs).
    pub frame: Option<FrameRecord>,
    /// Whether the estimator took the held frame (camera runs, once one is held).
    pub frame_trusted: Option<bool>,
    /// The gimbal's angles and command now (gimballed cameras).
    pub gimbal: Option<GimbalReading>,
    /// The 6-DOF follower's air data, actuators and flight controller (aircraft runs).
    pub aircraft: Option<AircraftActuation>,
    /// The follower as its navigation knows itself (`navigation.mode = "ins_gps"` runs).
    pub navigation: Option<FollowerPose>,
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
    /// Whether the gimbal has a roll axis.
    pub roll_axis: bool,
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
