//! The guidance stage as the simulation sees it: one of the two laws behind one interface
//! (`[guidance] law = "velocity" | "acceleration"`). It builds the law a scenario asks for, with
//! the velocity law's estimator gain, the acceleration law's observer-gain design and, when the
//! simulation says the follower does not realise the command, the compensation of
//! [`super::compensation`].

use super::acceleration::AccelerationGuidance;
use super::compensation::{ShortfallCompensation, VelocityLagCompensation};
use super::on_estimate::{self, VelocityOnEstimate};
use super::signals::{
    AccelerationGuidanceOutput, ExcitationErrors, FollowerCommand, GuidanceInput, GuidanceOutput,
};
use super::velocity::VelocityGuidance;
use super::velocity_estimator::{VelocityEstimator, steady_state_estimator_gain};
use crate::estimation::{LawEstimates, TargetMotionEstimate};
use crate::frames::{Mat3, Vec3};
use crate::linalg::LinalgError;
use crate::scenario::{AccelerationSection, EstimatorGainMode, GuidanceLawKind, GuidanceSection};

/// Why a guidance law could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GuidanceSetupError {
    /// The velocity estimator's matrices could not be computed.
    #[error("velocity estimator: {0}")]
    Estimator(#[from] LinalgError),
}

/// The guidance law of a run.
#[derive(Debug, Clone, PartialEq)]
pub enum GuidanceLaw {
    /// Velocity guidance (4.3)-(4.5), with the estimator (6.10)-(6.17) when asked for.
    Velocity(VelocityGuidance),
    /// Acceleration guidance (5.2)-(5.41), (6.39)-(6.42).
    Acceleration(AccelerationGuidance),
    /// The velocity law flown on the Kalman estimator's estimates (docs/equations.md, Beyond
    /// the seed: range from the follower's own motion).
    VelocityOnEstimate(VelocityOnEstimate),
}

impl GuidanceLaw {
    /// The seed's adaptive law of a `[guidance]` (and `[acceleration]`) section, in which b̂
    /// and d̂ adapt inside the law, compensating for a follower that does not realise the
    /// command when `compensate`, and the notes its design leaves for the run's log (the
    /// estimator gain in use; a Riccati observer gain that fell back to the fixed one).
    pub fn adaptive(
        g: &GuidanceSection,
        acceleration: &AccelerationSection,
        compensate: bool,
    ) -> Result<(Self, Vec<String>), GuidanceSetupError> {
        let mut notes = Vec::new();
        match g.law {
            GuidanceLawKind::Velocity => {
                let estimator = if g.estimator {
                    let (gain, note) = estimator_gain(g)?;
                    notes.extend(note);
                    Some(VelocityEstimator::new(
                        g.k,
                        gain,
                        g.estimator_lyapunov_weight,
                    )?)
                } else {
                    None
                };
                let compensation = compensate.then_some(VelocityLagCompensation {
                    adaptation_gain_per_s: g.k,
                    feedback_gain_per_s: g.k_aircraft,
                });
                let law = VelocityGuidance::new(g, estimator, compensation);
                Ok((Self::Velocity(law), notes))
            }
            GuidanceLawKind::Acceleration => {
                let compensation = compensate.then_some(ShortfallCompensation {
                    time_constant_s: acceleration.shortfall_time_constant_s,
                });
                let law = AccelerationGuidance::new(acceleration, g, compensation);
                notes.extend(law.observer_design().fallback_message());
                Ok((Self::Acceleration(law), notes))
            }
        }
    }

    /// The velocity law flown on the Kalman estimator's estimates, with the gentler gain
    /// `k_aircraft` when it compensates for a follower that does not realise the command.
    pub fn on_estimate(g: &GuidanceSection, compensate: bool) -> Self {
        let gain = if compensate { g.k_aircraft } else { g.k };
        Self::VelocityOnEstimate(VelocityOnEstimate::new(g, gain))
    }

    /// Length of the law's state slice.
    pub fn state_len(&self) -> usize {
        match self {
            Self::Velocity(law) => law.state_len(),
            Self::Acceleration(law) => law.state_len(),
            Self::VelocityOnEstimate(_) => on_estimate::STATE_LEN,
        }
    }

