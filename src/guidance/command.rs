//! The user's relative-position command R_c and its derivative ((3.13)-(3.14); docs/equations.md,
//! The relative motion and the seed's scenario (3.1-3.15, 4.4)).
//!
//! Frames:
//! - `inertial`: R_c fixed in NED (the seed's simulations).
//! - `body`: range, bearing, elevation in the follower's body frame, R_c = range L_BEᵀ T_IBc,
//!   Ṙ_c = range L_BEᵀ (ω × T_IBc) (3.13)-(3.14).
//! - `target` (docs/equations.md, Beyond the seed): `command_ft` in the frame V of the target's
//!   velocity (x along it, y right, z down): R_c = L_VE(χ_c, γ_c)ᵀ R_c,V, L_VE the DCM of
//!   docs/equations.md, Frames and angles, at (0, γ_c, χ_c), its angles following the heading and
//!   flight-path angle of a velocity through a first-order lag τ,
//!   χ̇_c = wrap(χ̂ - χ_c)/τ, γ̇_c = (γ̂ - γ_c)/τ, and
//!   Ṙ_c = (∂L_VEᵀ/∂χ χ̇_c + ∂L_VEᵀ/∂γ γ̇_c) R_c,V. The velocity it follows is
//!   the simulation's choice ([`CommandInput::track_ned`]): the target's estimated velocity once
//!   the estimator knows b; before, the frame holds still (the estimate's direction is wrong while
//!   b̂ is, and a frame that followed the follower's own track would turn the command with every
//!   turn of the follower, as the body frame does). The
//!   seed's [32, 8, 0] ft puts the follower 32 ft behind and 8 ft to the left of the target,
//!   14° right of the nose of a follower flying parallel to it; unlike the body and heading
//!   frames it does not turn with the follower's own motion (an excitation included).
//! - `heading`: the same geometry in a level frame that turns with the follower's heading
//!   through a first-order lag: R_c = range R_z(ψ_c)ᵀ T_IBc, ψ̇_c = (ψ - ψ_c)/τ_c. With the
//!   body frame and a follower whose attitude follows its own velocity, the commanded point
//!   moves with every turn and pitch of the follower and the loop V_F → attitude → R_c → V_F
//!   has a gain near range/(τ V) (about 3 for 33 ft, a 0.2 s attitude lag and 50 ft/s): it
//!   spins the follower. A heading lag of a few seconds keeps the gain well below one while
//!   the target stays at the commanded bearing once the follower flies the target's heading.
//!   The level frame also keeps the target's size b identifiable: with the body frame the
//!   commanded point tilts and turns with every motion an excitation asks of the follower,
//!   against the excitation, and b̂ learns nothing from it (docs/findings.md, What the
//!   guidance and control code rests on). A vertical
//!   excitation moves the level frame not at all; with the kinematic follower's 0.25 s
//!   attitude lag a heading lag of 0.5 s is enough (`vision_ch4_formation.toml`).
//!
//! State slice: `[ψ_c or χ_c, γ_c]`: the heading frame's ψ_c, or the target frame's angles.

use crate::frames::{EulerAngles, Mat3, Vec3, wrap_angle_rad};
use crate::scenario::{CommandFrame, GuidanceSection, Mission};
use crate::sensing::line_of_sight_body;

/// Length of the command's state slice.
pub const STATE_LEN: usize = 2;

/// The names of the command's state elements (for messages).
pub const STATE_NAMES: [&str; STATE_LEN] = [
    "command frame: heading, rad",
    "command frame: flight-path angle, rad",
];

/// What the command frames follow at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CommandInput {
    /// The follower's attitude (body and heading frames).
    pub attitude: EulerAngles,
    /// The follower's body rates [p, q, r], rad/s (body frame).
    pub body_rates_rps: Vec3,
    /// The velocity whose direction the target frame follows, NED (any scale); `None` holds
    /// the frame where it is (while the target's velocity is not known well enough).
    pub track_ned: Option<Vec3>,
}

/// The formation (or interception) command.
#[derive(Debug, Clone, PartialEq)]
pub struct FormationCommand {
    mission: Mission,
    frame: CommandFrame,
    /// `command_ft`: NED (inertial frame) or target-velocity axes (target frame), ft.
    command_ft: Vec3,
    /// range T_IBc in the body or heading frame, ft.
    offset_ft: Vec3,
    heading_lag_s: f64,
    target_lag_s: f64,
}

