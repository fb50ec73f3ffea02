//! What flows into the guidance stage and out of it: the measurement, the user's command and
//! the excitation in; the follower's command and the signals telemetry and the excitation read
//! out.

use crate::estimation::TargetEstimate;
use crate::frames::{Mat3, Vec3};

/// What a guidance law commands the follower with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FollowerCommand {
    /// Inertial velocity V_F, NED, ft/s (the velocity law, (4.3)).
    Velocity(Vec3),
    /// Inertial acceleration a_F, NED, ft/s² (the acceleration law, (5.38)).
    Acceleration(Vec3),
}

impl FollowerCommand {
    /// Which kind of command this is.
    pub fn kind(&self) -> CommandKind {
        match self {
            Self::Velocity(_) => CommandKind::Velocity,
            Self::Acceleration(_) => CommandKind::Acceleration,
        }
    }
}

/// The kind of command a law gives the follower (decided by `[guidance] law`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CommandKind {
    /// V_F, ft/s.
    Velocity,
    /// a_F, ft/s².
    Acceleration,
}

/// What the follower's own navigation tells the guidance about how it flies its command, for a
/// follower that does not realise the command exactly (the 6-DOF aircraft, see
/// [`super::compensation`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FollowerFeedback {
    /// The follower's inertial velocity V_a, NED, ft/s.
    pub realised_velocity_ned_fps: Vec3,
    /// V_F - V_a for a follower that integrates V_F = V_F(0) + ∫ a_F and flies it (the
    /// acceleration law), NED, ft/s; zero under the velocity law.
    pub velocity_shortfall_ned_fps: Vec3,
}

/// What a guidance law needs at one instant besides its own state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuidanceInput {
    /// Measured scaled relative position r (or r*), NED; `None` while the target is lost: the
    /// velocity law coasts on its estimate or its command and stops adapting, the
    /// acceleration law coasts on its observer's prediction C ẑ.
    pub r_measured: Option<Vec3>,
    /// R_c, the user's relative-position command, NED, ft (zero for interception).
    pub command_ned_ft: Vec3,
    /// Ṙ_c, ft/s.
    pub command_rate_ned_fps: Vec3,
    /// The angular velocity of the frame the command is shaped in (the target frame's; zero
    /// otherwise), NED, rad/s.
    pub command_frame_rate_rps: Vec3,
    /// The excitation added to the command after the shaping filter (4.31).
    pub excitation: ExcitationOffset,
    /// How the follower flies the command (6-DOF follower); `None` for the kinematic
    /// follower, which realises it exactly.
    pub follower: Option<FollowerFeedback>,
    /// The Kalman estimator's estimate, for the law that flies on it; `None` otherwise and
    /// before the filter starts.
    pub estimate: Option<TargetEstimate>,
}

#[cfg(test)]
impl GuidanceInput {
    /// A test input: measurement `r` and command `command_ned_ft`, nothing moving, no
    /// excitation, a follower that flies its command.
    pub(crate) fn steady(r: Vec3, command_ned_ft: Vec3) -> Self {
        Self {
            r_measured: Some(r),
            command_ned_ft,
            command_rate_ned_fps: Vec3::zeros(),
            command_frame_rate_rps: Vec3::zeros(),
            excitation: ExcitationOffset::default(),
            follower: None,
            estimate: None,
        }
    }
}

/// The excitation offset a sin(ωt) E and its rate as the laws add them to the command after the
/// shaping filter: given in ft (the law divides by b̂, (4.14)) or in scaled units (added as
/// they are), per `excitation.units`; the other pair is zero.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ExcitationOffset {
    /// Offset in ft, NED.
    pub ned_ft: Vec3,
    /// Its rate, ft/s.
    pub rate_ned_fps: Vec3,
    /// Offset in scaled units, NED.
    pub scaled: Vec3,
    /// Its rate, 1/s.
    pub scaled_rate_per_s: Vec3,
}

impl ExcitationOffset {
    /// The offset turned into NED from a frame: `rotation` (NED from the frame) and its rate
    /// (the rate gains the frame's turn, Ṙ o).
    pub fn turned(&self, rotation: &Mat3, rotation_rate: &Mat3) -> Self {
        Self {
            ned_ft: rotation * self.ned_ft,
            rate_ned_fps: rotation * self.rate_ned_fps + rotation_rate * self.ned_ft,
            scaled: rotation * self.scaled,
            scaled_rate_per_s: rotation * self.scaled_rate_per_s + rotation_rate * self.scaled,
        }
    }