    /// The names of the state slice's elements (for messages).
    pub fn state_names(&self) -> Vec<String> {
        match self {
            Self::Velocity(law) => law.state_names(),
            Self::Acceleration(law) => law.state_names(),
            Self::VelocityOnEstimate(_) => on_estimate::state_names(),
        }
    }

    /// Initial state with the filters started at the first measurement r(0).
    pub fn initial_state(&self, r0: &Vec3) -> Vec<f64> {
        match self {
            Self::Velocity(law) => law.initial_state(r0),
            Self::Acceleration(law) => law.initial_state(r0),
            Self::VelocityOnEstimate(law) => law.initial_state(r0),
        }
    }

    /// Restarts the filters at the first measurement, keeping the parameter estimates.
    pub fn start_at(&self, x: &mut [f64], r0: &Vec3) {
        match self {
            Self::Velocity(law) => law.start_at(x, r0),
            Self::Acceleration(law) => law.start_at(x, r0),
            Self::VelocityOnEstimate(law) => law.start_at(x, r0),
        }
    }

    /// Before the first measurement: no state moves; the velocity law commands b̂(0) d̂(0),
    /// the acceleration law a_F = 0 (the follower keeps V_F(0)).
    pub fn idle(&self, x: &[f64], dx: &mut [f64]) -> GuidanceOutput {
        match self {
            Self::Velocity(law) => law.idle(x, dx),
            Self::Acceleration(law) => acceleration_output(law.idle(x, dx)),
            Self::VelocityOnEstimate(law) => law.idle(x, dx),
        }
    }

    /// Writes the law's ẋ into `dx` and returns its command.
    pub fn derivative(&self, x: &[f64], input: &GuidanceInput, dx: &mut [f64]) -> GuidanceOutput {
        match self {
            Self::Velocity(law) => law.derivative(x, input, dx),
            Self::Acceleration(law) => acceleration_output(law.derivative(x, input, dx)),
            Self::VelocityOnEstimate(law) => law.derivative(x, input, dx),
        }
    }

    /// Clamps b̂ and d̂ back into their projection bounds after a step.
    pub fn enforce_bounds(&self, x: &mut [f64]) {
        match self {
            Self::Velocity(law) => law.enforce_bounds(x),
            Self::Acceleration(law) => law.enforce_bounds(x),
            Self::VelocityOnEstimate(_) => {}
        }
    }

    /// The law's own estimates b̂ and d̂ in a state slice (`None` for the law on the
    /// estimator's estimates).
    pub fn estimates(&self, x: &[f64]) -> Option<LawEstimates> {
        Some(match self {
            Self::Velocity(law) => {
                let state = law.unpack(x);
                LawEstimates {
                    b_hat_ft: state.b_hat_ft,
                    target_motion: TargetMotionEstimate::ScaledVelocity(state.d_hat_per_s),
                }
            }
            Self::Acceleration(law) => {
                let state = law.unpack(x);
                LawEstimates {
                    b_hat_ft: state.b_hat_ft,
                    target_motion: TargetMotionEstimate::FilteredAccelerationBound(state.d_hat_fps),
                }
            }
            Self::VelocityOnEstimate(_) => return None,
        })
    }
}

/// L_v of the velocity estimator: fixed, or from the steady-state covariance (6.36) with a
/// note saying which.
fn estimator_gain(g: &GuidanceSection) -> Result<(Mat3, Option<String>), LinalgError> {
    Ok(match g.estimator_gain_mode {
        EstimatorGainMode::Fixed => (Mat3::identity() * g.estimator_gain, None),
        EstimatorGainMode::Covariance => {
            let gain =
                steady_state_estimator_gain(g.k, g.estimator_process_psd, g.estimator_noise_psd)?;
            let note = format!(
                "velocity estimator: L_v = {:.4} I from the steady-state covariance (6.36) \
                 (q = {:e} 1/s, K_nr = {:e} s)",
                gain[(0, 0)],
                g.estimator_process_psd,
                g.estimator_noise_psd
            );
            (gain, Some(note))
        }
    })
}