/// R_z(ψ)ᵀ: NED from a level frame yawed by ψ, and its derivative with respect to ψ.
fn ned_from_heading(psi_rad: f64) -> (Mat3, Mat3) {
    let (s, c) = psi_rad.sin_cos();
    (
        Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
        Mat3::new(-s, -c, 0.0, c, -s, 0.0, 0.0, 0.0, 0.0),
    )
}

/// L_VE(χ, γ)ᵀ, NED from the target-velocity frame, and its derivatives with respect to χ and
/// γ (docs/equations.md, Frames and angles, with φ = 0, θ = γ, ψ = χ).
fn ned_from_velocity_frame(chi_rad: f64, gamma_rad: f64) -> (Mat3, Mat3, Mat3) {
    let (sc, cc) = chi_rad.sin_cos();
    let (sg, cg) = gamma_rad.sin_cos();
    let l = Mat3::new(cg * cc, cg * sc, -sg, -sc, cc, 0.0, sg * cc, sg * sc, cg);
    let d_chi = Mat3::new(
        -cg * sc,
        cg * cc,
        0.0,
        -cc,
        -sc,
        0.0,
        -sg * sc,
        sg * cc,
        0.0,
    );
    let d_gamma = Mat3::new(
        -sg * cc,
        -sg * sc,
        -cg,
        0.0,
        0.0,
        0.0,
        cg * cc,
        cg * sc,
        -sg,
    );
    (l.transpose(), d_chi.transpose(), d_gamma.transpose())
}

/// NED from the target frame at the command state `x`, L_VEᵀ(χ_c, γ_c).
pub fn ned_from_target_frame(x: &[f64]) -> Mat3 {
    ned_from_velocity_frame(x[0], x[1]).0
}

/// Heading and flight-path angle of a velocity, rad (None when it is zero).
fn heading_and_climb_rad(v: &Vec3) -> Option<(f64, f64)> {
    let speed = v.norm();
    (speed > 1e-9 && speed.is_finite())
        .then(|| (v.y.atan2(v.x), (-v.z / speed).clamp(-1.0, 1.0).asin()))
}

impl FormationCommand {
    /// The command a `[guidance]` section describes.
    pub fn new(section: &GuidanceSection) -> Self {
        Self {
            mission: section.mission,
            frame: section.command_frame,
            command_ft: Vec3::from(section.command_ft),
            offset_ft: line_of_sight_body(
                section.command_bearing_deg.to_radians(),
                section.command_elevation_deg.to_radians(),
            ) * section.command_range_ft,
            heading_lag_s: section.command_heading_lag_s,
            target_lag_s: section.command_target_lag_s,
        }
    }

    /// Where the slot lies from the target, ft: how far the target is ahead of it and to its
    /// right, along and across the target's track, for the S-turns. In the target's velocity
    /// frame these are R_c's own x and y (the frame's heading follows the estimate once it
    /// is trusted, through its lag); in any other frame, `command_ned_ft` (R_c, NED) along
    /// the estimated track's horizontal unit `along`.
    pub fn slot_lead_and_offset_ft(&self, command_ned_ft: &Vec3, along: &Vec3) -> (f64, f64) {
        match self.frame {
            CommandFrame::Target => (self.command_ft.x, self.command_ft.y),
            _ => (
                command_ned_ft.dot(along),
                command_ned_ft.dot(&Vec3::new(-along.y, along.x, 0.0)),
            ),
        }
    }

    /// Initial state: the heading and target frames start at the follower's heading, level.
    pub fn initial_state(follower_attitude: &EulerAngles) -> [f64; STATE_LEN] {
        [follower_attitude.psi_rad, 0.0]
    }

