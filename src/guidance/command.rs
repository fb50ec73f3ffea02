//! The user's relative-position command R_c and its derivative (SPEC §2, (3.13)-(3.14)).
//!
//! Frames:
//! - `inertial`: R_c fixed in NED (the seed's simulations).
//! - `body`: range, bearing, elevation in the follower's body frame, R_c = range L_BEᵀ T_IBc,
//!   Ṙ_c = range L_BEᵀ (ω × T_IBc) (3.13)-(3.14).
//! - `heading`: the same geometry in a level frame that turns with the follower's heading
//!   through a first-order lag: R_c = range R_z(ψ_c)ᵀ T_IBc, ψ̇_c = (ψ - ψ_c)/τ_c. With the
//!   body frame and a follower whose attitude follows its own velocity, the commanded point
//!   moves with every turn and pitch of the follower and the loop V_F → attitude → R_c → V_F
//!   has a gain near range/(τ V) (about 3 for 33 ft, a 0.2 s attitude lag and 50 ft/s): it
//!   spins the follower. A heading lag of a few seconds keeps the gain well below one while
//!   the target stays at the commanded bearing once the follower flies the target's heading.
//!   The level frame also keeps the target's size b identifiable: with the body frame the
//!   commanded point tilts and turns with every motion an excitation asks of the follower,
//!   against the excitation, and b̂ learns nothing from it (measured with perfect
//!   measurements: b̂ 4.3 ft against 8.17 ft with the inertial command; a vertical excitation
//!   with the heading frame gives 8.43 ft; `tests/vision_ch4_formation.rs`). A vertical
//!   excitation moves the level frame not at all; with the kinematic follower's 0.25 s
//!   attitude lag a heading lag of 0.5 s is enough (`vision_ch4_formation.toml`).
//!
//! State slice: `[ψ_c]` (used by the heading frame only).

use crate::frames::{EulerAngles, Mat3, Vec3, wrap_angle_rad};
use crate::scenario::{CommandFrame, GuidanceSection, Mission};
use crate::sensing::line_of_sight_body;

/// Length of the command's state slice.
pub const STATE_LEN: usize = 1;

/// The formation (or interception) command.
#[derive(Debug, Clone, PartialEq)]
pub struct FormationCommand {
    mission: Mission,
    frame: CommandFrame,
    inertial_ned_ft: Vec3,
    /// range T_IBc in the command frame, ft.
    offset_ft: Vec3,
    heading_lag_s: f64,
}

/// R_z(ψ)ᵀ: NED from a level frame yawed by ψ, and its derivative with respect to ψ.
fn ned_from_heading(psi_rad: f64) -> (Mat3, Mat3) {
    let (s, c) = psi_rad.sin_cos();
    (
        Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
        Mat3::new(-s, -c, 0.0, c, -s, 0.0, 0.0, 0.0, 0.0),
    )
}

impl FormationCommand {
    /// The command a `[guidance]` section describes.
    pub fn new(section: &GuidanceSection) -> Self {
        Self {
            mission: section.mission,
            frame: section.command_frame,
            inertial_ned_ft: Vec3::from(section.command_ft),
            offset_ft: line_of_sight_body(
                section.command_bearing_deg.to_radians(),
                section.command_elevation_deg.to_radians(),
            ) * section.command_range_ft,
            heading_lag_s: section.command_heading_lag_s,
        }
    }

    /// Initial state: the command frame starts at the follower's heading.
    pub fn initial_state(follower_attitude: &EulerAngles) -> [f64; STATE_LEN] {
        [follower_attitude.psi_rad]
    }

