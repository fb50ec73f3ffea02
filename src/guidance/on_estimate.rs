//! The seed's velocity law flown on the Kalman estimator's estimates (docs/equations.md, Beyond the
//! seed: range from the follower's own motion; certainty equivalence): with b̂ = 1/β̂, d̂ and r̂
//! from the filter, e = r̂ - p̂ - r_c (p̂ the leader's swing where the filter models one, so that
//! a link flies its leader's path: docs/equations.md, The leader's swing in its model) and
//! ```text
//! V_F = b̂ (k_F e + d̂ - ṙ_c)       (4.3) with the filter's estimates in place of (4.5)'s
//! ```
//! With b̂ = b this gives ė = -k_F e. The command r_c is the shaping filter's ([`super::shaping`],
//! with R_c / b̂ and the excitation after it); the filter's b̂ changes only at frames, so ṙ_c
//! carries no b̂' term. k_F is `guidance.k` for a follower that realises V_F and
//! `guidance.k_aircraft` for the 6-DOF aircraft, whose velocity lags V_F (the filter itself
//! runs on the follower's realised velocity, so nothing else needs compensating).
//!
//! Beyond the seed, the target's estimated acceleration can be fed forward over the lag of the
//! follower's velocity: V_F += b̂ â τ_lead (`guidance.velocity_lead_s`, 0 for none); and an
//! integral of the slot error removes what a steady shortfall of the realised velocity leaves
//! (docs/equations.md, The slot error's integral):
//! ```text
//! V_F += k_I s,   ṡ = b̂ e   (per axis, held while |k_I s| ≥ the limit and e grows it)
//! ```
//! (`guidance.integral_gain_per_s2`, 0 for none, and `integral_limit_fps`).
//!
//! State: `[r_cf (3), s (3)]`, the shaping filter and the error's integral, ft·s.

use super::shaping::CommandShaping;
use super::signals::{ExcitationErrors, FollowerCommand, GuidanceInput, GuidanceOutput};
use crate::frames::Vec3;
use crate::scenario::GuidanceSection;

/// Length of the law's state.
pub const STATE_LEN: usize = 6;

/// Where the error's integral s starts in the state.
const INTEGRAL: usize = 3;

/// The velocity law on the estimator's estimates.
#[derive(Debug, Clone, PartialEq)]
pub struct VelocityOnEstimate {
    feedback_gain_per_s: f64,
    lead_s: f64,
    integral: ErrorIntegral,
    shaping: CommandShaping,
    /// V_F before the first estimate: b̂(0) d̂(0), as the adaptive law's.
    idle_velocity_ned_fps: Vec3,
}

impl VelocityOnEstimate {
    /// The law a `[guidance]` section describes, feeding the error back with `k_F`.
    pub fn new(section: &GuidanceSection, feedback_gain_per_s: f64) -> Self {
        Self {
            feedback_gain_per_s,
            lead_s: section.velocity_lead_s,
            integral: ErrorIntegral {
                gain_per_s2: section.integral_gain_per_s2,
                limit_fps: section.integral_limit_fps,
            },
            shaping: CommandShaping::of(section),
            idle_velocity_ned_fps: Vec3::from(section.d0_per_s) * section.b0_ft,
        }
    }

    /// Initial state: the shaping filter at the first measurement r(0), no integral.
    pub fn initial_state(&self, r0: &Vec3) -> Vec<f64> {
        let mut x = vec![0.0; STATE_LEN];
        self.start_at(&mut x, r0);
        x
    }

    /// Restarts the shaping filter at the first measurement and empties the integral.
    pub fn start_at(&self, x: &mut [f64], r0: &Vec3) {
        x[..INTEGRAL].copy_from_slice(r0.as_slice());
        x[INTEGRAL..].fill(0.0);
    }

    /// Before the first estimate: nothing moves and the follower cruises at b̂(0) d̂(0).
    pub fn idle(&self, x: &[f64], dx: &mut [f64]) -> GuidanceOutput {
        dx.fill(0.0);
        GuidanceOutput {
            command: FollowerCommand::Velocity(self.idle_velocity_ned_fps),
            r_command: Vec3::from_column_slice(x),
            excitation_errors: ExcitationErrors::default(),
            acceleration: None,
        }
    }