    /// R_c and Ṙ_c, NED (ft, ft/s), for the command state `x` and what the frames follow.
    pub fn command(&self, x: &[f64], input: &CommandInput) -> (Vec3, Vec3) {
        match (self.mission, self.frame) {
            (Mission::Intercept, _) => (Vec3::zeros(), Vec3::zeros()),
            (Mission::Formation, CommandFrame::Inertial) => (self.command_ft, Vec3::zeros()),
            (Mission::Formation, CommandFrame::Body) => {
                let ned_from_body = input.attitude.body_from_ned().transpose();
                (
                    ned_from_body * self.offset_ft,
                    ned_from_body * input.body_rates_rps.cross(&self.offset_ft),
                )
            }
            (Mission::Formation, CommandFrame::Heading) => {
                let (rotation, rotation_rate) = ned_from_heading(x[0]);
                let [psi_rate, _] = self.rates(x, input);
                (
                    rotation * self.offset_ft,
                    rotation_rate * self.offset_ft * psi_rate,
                )
            }
            (Mission::Formation, CommandFrame::Target) => {
                let (rotation, rotation_rate) = self.target_frame_turn(x, input);
                (rotation * self.command_ft, rotation_rate * self.command_ft)
            }
        }
    }

    /// The target frame at the command state `x`: NED from it, L_VEᵀ(χ_c, γ_c), and that
    /// rotation's rate, ∂L_VEᵀ/∂χ χ̇_c + ∂L_VEᵀ/∂γ γ̇_c (R_c's frame, and the excitation's with
    /// `excitation.frame = "target"`).
    pub fn target_frame_turn(&self, x: &[f64], input: &CommandInput) -> (Mat3, Mat3) {
        let (rotation, d_chi, d_gamma) = ned_from_velocity_frame(x[0], x[1]);
        let [chi_rate, gamma_rate] = self.rates(x, input);
        (rotation, d_chi * chi_rate + d_gamma * gamma_rate)
    }

    /// The angular velocity of the frame the shaping filter runs in, NED, rad/s: the target
    /// frame's, ω = χ̇_c ẑ + γ̇_c ŷ_V (ŷ_V = [-sin χ_c, cos χ_c, 0]), so that a slot approached
    /// from afar turns with the target around it; zero for the other frames (the body and
    /// heading frames turn with the follower itself, and a far commanded point swung by the
    /// follower's own turns would feed them back).
    pub fn shaping_frame_rate_rps(&self, x: &[f64], input: &CommandInput) -> Vec3 {
        match (self.mission, self.frame) {
            (Mission::Formation, CommandFrame::Target) => {
                let [chi_rate, gamma_rate] = self.rates(x, input);
                let (s, c) = x[0].sin_cos();
                Vec3::new(0.0, 0.0, chi_rate) + Vec3::new(-s, c, 0.0) * gamma_rate
            }
            _ => Vec3::zeros(),
        }
    }

    /// The state's rates: ψ̇_c = wrap(ψ - ψ_c)/τ_c (heading frame); χ̇_c and γ̇_c toward the
    /// track's heading and flight-path angle (target frame); zero otherwise.
    fn rates(&self, x: &[f64], input: &CommandInput) -> [f64; STATE_LEN] {
        match self.frame {
            CommandFrame::Heading => [
                wrap_angle_rad(input.attitude.psi_rad - x[0]) / self.heading_lag_s,
                0.0,
            ],
            CommandFrame::Target => input
                .track_ned
                .and_then(|v| heading_and_climb_rad(&v))
                .map_or([0.0; STATE_LEN], |(chi, gamma)| {
                    [
                        wrap_angle_rad(chi - x[0]) / self.target_lag_s,
                        (gamma - x[1]) / self.target_lag_s,
                    ]
                }),
            CommandFrame::Inertial | CommandFrame::Body => [0.0; STATE_LEN],
        }
    }

    /// Writes the command state's derivative.
    pub fn derivative(&self, x: &[f64], input: &CommandInput, dx: &mut [f64]) {
        dx.copy_from_slice(&self.rates(x, input));
    }

