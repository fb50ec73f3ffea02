//! The seed's velocity law flown on the Kalman estimator's estimates (docs/equations.md, Beyond the
//! seed: range from the follower's own motion; certainty equivalence): with b̂ = 1/β̂, d̂ and r̂
//! from the filter, e = r̂ - r_c and
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
//! follower's velocity: V_F += b̂ â τ_lead (`guidance.velocity_lead_s`, 0 for none).
//!
//! State: `[r_cf (3)]`, the shaping filter.

use super::shaping::CommandShaping;
use super::signals::{ExcitationErrors, FollowerCommand, GuidanceInput, GuidanceOutput};
use crate::frames::Vec3;
use crate::scenario::GuidanceSection;

/// Length of the law's state.
pub const STATE_LEN: usize = 3;

/// The velocity law on the estimator's estimates.
#[derive(Debug, Clone, PartialEq)]
pub struct VelocityOnEstimate {
    feedback_gain_per_s: f64,
    lead_s: f64,
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
            shaping: CommandShaping::of(section),
            idle_velocity_ned_fps: Vec3::from(section.d0_per_s) * section.b0_ft,
        }
    }

    /// Initial state: the shaping filter at the first measurement r(0).
    pub fn initial_state(&self, r0: &Vec3) -> Vec<f64> {
        r0.as_slice().to_vec()
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
        let filter = Vec3::from_column_slice(x);
        let command = self.shaping.command(&filter, b_hat, input);
        let error = estimate.r - command.value;
        let g = error * self.feedback_gain_per_s + estimate.d_per_s - command.rate(0.0)
            + estimate.a_per_s2 * self.lead_s;
        dx.copy_from_slice(command.filter_rate.as_slice());
        GuidanceOutput {
            command: FollowerCommand::Velocity(g * b_hat),
            r_command: command.value,
            excitation_errors: ExcitationErrors {
                measured: input.r_measured.map_or(error, |r| r - command.value),
                estimated: error,
            },
            acceleration: None,
        }
    }
}

/// The names of the state slice's elements (for messages).
pub fn state_names() -> Vec<String> {
    crate::state_block::element_names(
        "guidance",
        &[("shaping filter r_cf", crate::state_block::XYZ)],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimation::TargetEstimate;

    fn estimate(r: Vec3) -> TargetEstimate {
        TargetEstimate {
            r,
            d_per_s: Vec3::new(6.25, 0.0, 0.0),
            a_per_s2: Vec3::zeros(),
            b_hat_ft: 8.0,
            b_sigma_ft: 0.1,
            b_sigma_reducible_ft: 0.1,
        }
    }

    /// On the slot with d̂ = d the follower flies the target's velocity b d; ahead of the slot
    /// it speeds up by k_F b e.
    #[test]
    fn flies_the_target_velocity_plus_feedback() {
        let section = GuidanceSection {
            shaping_pole_rps: 0.0,
            ..GuidanceSection::default()
        };
        let law = VelocityOnEstimate::new(&section, 0.5);
        let slot = Vec3::new(32.0, 8.0, 0.0);
        let input = GuidanceInput::steady(slot / 8.0, slot);
        let mut dx = vec![0.0; STATE_LEN];
        let x = law.initial_state(&(slot / 8.0));
        let on_slot = GuidanceInput {
            estimate: Some(estimate(slot / 8.0)),
            ..input
        };
        let out = law.derivative(&x, &on_slot, &mut dx);
        assert_eq!(
            out.command,
            FollowerCommand::Velocity(Vec3::new(50.0, 0.0, 0.0))
        );
        let ahead = GuidanceInput {
            estimate: Some(estimate(slot / 8.0 + Vec3::new(1.0, 0.0, 0.0))),
            ..input
        };
        let out = law.derivative(&x, &ahead, &mut dx);
        assert_eq!(
            out.command,
            FollowerCommand::Velocity(Vec3::new(54.0, 0.0, 0.0))
        );
    }
}