    /// R_c and Ṙ_c, NED (ft, ft/s), for the command state `x`, the follower's attitude and
    /// its body rates ω (rad/s).
    pub fn command(&self, x: &[f64], attitude: &EulerAngles, body_rates: &Vec3) -> (Vec3, Vec3) {
        match (self.mission, self.frame) {
            (Mission::Intercept, _) => (Vec3::zeros(), Vec3::zeros()),
            (Mission::Formation, CommandFrame::Inertial) => (self.inertial_ned_ft, Vec3::zeros()),
            (Mission::Formation, CommandFrame::Body) => {
                let ned_from_body = attitude.body_from_ned().transpose();
                (
                    ned_from_body * self.offset_ft,
                    ned_from_body * body_rates.cross(&self.offset_ft),
                )
            }
            (Mission::Formation, CommandFrame::Heading) => {
                let (rotation, rotation_rate) = ned_from_heading(x[0]);
                let psi_rate = self.heading_rate(x, attitude);
                (
                    rotation * self.offset_ft,
                    rotation_rate * self.offset_ft * psi_rate,
                )
            }
        }
    }

    /// ψ̇_c = wrap(ψ - ψ_c)/τ_c.
    fn heading_rate(&self, x: &[f64], attitude: &EulerAngles) -> f64 {
        wrap_angle_rad(attitude.psi_rad - x[0]) / self.heading_lag_s
    }

    /// Writes the command state's derivative.
    pub fn derivative(&self, x: &[f64], attitude: &EulerAngles, dx: &mut [f64]) {
        dx[0] = self.heading_rate(x, attitude);
    }

    /// Wraps ψ_c into (-π, π] after a step.
    pub fn normalize(x: &mut [f64]) {
        x[0] = wrap_angle_rad(x[0]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn section(frame: CommandFrame) -> GuidanceSection {
        GuidanceSection {
            command_frame: frame,
            ..GuidanceSection::default()
        }
    }

    /// At the follower's heading, the heading and body frames put the target at the
    /// commanded bearing: 33 ft at 14° right of the nose.
    #[test]
    fn heading_frame_matches_body_frame_when_level() {
        let attitude = EulerAngles::new(0.0, 0.0, 0.7);
        let heading = FormationCommand::new(&section(CommandFrame::Heading));
        let body = FormationCommand::new(&section(CommandFrame::Body));
        let x = FormationCommand::initial_state(&attitude);
        let (a, _) = heading.command(&x, &attitude, &Vec3::zeros());
        let (b, _) = body.command(&x, &attitude, &Vec3::zeros());
        assert!((a - b).norm() < 1e-12);
        assert!((a.norm() - 33.0).abs() < 1e-12);
        let bearing = a.y.atan2(a.x) - 0.7;
        assert!((bearing - 14f64.to_radians()).abs() < 1e-12);
    }

    /// Ṙ_c is the time derivative of R_c along the command state's motion.
    #[test]
    fn heading_command_rate_is_derivative() {
        let cmd = FormationCommand::new(&section(CommandFrame::Heading));
        let attitude = EulerAngles::new(0.1, 0.0, 1.0);
        let x = [0.4];
        let mut dx = [0.0];
        cmd.derivative(&x, &attitude, &mut dx);
        let h = 1e-6;
        let (before, _) = cmd.command(&[x[0] - h * dx[0]], &attitude, &Vec3::zeros());
        let (after, _) = cmd.command(&[x[0] + h * dx[0]], &attitude, &Vec3::zeros());
        let (_, rate) = cmd.command(&x, &attitude, &Vec3::zeros());
        assert!(((after - before) / (2.0 * h) - rate).norm() < 1e-6);
    }

    /// Body frame: Ṙ_c = L_BEᵀ (ω × offset), a yaw rate moves the point sideways.
    #[test]
    fn body_command_rate_follows_rotation() {
        let cmd = FormationCommand::new(&section(CommandFrame::Body));
        let attitude = EulerAngles::default();
        let (r_c, rate) = cmd.command(&[0.0], &attitude, &Vec3::new(0.0, 0.0, 0.1));
        assert!((rate - Vec3::new(-0.1 * r_c.y, 0.1 * r_c.x, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn interception_commands_zero() {
        let mut s = section(CommandFrame::Body);
        s.mission = Mission::Intercept;
        let cmd = FormationCommand::new(&s);
        let (r_c, rate) = cmd.command(&[0.0], &EulerAngles::default(), &Vec3::new(1.0, 1.0, 1.0));
        assert_eq!((r_c, rate), (Vec3::zeros(), Vec3::zeros()));
    }
}
