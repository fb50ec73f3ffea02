//! Velocity guidance ((4.3)-(4.5); docs/equations.md, Velocity guidance (Chapter 4)):
//! V_F = b̂ g with adaptive estimates of the target's size b̂ and scaled velocity d̂, the command
//! shaping of [`super::shaping`], and optionally the state estimator of Chapter 6 ((6.10)-(6.17))
//! for noisy measurements. For a follower that does not realise V_F (the 6-DOF aircraft) the law
//! carries the lag compensation of [`super::compensation`]: it feeds the error back with k_F and
//! adapts on ē = e - η.
//!
//! State: [`VelocityState`], `[b̂, d̂ (3), r_cf (3), r̂ (3, with the estimator), η (3, with
//! compensation)]`.

use super::compensation::VelocityLagCompensation;
use super::shaping::{CommandShaping, ShapedCommand};
use super::signals::{ExcitationErrors, FollowerCommand, GuidanceInput, GuidanceOutput};
use super::velocity_estimator::VelocityEstimator;
use crate::frames::Vec3;
use crate::projection::{BallBound, EstimateBounds, IntervalBound};
use crate::scenario::GuidanceSection;
use crate::state_block::{StateReader, StateWriter};
use nalgebra::SMatrix;

/// The law's continuous state; holding rates, its derivative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityState {
    /// b̂, the estimate of the target's size, ft (4.5).
    pub b_hat_ft: f64,
    /// d̂, the estimate of the scaled target velocity V_T/b, 1/s (4.5).
    pub d_hat_per_s: Vec3,
    /// r_cf, the shaping filter's state ([`super::shaping`]).
    pub shaping_filter: Vec3,
    /// r̂, the Chapter 6 estimator's state (6.10), with the estimator.
    pub r_hat: Option<Vec3>,
    /// η, the lag error of [`super::compensation`], with compensation.
    pub lag_error: Option<Vec3>,
}

impl VelocityState {
    /// Writes the block into its state slice.
    pub fn pack(&self, x: &mut [f64]) {
        StateWriter::new(x)
            .scalar(self.b_hat_ft)
            .vec3(&self.d_hat_per_s)
            .vec3(&self.shaping_filter)
            .optional_vec3(&self.r_hat)
            .optional_vec3(&self.lag_error);
    }
}

/// Velocity guidance (4.3)-(4.5), (4.14)-(4.15), (4.40), with optional estimator (6.10)-(6.17)
/// and compensation for a follower that does not realise V_F.
#[derive(Debug, Clone, PartialEq)]
pub struct VelocityGuidance {
    k: f64,
    sigma: f64,
    gamma_d: f64,
    bounds: EstimateBounds,
    shaping: CommandShaping,
    b0_ft: f64,
    d0: Vec3,
    estimator: Option<VelocityEstimator>,
    compensation: Option<VelocityLagCompensation>,
}

impl VelocityGuidance {
    /// The law a `[guidance]` section describes, with the estimator and the compensation when
    /// given.
    pub fn new(
        section: &GuidanceSection,
        estimator: Option<VelocityEstimator>,
        compensation: Option<VelocityLagCompensation>,
    ) -> Self {
        Self {
            k: section.k,
            sigma: section.sigma,
            gamma_d: section.gamma_d,
            bounds: EstimateBounds {
                b: IntervalBound {
                    min: section.b_min_ft,
                    max: section.b_max_ft,
                    epsilon: section.b_epsilon_ft2,
                },
                d: BallBound {
                    max_norm: section.d_max_per_s,
                    epsilon: section.d_epsilon,
                },
            },
            shaping: CommandShaping::of(section),
            b0_ft: section.b0_ft,
            d0: Vec3::from(section.d0_per_s),
            estimator,
            compensation,
        }
    }

    /// Length of this law's state slice.
    pub fn state_len(&self) -> usize {
        7 + 3 * usize::from(self.estimator.is_some()) + 3 * usize::from(self.compensation.is_some())
    }

    /// The typed state of a state slice.
    pub fn unpack(&self, x: &[f64]) -> VelocityState {
        let mut r = StateReader::new(x);
        VelocityState {
            b_hat_ft: r.scalar(),
            d_hat_per_s: r.vec3(),
            shaping_filter: r.vec3(),
            r_hat: r.optional_vec3(self.estimator.is_some()),
            lag_error: r.optional_vec3(self.compensation.is_some()),
        }
    }

    /// Initial state: b̂(0), d̂(0); the shaping filter and the estimator start at the first
    /// measurement r(0), the lag error at zero.
    pub fn initial_state(&self, r0: &Vec3) -> Vec<f64> {
        let mut x = vec![0.0; self.state_len()];
        VelocityState {
            b_hat_ft: self.b0_ft,
            d_hat_per_s: self.d0,
            shaping_filter: *r0,
            r_hat: self.estimator.as_ref().map(|_| *r0),
            lag_error: self.compensation.map(|_| Vec3::zeros()),
        }
        .pack(&mut x);
        x
    }