    /// Writes ẋ into `dx` and returns V_F for the input's estimate (idles without one).
    pub fn derivative(&self, x: &[f64], input: &GuidanceInput, dx: &mut [f64]) -> GuidanceOutput {
        let Some(estimate) = &input.estimate else {
            return self.idle(x, dx);
        };
        let b_hat = estimate.b_hat_ft;
        let filter = Vec3::from_column_slice(&x[..INTEGRAL]);
        let integral_ft_s = Vec3::from_column_slice(&x[INTEGRAL..]);
        let command = self.shaping.command(&filter, b_hat, input);
        let error = estimate.r - estimate.swing - command.value;
        let g = error * self.feedback_gain_per_s + estimate.d_per_s - command.rate(0.0)
            + estimate.a_per_s2 * self.lead_s;
        dx[..INTEGRAL].copy_from_slice(command.filter_rate.as_slice());
        let integral_rate = self.integral.rate(&integral_ft_s, &(error * b_hat));
        dx[INTEGRAL..].copy_from_slice(integral_rate.as_slice());
        GuidanceOutput {
            command: FollowerCommand::Velocity(
                g * b_hat + integral_ft_s * self.integral.gain_per_s2,
            ),
            r_command: command.value,
            excitation_errors: ExcitationErrors {
                measured: input.r_measured.map_or(error, |r| r - command.value),
                estimated: error,
            },
            acceleration: None,
        }
    }
}

/// The integral of the slot error in feet, s, and its term k_I s in V_F with its bound.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ErrorIntegral {
    /// k_I, 1/s².
    gain_per_s2: f64,
    /// The bound of |k_I s| per axis, ft/s.
    limit_fps: f64,
}

impl ErrorIntegral {
    /// ṡ = b̂ e per axis, but zero on an axis whose term is at its bound and which the error
    /// would push further (conditional integration); zero throughout without a gain, so the
    /// state stays inert in the seed's law.
    fn rate(&self, integral_ft_s: &Vec3, error_ft: &Vec3) -> Vec3 {
        if self.gain_per_s2 == 0.0 {
            return Vec3::zeros();
        }
        Vec3::from_fn(|i, _| {
            let term_fps = self.gain_per_s2 * integral_ft_s[i];
            let saturated = term_fps.abs() >= self.limit_fps && term_fps * error_ft[i] > 0.0;
            if saturated { 0.0 } else { error_ft[i] }
        })
    }
}

