//! The scaled command both laws track: the user's command R_c in scaled units r̂_c = R_c / b̂
//! (4.14), smoothed by the Chapter 4 shaping filter, with the excitation added after the filter
//! (4.31), and its rate (4.15).
//!
//! Shaping filter (docs/equations.md, Velocity guidance (Chapter 4)):
//! ṙ_cf = -p (r_cf - R_c/b̂) + Ṙ_c/b̂, started at the first measurement r(0). For the seed's
//! constant inertial R_c this is the seed's filter. In the target frame, which turns at ω with
//! the target (not with the follower), the filter runs in that frame:
//! ṙ_cf = ω × r_cf - p (r_cf - R_c/b̂) + (Ṙ_c - ω × R_c)/b̂, so that a slot still being
//! approached from afar turns with the target around it (in NED the follower would fly the
//! target's new heading while the point it closes on stayed on the old side, and the
//! target would leave the camera's view in the first turn). A command
//! that turns (body, heading frames) has Ṙ_c ≠ 0, and the feed-forward Ṙ_c/b̂ lets r_cf turn
//! with it instead of lagging every turn by 1/p (10 s at the seed's pole). (Shaping R_c/b̂ by
//! an offset that decays instead would put the term -b̂' R_c/b̂² of (4.15) into the velocity
//! law's g, and with σ = 39 the loop b̂' → g → b̂' is singular once eᵀR_c reaches b̂²/σ, an
//! error of about 0.01.) With the pole at 0 there is no filter and r_c = R_c / b̂ directly.
//!
//! The command r_c = base + extra / b̂ has a part that does not depend on b̂ (the filter state
//! and scaled excitation) and one given in ft; its rate ṙ_c = base' + extra'/b̂ - b̂' extra/b̂²
//! needs b̂', which the laws compute from r_c itself, so [`ShapedCommand::rate`] takes it.

use super::signals::GuidanceInput;
use crate::frames::Vec3;
use crate::scenario::GuidanceSection;

/// The shaping filter of a law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CommandShaping {
    /// Pole p of the filter, rad/s; 0 turns it off.
    pub pole_rps: f64,
    /// The fastest the filter's own term may move the commanded point, b̂ ‖p (R_c/b̂ - r_cf)‖,
    /// ft/s (the follower cannot slow down as fast as it speeds up: a slot approached too fast
    /// is overshot); `None` leaves the seed's filter as it is.
    pub approach_speed_max_fps: Option<f64>,
}

/// The scaled command at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapedCommand {
    /// r_c = base + extra / b̂.
    pub value: Vec3,
    /// ṙ_cf, the filter state's derivative (zero without the filter).
    pub filter_rate: Vec3,
    b_hat_ft: f64,
    base_rate: Vec3,
    extra_ft: Vec3,
    extra_rate_fps: Vec3,
}

impl ShapedCommand {
    /// ṙ_c for the size estimate's rate b̂' (4.15).
    pub fn rate(&self, b_hat_rate_fps: f64) -> Vec3 {
        let b = self.b_hat_ft;
        self.base_rate + self.extra_rate_fps / b - self.extra_ft * (b_hat_rate_fps / (b * b))
    }
}

impl CommandShaping {
    /// The filter a `[guidance]` section describes.
    pub fn of(section: &GuidanceSection) -> Self {
        Self {
            pole_rps: section.shaping_pole_rps,
            approach_speed_max_fps: (section.approach_speed_max_fps > 0.0)
                .then_some(section.approach_speed_max_fps),
        }
    }

    /// p (R_c/b̂ - r_cf), limited to [`Self::approach_speed_max_fps`] / b_upper: the speed in
    /// ft is b ‖ṙ_cf‖, and with the Kalman estimate the limit holds for any b up to
    /// b_upper = b̂ + 3σ_b (a slot approached while b is still unknown is approached slowly,
    /// not at twice the speed a b̂ half the truth would allow).
    fn approach_rate(&self, filter: &Vec3, b_hat_ft: f64, input: &GuidanceInput) -> Vec3 {
        let rate = (input.command_ned_ft / b_hat_ft - filter) * self.pole_rps;
        let b_upper_ft = input
            .estimate
            .map_or(b_hat_ft, |e| e.b_hat_ft + 3.0 * e.b_sigma_ft);
        match self.approach_speed_max_fps {
            Some(max_fps) if rate.norm() * b_upper_ft > max_fps => {
                rate * (max_fps / (rate.norm() * b_upper_ft))
            }
            _ => rate,
        }
    }