    /// Restarts the shaping filter and the estimator at the first measurement r(0), keeping
    /// b̂ and d̂ (a camera's first frame arrives after the run starts).
    pub fn start_at(&self, x: &mut [f64], r0: &Vec3) {
        let state = self.unpack(x);
        VelocityState {
            shaping_filter: *r0,
            r_hat: state.r_hat.map(|_| *r0),
            ..state
        }
        .pack(x);
    }

    /// Before the first measurement: no state moves and the follower cruises at V_F = b̂ d̂.
    pub fn idle(&self, x: &[f64], dx: &mut [f64]) -> GuidanceOutput {
        dx.fill(0.0);
        let state = self.unpack(x);
        GuidanceOutput {
            command: FollowerCommand::Velocity(state.d_hat_per_s * state.b_hat_ft),
            r_command: state.shaping_filter,
            excitation_errors: ExcitationErrors::default(),
            acceleration: None,
        }
    }

    /// k_F, the gain on the error in V_F: `k_aircraft` with compensation, k without.
    fn feedback_gain(&self) -> f64 {
        self.compensation.map_or(self.k, |c| c.feedback_gain_per_s)
    }

    /// Writes ẋ into `dx` and returns the command. Mission formation or interception is set
    /// by the input: interception is R_c = 0 (4.40).
    pub fn derivative(&self, x: &[f64], input: &GuidanceInput, dx: &mut [f64]) -> GuidanceOutput {
        let state = self.unpack(x);
        let b_hat = state.b_hat_ft;
        let command = self.shaping.command(&state.shaping_filter, b_hat, input);
        let r_used = match (state.r_hat, input.r_measured) {
            (Some(r_hat), _) => r_hat,
            (None, Some(r_star)) => r_star,
            (None, None) => command.value,
        };
        let error = r_used - command.value;
        let adaptation_signal = self.adaptation_signal(&state, input, &command.value, &r_used);
        // g_a = V_a / b̂, the realised scaled velocity, when compensating.
        let realised = self
            .compensation
            .and(input.follower)
            .map(|f| f.realised_velocity_ned_fps / b_hat);
        let (g, b_hat_rate) =
            self.scaled_velocity(&state, &command, &error, &adaptation_signal, realised);
        let g_a = realised.unwrap_or(g);
        let rates = VelocityState {
            b_hat_ft: b_hat_rate,
            d_hat_per_s: self
                .bounds
                .d
                .project(&state.d_hat_per_s, &adaptation_signal)
                * self.gamma_d,
            shaping_filter: command.filter_rate,
            r_hat: self.estimator.as_ref().map(|est| {
                // (6.10): r̂' = d̂ - g + L_v (r* - r̂), with g_a when compensating.
                let innovation = input
                    .r_measured
                    .map_or(Vec3::zeros(), |r_star| r_star - r_used);
                state.d_hat_per_s - g_a + est.gain * innovation
            }),
            lag_error: self
                .compensation
                .zip(state.lag_error)
                .map(|(c, chi)| c.lag_error_rate(&chi, &error, &g, &g_a)),
        };
        rates.pack(dx);
        let measured = input.r_measured.unwrap_or(r_used) - command.value;
        GuidanceOutput {
            command: FollowerCommand::Velocity(g * b_hat),
            r_command: command.value,
            excitation_errors: ExcitationErrors {
                measured: compensated(measured, state.lag_error),
                estimated: compensated(error, state.lag_error),
            },
            acceleration: None,
        }
    }

    /// The vector the adaptation (4.5) or (6.16) runs on: ē = e - η, or B_vᵀ P_v ξ*_v with
    /// ξ*_v = [r* - r_c - η; r* - r̂] with the estimator; zero while the target is lost.
    fn adaptation_signal(
        &self,
        state: &VelocityState,
        input: &GuidanceInput,
        r_command: &Vec3,
        r_used: &Vec3,
    ) -> Vec3 {
        match (&self.estimator, input.r_measured) {
            (_, None) => Vec3::zeros(),
            (Some(est), Some(r_star)) => {
                let mut xi = SMatrix::<f64, 6, 1>::zeros();
                xi.fixed_rows_mut::<3>(0)
                    .copy_from(&compensated(r_star - r_command, state.lag_error));
                xi.fixed_rows_mut::<3>(3).copy_from(&(r_star - r_used));
                est.bt_p * xi
            }
            (None, Some(_)) => compensated(r_used - r_command, state.lag_error),
        }
    }

    /// g = k_F e + d̂ - ṙ_c (4.3) and b̂' = σ Proj(b̂, g_aᵀ ē) (4.5), g_a = g without
    /// compensation. ṙ_c contains -b̂' R_c / b̂² (4.15) and b̂' depends on g: the algebraic
    /// loop is closed by one fixed-point pass starting from b̂' = 0.
    fn scaled_velocity(
        &self,
        state: &VelocityState,
        command: &ShapedCommand,
        error: &Vec3,
        adaptation_signal: &Vec3,
        realised: Option<Vec3>,
    ) -> (Vec3, f64) {
        let gain = self.feedback_gain();
        let guidance =
            |b_hat_rate: f64| error * gain + state.d_hat_per_s - command.rate(b_hat_rate);
        let b_rate_of = |g: &Vec3| {
            let g_a = realised.unwrap_or(*g);
            self.sigma
                * self
                    .bounds
                    .b
                    .project(state.b_hat_ft, g_a.dot(adaptation_signal))
        };
        let g = guidance(b_rate_of(&guidance(0.0)));
        (g, b_rate_of(&g))
    }