/// The acceleration law's output as a [`GuidanceOutput`]: its excitation errors are the
/// combined output y_a (measured) and C (ẑ - z_m) (estimated).
fn acceleration_output(out: AccelerationGuidanceOutput) -> GuidanceOutput {
    GuidanceOutput {
        command: FollowerCommand::Acceleration(out.accel_cmd_ned_fps2),
        r_command: out.y_command,
        excitation_errors: ExcitationErrors {
            measured: out.y_combined,
            estimated: out.y_observer - out.y_model,
        },
        acceleration: Some(out),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::ObserverGainMode;

    fn build(g: &GuidanceSection, a: &AccelerationSection) -> (GuidanceLaw, Vec<String>) {
        GuidanceLaw::adaptive(g, a, false).expect("builds")
    }

    /// The law follows `[guidance] law`; a Riccati observer gain that falls back leaves a
    /// note for the log, as does a covariance estimator gain.
    #[test]
    fn builds_the_law_the_scenario_asks_for() {
        let mut g = GuidanceSection::default();
        let a = AccelerationSection::default();
        let (law, notes) = build(&g, &a);
        assert!(matches!(law, GuidanceLaw::Velocity(_)) && notes.is_empty());

        g.estimator = true;
        g.estimator_gain_mode = EstimatorGainMode::Covariance;
        let (law, notes) = build(&g, &a);
        assert_eq!(law.state_len(), 10);
        assert!(notes[0].contains("L_v"), "{notes:?}");

        g.law = GuidanceLawKind::Acceleration;
        let riccati = AccelerationSection {
            observer_gain_mode: ObserverGainMode::Riccati,
            riccati_process_psd: 1e-4,
            riccati_noise_psd: 1.0,
            ..AccelerationSection::default()
        };
        let (law, notes) = build(&g, &riccati);
        assert!(matches!(law, GuidanceLaw::Acceleration(_)));
        assert!(notes[0].contains("Riccati gain rejected"), "{notes:?}");
    }

    /// With compensation each law carries the compensation's state (3 values).
    #[test]
    fn compensation_adds_its_state() {
        let mut g = GuidanceSection::default();
        let a = AccelerationSection::default();
        for law in [GuidanceLawKind::Velocity, GuidanceLawKind::Acceleration] {
            g.law = law;
            let plain = build(&g, &a).0.state_len();
            let compensated = GuidanceLaw::adaptive(&g, &a, true)
                .expect("builds")
                .0
                .state_len();
            assert_eq!(compensated, plain + 3);
        }
    }

    /// Before the first measurement the acceleration law commands a_F = 0, moves nothing, and
    /// still reports its signals (telemetry columns do not change when the camera's first
    /// frame arrives).
    #[test]
    fn acceleration_law_idles_with_its_signals() {
        let g = GuidanceSection {
            law: GuidanceLawKind::Acceleration,
            ..GuidanceSection::default()
        };
        let (law, _) = build(&g, &AccelerationSection::default());
        let x = law.initial_state(&Vec3::new(25.0, 6.25, 3.75));
        let mut dx = vec![1.0; law.state_len()];
        let out = law.idle(&x, &mut dx);
        assert!(dx.iter().all(|v| *v == 0.0));
        assert_eq!(out.command, FollowerCommand::Acceleration(Vec3::zeros()));
        let signals = out.acceleration.expect("signals");
        assert_eq!(signals.y_observer, Vec3::new(25.0, 6.25, 3.75));
    }

    /// Without a measurement the acceleration law coasts on its observer: at the equilibrium
    /// that is the measurement itself, so the command is the same.
    #[test]
    fn acceleration_law_coasts_on_its_observer() {
        let g = GuidanceSection {
            law: GuidanceLawKind::Acceleration,
            shaping_pole_rps: 0.0,
            ..GuidanceSection::default()
        };
        let (law, _) = build(&g, &AccelerationSection::default());
        let GuidanceLaw::Acceleration(acceleration) = &law else {
            panic!("an acceleration law");
        };
        let r_c = Vec3::new(4.0, 1.0, 0.0);
        let mut x = law.initial_state(&r_c);
        let state = acceleration.unpack(&x);
        crate::guidance::acceleration::AccelerationState {
            b_hat_ft: 8.0,
            ..state
        }
        .pack(&mut x);
        let input = GuidanceInput::steady(r_c, r_c * 8.0);
        let mut dx = vec![0.0; law.state_len()];
        let measured = law.derivative(&x, &input, &mut dx);
        let lost = law.derivative(
            &x,
            &GuidanceInput {
                r_measured: None,
                ..input
            },
            &mut dx,
        );
        assert_eq!(measured.command, lost.command);
        assert_eq!(lost.command, FollowerCommand::Acceleration(Vec3::zeros()));
    }
}