    /// Wraps the frame's heading into (-π, π] after a step.
    pub fn normalize(x: &mut [f64]) {
        x[0] = wrap_angle_rad(x[0]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(attitude: EulerAngles, body_rates_rps: Vec3) -> CommandInput {
        CommandInput {
            attitude,
            body_rates_rps,
            track_ned: Some(Vec3::new(30.0, 40.0, -5.0)),
        }
    }

    /// Ṙ_c is the time derivative of R_c along the command state's motion.
    fn assert_rate_is_derivative(cmd: &FormationCommand, x: &[f64; 2], input: &CommandInput) {
        let mut dx = [0.0; 2];
        cmd.derivative(x, input, &mut dx);
        let h = 1e-6;
        let at = |s: f64| [x[0] + s * h * dx[0], x[1] + s * h * dx[1]];
        let (before, _) = cmd.command(&at(-1.0), input);
        let (after, _) = cmd.command(&at(1.0), input);
        let (_, rate) = cmd.command(x, input);
        assert!(
            ((after - before) / (2.0 * h) - rate).norm() < 1e-6,
            "{rate}"
        );
        assert!(rate.norm() > 0.0, "the state moves in this test");
    }

    /// Target frame: a target flying north puts the seed's [32, 8, 0] ft at [32, 8, 0] in NED;
    /// flying east, at [-8, 32, 0]; climbing at γ, the slot tilts with it; and Ṙ_c is the
    /// derivative of R_c along the frame's motion.
    #[test]
    fn target_frame_follows_the_track() {
        let mut s = section(CommandFrame::Target);
        s.command_ft = [32.0, 8.0, 0.0];
        let cmd = FormationCommand::new(&s);
        let level = EulerAngles::default();
        let (north, _) = cmd.command(&[0.0, 0.0], &input(level, Vec3::zeros()));
        assert!((north - Vec3::new(32.0, 8.0, 0.0)).norm() < 1e-12);
        let east = std::f64::consts::FRAC_PI_2;
        let (r_c, _) = cmd.command(&[east, 0.0], &input(level, Vec3::zeros()));
        assert!((r_c - Vec3::new(-8.0, 32.0, 0.0)).norm() < 1e-12, "{r_c}");
        let climb = 0.1f64;
        let (r_c, _) = cmd.command(&[0.0, climb], &input(level, Vec3::zeros()));
        assert!((r_c - Vec3::new(32.0 * climb.cos(), 8.0, -32.0 * climb.sin())).norm() < 1e-12);
        let x = [0.3, -0.05];
        let input = input(level, Vec3::zeros());
        assert_rate_is_derivative(&cmd, &x, &input);
        // The frame's angular velocity turns the slot as Ṙ_c does.
        let (r_c, rate) = cmd.command(&x, &input);
        let omega = cmd.shaping_frame_rate_rps(&x, &input);
        assert!((omega.cross(&r_c) - rate).norm() < 1e-12, "{omega} {rate}");
    }

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
        let input = input(attitude, Vec3::zeros());
        let (a, _) = heading.command(&x, &input);
        let (b, _) = body.command(&x, &input);
        assert!((a - b).norm() < 1e-12);
        assert!((a.norm() - 33.0).abs() < 1e-12);
        let bearing = a.y.atan2(a.x) - 0.7;
        assert!((bearing - 14f64.to_radians()).abs() < 1e-12);
    }

    /// Ṙ_c is the time derivative of R_c along the command state's motion.
    #[test]
    fn heading_command_rate_is_derivative() {
        let cmd = FormationCommand::new(&section(CommandFrame::Heading));
        let input = input(EulerAngles::new(0.1, 0.0, 1.0), Vec3::zeros());
        assert_rate_is_derivative(&cmd, &[0.4, 0.0], &input);
    }

    /// Body frame: Ṙ_c = L_BEᵀ (ω × offset), a yaw rate moves the point sideways.
    #[test]
    fn body_command_rate_follows_rotation() {
        let cmd = FormationCommand::new(&section(CommandFrame::Body));
        let attitude = EulerAngles::default();
        let (r_c, rate) = cmd.command(&[0.0; 2], &input(attitude, Vec3::new(0.0, 0.0, 0.1)));
        assert!((rate - Vec3::new(-0.1 * r_c.y, 0.1 * r_c.x, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn interception_commands_zero() {
        let mut s = section(CommandFrame::Body);
        s.mission = Mission::Intercept;
        let cmd = FormationCommand::new(&s);
        let (r_c, rate) = cmd.command(
            &[0.0; 2],
            &input(EulerAngles::default(), Vec3::new(1.0, 1.0, 1.0)),
        );
        assert_eq!((r_c, rate), (Vec3::zeros(), Vec3::zeros()));
    }
}