    /// Clamps b̂ and d̂ back into Ω_1 after an integration step (see [`crate::projection`]).
    pub fn enforce_bounds(&self, x: &mut [f64]) {
        let mut state = self.unpack(x);
        (state.b_hat_ft, state.d_hat_per_s) = self.bounds.clamp(state.b_hat_ft, &state.d_hat_per_s);
        state.pack(x);
    }
}

/// ē = e - η with compensation, e without.
fn compensated(error: Vec3, lag_error: Option<Vec3>) -> Vec3 {
    lag_error.map_or(error, |chi| error - chi)
}

impl VelocityGuidance {
    /// The names of the state slice's elements, in [`VelocityState`]'s order (for messages).
    pub fn state_names(&self) -> Vec<String> {
        use crate::state_block::{XYZ, element_names};
        let mut groups: Vec<(&str, &[&str])> = vec![
            ("b̂ (target size estimate), ft", &[]),
            ("d̂ (scaled target velocity estimate), 1/s", XYZ),
            ("shaping filter r_cf", XYZ),
        ];
        if self.estimator.is_some() {
            groups.push(("estimator r̂", XYZ));
        }
        if self.compensation.is_some() {
            groups.push(("lag error", XYZ));
        }
        element_names("guidance", &groups)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(r: Vec3) -> GuidanceInput {
        GuidanceInput::steady(r, Vec3::new(32.0, 8.0, 0.0))
    }

    fn velocity(out: &GuidanceOutput) -> Vec3 {
        match out.command {
            FollowerCommand::Velocity(v) => v,
            FollowerCommand::Acceleration(_) => panic!("the velocity law commands velocities"),
        }
    }

    /// The typed state packs and unpacks in the slice layout the module documents.
    #[test]
    fn state_layout() {
        let section = GuidanceSection::default();
        let compensation = VelocityLagCompensation {
            adaptation_gain_per_s: 3.5,
            feedback_gain_per_s: 0.5,
        };
        let estimator =
            VelocityEstimator::new(3.5, crate::frames::Mat3::identity() * 1.7, 1.0).ok();
        let law = VelocityGuidance::new(&section, estimator, Some(compensation));
        assert_eq!(law.state_len(), 13);
        let x: Vec<f64> = (0..13).map(f64::from).collect();
        let state = law.unpack(&x);
        assert_eq!(state.b_hat_ft, 0.0);
        assert_eq!(state.r_hat, Some(Vec3::new(7.0, 8.0, 9.0)));
        assert_eq!(state.lag_error, Some(Vec3::new(10.0, 11.0, 12.0)));
        let mut back = vec![0.0; 13];
        state.pack(&mut back);
        assert_eq!(back, x);
    }

    /// With the error at zero and d̂ = d, the follower flies the target's velocity b d and no
    /// estimate moves.
    #[test]
    fn at_equilibrium_nothing_moves() {
        let section = GuidanceSection {
            shaping_pole_rps: 0.0,
            b0_ft: 8.0,
            d0_per_s: [6.25, 0.0, 0.0],
            ..GuidanceSection::default()
        };
        let law = VelocityGuidance::new(&section, None, None);
        let r_c = Vec3::new(32.0, 8.0, 0.0) / 8.0;
        let x = law.initial_state(&r_c);
        let mut dx = vec![0.0; law.state_len()];
        let out = law.derivative(&x, &input(r_c), &mut dx);
        assert!((velocity(&out) - Vec3::new(50.0, 0.0, 0.0)).norm() < 1e-12);
        assert!(dx.iter().all(|v| v.abs() < 1e-12), "{dx:?}");
    }

    /// Sign check of (4.6): with a positive error along x the follower speeds up along x.
    #[test]
    fn error_ahead_speeds_up() {
        let section = GuidanceSection {
            d0_per_s: [0.0; 3],
            ..GuidanceSection::default()
        };
        let law = VelocityGuidance::new(&section, None, None);
        let r = Vec3::new(10.0, 2.0, 0.0);
        let mut x = law.initial_state(&r);
        let state = law.unpack(&x);
        VelocityState {
            shaping_filter: Vec3::new(8.0, 2.0, 0.0),
            ..state
        }
        .pack(&mut x);
        let mut dx = vec![0.0; law.state_len()];
        let out = law.derivative(&x, &input(r), &mut dx);
        assert!(velocity(&out).x > 0.0);
        assert!(law.unpack(&dx).d_hat_per_s.x > 0.0);
    }
}