    /// The offset in ft for the size estimate b̂ (scaled offsets times b̂).
    pub fn in_ft(&self, b_hat_ft: f64) -> Vec3 {
        self.ned_ft + self.scaled * b_hat_ft
    }
}

/// The errors whose energy sets the intelligent excitation's amplitude (4.31), (5.27).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ExcitationErrors {
    /// From the measurement (`excitation.error = "measured"`): e = r* - r_c (velocity law,
    /// (4.31)); the combined output y*_a = 2y* - y_m - C ẑ (acceleration law: (5.27)
    /// integrates ‖ξ_a‖², of which y_a is the measurable part; the error y - y_c would keep
    /// the amplitude up through the reference model's lag alone).
    pub measured: Vec3,
    /// From the law's filtered states (`excitation.error = "estimated"`): r̂ - r_c (velocity
    /// law with the estimator (6.10)); C (ẑ - z_m), the observer's estimate of the output
    /// tracking error C e (acceleration law). Without measurement noise both tend to zero with
    /// ξ; with noise they stay near the estimator's residual noise instead of the sensor's.
    pub estimated: Vec3,
}

/// A law's output at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuidanceOutput {
    /// The command for the follower: V_F (4.3) or a_F (5.38).
    pub command: FollowerCommand,
    /// The scaled command the law tracks (shaped, excitation included): r_c or y_c.
    pub r_command: Vec3,
    /// What drives the excitation's amplitude.
    pub excitation_errors: ExcitationErrors,
    /// The acceleration law's internal signals (y_m, C ẑ, y_a, w_f, …).
    pub acceleration: Option<AccelerationGuidanceOutput>,
}

/// The acceleration law's output at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AccelerationGuidanceOutput {
    /// Commanded follower acceleration a_F (5.38), NED, ft/s².
    pub accel_cmd_ned_fps2: Vec3,
    /// The scaled command y_c the law tracks (shaped, excitation included).
    pub y_command: Vec3,
    /// ẏ_c, including -b̂' y_c,ft / b̂², 1/s.
    pub y_command_rate: Vec3,
    /// Reference-model output y_m = C z_m.
    pub y_model: Vec3,
    /// Observer output C ẑ.
    pub y_observer: Vec3,
    /// Combined measurable output y_a = 2y - y_m - C ẑ (docs/equations.md, Acceleration
    /// guidance (Chapter 5)).
    pub y_combined: Vec3,
    /// Virtual control w_f = b̂ h - S_f d̂ (5.36), ft/s.
    pub virtual_control_fps: Vec3,
    /// Its exact derivative ẇ_f, ft/s².
    pub virtual_control_rate_fps2: Vec3,
    /// Tracking error of the measurement y - y_c (what the excitation amplitude integrates).
    pub error: Vec3,
    /// b̂', ft/s.
    pub b_hat_rate_fps: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An offset turned into NED by a frame yawing at χ̇: the frame's turn adds χ̇ ẑ × o to
    /// its rate (a swing across the track of a target turning east stays across it).
    #[test]
    fn a_turned_offset_gains_the_frame_turn() {
        let (chi, chi_rate) = (0.5_f64, 0.1);
        let (s, c) = chi.sin_cos();
        let rotation = Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
        let rotation_rate = Mat3::new(-s, -c, 0.0, c, -s, 0.0, 0.0, 0.0, 0.0) * chi_rate;
        let offset = ExcitationOffset {
            ned_ft: Vec3::new(0.0, 2.0, 0.0),
            rate_ned_fps: Vec3::new(0.0, 1.0, 0.0),
            ..ExcitationOffset::default()
        };
        let turned = offset.turned(&rotation, &rotation_rate);
        assert!((turned.ned_ft - Vec3::new(-2.0 * s, 2.0 * c, 0.0)).norm() < 1e-12);
        let spin = Vec3::new(0.0, 0.0, chi_rate).cross(&turned.ned_ft);
        let expected_rate = rotation * offset.rate_ned_fps + spin;
        assert!((turned.rate_ned_fps - expected_rate).norm() < 1e-12);
        assert_eq!(turned.scaled, Vec3::zeros());
    }
}