/// The names of the state slice's elements (for messages).
pub fn state_names() -> Vec<String> {
    crate::state_block::element_names(
        "guidance",
        &[
            ("shaping filter r_cf", crate::state_block::XYZ),
            ("slot error integral s", crate::state_block::XYZ),
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimation::TargetEstimate;

    fn estimate(r: Vec3) -> TargetEstimate {
        TargetEstimate {
            r,
            swing: Vec3::zeros(),
            d_per_s: Vec3::new(6.25, 0.0, 0.0),
            a_per_s2: Vec3::zeros(),
            b_hat_ft: 8.0,
            b_sigma_ft: 0.1,
            b_sigma_reducible_ft: 0.1,
        }
    }

    /// The slot R_c of an 8 ft target, ft.
    const SLOT_FT: Vec3 = Vec3::new(32.0, 8.0, 0.0);

    /// V_F of a law without shaping (k_F = 0.5) on its slot's scaled command, its filter
    /// started there, for `estimate`.
    fn command_for(estimate: TargetEstimate) -> FollowerCommand {
        let section = GuidanceSection {
            shaping_pole_rps: 0.0,
            ..GuidanceSection::default()
        };
        let law = VelocityOnEstimate::new(&section, 0.5);
        let x = law.initial_state(&(SLOT_FT / 8.0));
        let mut dx = vec![0.0; STATE_LEN];
        let input = GuidanceInput {
            estimate: Some(estimate),
            ..GuidanceInput::steady(SLOT_FT / 8.0, SLOT_FT)
        };
        law.derivative(&x, &input, &mut dx).command
    }

    /// On the slot with d̂ = d the follower flies the target's velocity b d; ahead of the slot
    /// it speeds up by k_F b e.
    #[test]
    fn flies_the_target_velocity_plus_feedback() {
        assert_eq!(
            command_for(estimate(SLOT_FT / 8.0)),
            FollowerCommand::Velocity(Vec3::new(50.0, 0.0, 0.0))
        );
        assert_eq!(
            command_for(estimate(SLOT_FT / 8.0 + Vec3::new(1.0, 0.0, 0.0))),
            FollowerCommand::Velocity(Vec3::new(54.0, 0.0, 0.0))
        );
    }

    /// A leader estimated 1 ft ahead of its path by its swing is flown on its path: the command
    /// is the one for r̂ - p̂, the error's swing left out.
    #[test]
    fn the_leaders_swing_is_not_flown() {
        let section = GuidanceSection {
            shaping_pole_rps: 0.0,
            ..GuidanceSection::default()
        };
        let law = VelocityOnEstimate::new(&section, 0.5);
        let slot = Vec3::new(32.0, 8.0, 0.0);
        let x = law.initial_state(&(slot / 8.0));
        let mut dx = vec![0.0; STATE_LEN];
        let swing = Vec3::new(1.0, 0.0, 0.0) / 8.0;
        let swinging = GuidanceInput {
            estimate: Some(TargetEstimate {
                swing,
                ..estimate(slot / 8.0 + swing)
            }),
            ..GuidanceInput::steady(slot / 8.0, slot)
        };
        let out = law.derivative(&x, &swinging, &mut dx);
        assert_eq!(
            out.command,
            FollowerCommand::Velocity(Vec3::new(50.0, 0.0, 0.0))
        );
    }

    /// A follower that flies 1.2 ft/s less downward than asked (a biased attitude or α vane)
    /// settles at e = shortfall / k_F = 3 ft off the slot without the integral, and on the slot
    /// with it; the integral's term then stands for the shortfall.
    #[test]
    fn integral_removes_a_steady_shortfall() {
        let shortfall_fps = Vec3::new(0.0, 0.0, -1.2);
        let settle = |gain_per_s2: f64| {
            let section = GuidanceSection {
                shaping_pole_rps: 0.0,
                integral_gain_per_s2: gain_per_s2,
                ..GuidanceSection::default()
            };
            fly_with_shortfall(&VelocityOnEstimate::new(&section, 0.4), shortfall_fps)
        };
        let (error_ft, _) = settle(0.0);
        assert!((error_ft.z - 3.0).abs() < 0.05, "{error_ft}");
        let (error_ft, x) = settle(0.02);
        assert!(error_ft.norm() < 0.05, "{error_ft}");
        let term_fps = x[INTEGRAL + 2] * 0.02;
        assert!((term_fps - 1.2).abs() < 0.05, "{term_fps}");
    }

    /// The integral's term stops at its bound while the error would grow it further, and
    /// unwinds as soon as the error turns.
    #[test]
    fn integral_stops_at_its_bound() {
        let integral = ErrorIntegral {
            gain_per_s2: 0.02,
            limit_fps: 5.0,
        };
        let at_bound = Vec3::new(250.0, -250.0, 100.0);
        let error_ft = Vec3::new(1.0, -1.0, 1.0);
        assert_eq!(
            integral.rate(&at_bound, &error_ft),
            Vec3::new(0.0, 0.0, 1.0)
        );
        assert_eq!(integral.rate(&at_bound, &-error_ft), -error_ft);
        let off = ErrorIntegral {
            gain_per_s2: 0.0,
            ..integral
        };
        assert_eq!(off.rate(&Vec3::zeros(), &error_ft), Vec3::zeros());
    }

    /// Flies the law for 400 s (Euler, 10 ms) against a target at 50 ft/s north with b = b̂ =
    /// 8 ft and the estimate exact, the follower realising V_F + `shortfall_fps`; returns the
    /// final error R - R_c, ft, and the law's state.
    fn fly_with_shortfall(law: &VelocityOnEstimate, shortfall_fps: Vec3) -> (Vec3, Vec<f64>) {
        let slot_ft = Vec3::new(32.0, 8.0, 0.0);
        let target_fps = Vec3::new(50.0, 0.0, 0.0);
        let dt_s = 0.01;
        let mut relative_ft = slot_ft;
        let mut x = law.initial_state(&(slot_ft / 8.0));
        let mut dx = vec![0.0; STATE_LEN];
        for _ in 0..40_000 {
            let input = GuidanceInput {
                estimate: Some(estimate(relative_ft / 8.0)),
                ..GuidanceInput::steady(relative_ft / 8.0, slot_ft)
            };
            let FollowerCommand::Velocity(v_fps) = law.derivative(&x, &input, &mut dx).command
            else {
                panic!("a velocity command");
            };
            relative_ft += (target_fps - v_fps - shortfall_fps) * dt_s;
            for (xi, dxi) in x.iter_mut().zip(&dx) {
                *xi += dxi * dt_s;
            }
        }
        (relative_ft - slot_ft, x)
    }
}