    /// The command for the filter state r_cf, the size estimate b̂ and the law's input.
    pub fn command(&self, filter: &Vec3, b_hat_ft: f64, input: &GuidanceInput) -> ShapedCommand {
        let excitation = &input.excitation;
        let (base, base_rate, extra_ft, extra_rate_fps, filter_rate) = if self.pole_rps > 0.0 {
            let omega = input.command_frame_rate_rps;
            let frame_rate = input.command_rate_ned_fps - omega.cross(&input.command_ned_ft);
            let filter_rate = omega.cross(filter)
                + self.approach_rate(filter, b_hat_ft, input)
                + frame_rate / b_hat_ft;
            (
                filter + excitation.scaled,
                filter_rate + excitation.scaled_rate_per_s,
                excitation.ned_ft,
                excitation.rate_ned_fps,
                filter_rate,
            )
        } else {
            (
                excitation.scaled,
                excitation.scaled_rate_per_s,
                input.command_ned_ft + excitation.ned_ft,
                input.command_rate_ned_fps + excitation.rate_ned_fps,
                Vec3::zeros(),
            )
        };
        ShapedCommand {
            value: base + extra_ft / b_hat_ft,
            filter_rate,
            b_hat_ft,
            base_rate,
            extra_ft,
            extra_rate_fps,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A command that turns at a steady rate: with the feed-forward the filter, started on the
    /// command, stays on it (to the integrator's error), where a filter without it would lag
    /// by Ṙ_c / (p b̂) (here 10 s of turn, more than the whole offset).
    #[test]
    fn filter_follows_a_turning_command() {
        let shaping = CommandShaping {
            pole_rps: 0.1,
            approach_speed_max_fps: None,
        };
        let b_hat = 8.0;
        let (range_ft, turn_rps) = (33.0, 0.2);
        let command_at = |t: f64| {
            let (s, c) = (turn_rps * t).sin_cos();
            (
                Vec3::new(c, s, 0.0) * range_ft,
                Vec3::new(-s, c, 0.0) * range_ft * turn_rps,
            )
        };
        let input_at = |t: f64| {
            let (command, rate) = command_at(t);
            GuidanceInput {
                command_ned_ft: command,
                command_rate_ned_fps: rate,
                ..GuidanceInput::steady(Vec3::zeros(), Vec3::zeros())
            }
        };
        let mut filter = command_at(0.0).0 / b_hat;
        let dt = 0.01;
        for i in 0..2000 {
            let t = i as f64 * dt;
            // Midpoint step: second order, enough for a test of the equation.
            let k1 = shaping.command(&filter, b_hat, &input_at(t)).filter_rate;
            let mid = filter + k1 * (0.5 * dt);
            filter += shaping
                .command(&mid, b_hat, &input_at(t + 0.5 * dt))
                .filter_rate
                * dt;
        }
        let expected = command_at(20.0).0 / b_hat;
        assert!((filter - expected).norm() < 1e-3, "{filter} vs {expected}");
    }

    /// The approach limit holds the commanded point's speed to its bound, in ft/s.
    #[test]
    fn approach_speed_is_limited() {
        let shaping = CommandShaping {
            pole_rps: 0.1,
            approach_speed_max_fps: Some(7.0),
        };
        let input = GuidanceInput::steady(Vec3::zeros(), Vec3::new(32.0, 8.0, 0.0));
        let far = Vec3::new(200.0, 50.0, 30.0) / 8.0;
        let rate = shaping.command(&far, 8.0, &input).filter_rate;
        assert!((rate.norm() * 8.0 - 7.0).abs() < 1e-12, "{rate}");
        let near = Vec3::new(33.0, 8.0, 0.0) / 8.0;
        let rate = shaping.command(&near, 8.0, &input).filter_rate;
        assert!((rate - (Vec3::new(32.0, 8.0, 0.0) / 8.0 - near) * 0.1).norm() < 1e-15);
    }

    /// Without the filter r_c = (R_c + excitation) / b̂ and ṙ_c carries -b̂' R_c / b̂² (4.15).
    #[test]
    fn unfiltered_command_and_rate() {
        let shaping = CommandShaping {
            pole_rps: 0.0,
            approach_speed_max_fps: None,
        };
        let input = GuidanceInput::steady(Vec3::zeros(), Vec3::new(32.0, 8.0, 0.0));
        let cmd = shaping.command(&Vec3::zeros(), 8.0, &input);
        assert_eq!(cmd.value, Vec3::new(4.0, 1.0, 0.0));
        assert_eq!(cmd.rate(2.0), -Vec3::new(32.0, 8.0, 0.0) * (2.0 / 64.0));
        assert_eq!(cmd.filter_rate, Vec3::zeros());
    }
}
