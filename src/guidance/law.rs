//! The guidance stage as the simulation sees it: one of the two laws behind one interface
//! (`[guidance] law = "velocity" | "acceleration"`). It builds the law a scenario asks for
//! (with the velocity law's estimator gain and the acceleration law's observer-gain design),
//! maps the common input onto the law's own, and reports the law's command as a
//! [`FollowerCommand`] for the follower stage.

use super::acceleration::{AccelerationGuidance, AccelerationGuidanceOutput};
use super::velocity::{
    VelocityEstimator, VelocityGuidance, VelocityGuidanceOutput, steady_state_estimator_gain,
};
use crate::frames::{Mat3, Vec3};
use crate::scenario::{EstimatorGainMode, FollowerModel, GuidanceLawKind, Scenario};
use crate::world::kinematic::FollowerCommand;

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
    /// Excitation offset a sin(ωt) E in ft, added after the shaping filter (4.31).
    pub excitation_ned_ft: Vec3,
    /// Its time derivative, ft/s.
    pub excitation_rate_ned_fps: Vec3,
    /// Excitation offset in scaled units, added after the shaping filter as it is.
    pub excitation_scaled: Vec3,
    /// Its time derivative, 1/s.
    pub excitation_scaled_rate: Vec3,
    /// The follower's realised inertial velocity, NED, ft/s, when it does not realise the
    /// command exactly (6-DOF follower): the laws then compensate for the difference (see
    /// [`super::velocity`]); `None` for the kinematic follower.
    pub follower_velocity_ned_fps: Option<Vec3>,
    /// The shortfall V_F - V_a of a follower that integrates V_F = V_F(0) + ∫ a_F and flies it
    /// through its own dynamics (6-DOF follower, acceleration law: see
    /// [`super::acceleration`]); `None` otherwise.
    pub follower_velocity_shortfall_ned_fps: Option<Vec3>,
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
            excitation_ned_ft: Vec3::zeros(),
            excitation_rate_ned_fps: Vec3::zeros(),
            excitation_scaled: Vec3::zeros(),
            excitation_scaled_rate: Vec3::zeros(),
            follower_velocity_ned_fps: None,
            follower_velocity_shortfall_ned_fps: None,
        }
    }
}

/// A law's output at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuidanceOutput {
    /// The command for the follower: V_F (4.3) or a_F (5.38).
    pub command: FollowerCommand,
    /// The scaled command the law tracks (shaped, excitation included): r_c or y_c.
    pub r_command: Vec3,
    /// The measured error whose energy sets the intelligent excitation's amplitude
    /// (`excitation.error = "measured"`): e = r* - r_c (velocity law, (4.31)); the combined
    /// output y*_a = C_a ξ_a + 2 n_r = 2y* - y_m - C ẑ (acceleration law: (5.27) integrates
    /// ‖ξ_a‖², of which y_a is the measurable part; the error y - y_c would keep the amplitude
    /// up through the reference model's lag alone).
    pub error: Vec3,
    /// The law's estimate of the same error from its filtered states
    /// (`excitation.error = "estimated"`): r̂ - r_c (velocity law with the estimator (6.10));
    /// C (ẑ - z_m), the observer's estimate of the output tracking error C e (acceleration
    /// law). Without measurement noise both tend to zero with ξ; with noise they stay near
    /// the estimator's residual noise instead of the sensor's.
    pub estimated_error: Vec3,
    /// The acceleration law's internal signals (y_m, C ẑ, y_a, w_f, …).
    pub acceleration: Option<AccelerationGuidanceOutput>,
}

/// Why a guidance law could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GuidanceSetupError {
    /// The velocity estimator's matrices could not be computed.
    #[error("velocity estimator: {0}")]
    Estimator(String),
}

/// The guidance law of a run.
#[derive(Debug, Clone, PartialEq)]
pub enum GuidanceLaw {
    /// Velocity guidance (4.3)-(4.5), with the estimator (6.10)-(6.17) when asked for.
    Velocity(VelocityGuidance),
    /// Acceleration guidance (5.2)-(5.41), (6.39)-(6.42).
    Acceleration(AccelerationGuidance),
}

impl GuidanceLaw {
    /// The law a scenario describes, and the notes its design leaves for the run's log (the
    /// estimator gain in use; a Riccati observer gain that fell back to the fixed one).
    pub fn from_scenario(scenario: &Scenario) -> Result<(Self, Vec<String>), GuidanceSetupError> {
        let g = &scenario.guidance;
        let mut notes = Vec::new();
        match g.law {
            GuidanceLawKind::Velocity => {
                let estimator = if g.estimator {
                    let gain = match g.estimator_gain_mode {
                        EstimatorGainMode::Fixed => Mat3::identity() * g.estimator_gain,
                        EstimatorGainMode::Covariance => {
                            let gain = steady_state_estimator_gain(
                                g.k,
                                g.estimator_process_psd,
                                g.estimator_noise_psd,
                            )
                            .map_err(|e| GuidanceSetupError::Estimator(e.to_string()))?;
                            notes.push(format!(
                                "velocity estimator: L_v = {:.4} I from the steady-state \
                                 covariance (6.36) (q = {:e} 1/s, K_nr = {:e} s)",
                                gain[(0, 0)],
                                g.estimator_process_psd,
                                g.estimator_noise_psd
                            ));
                            gain
                        }
                    };
                    Some(
                        VelocityEstimator::new(g.k, gain, g.estimator_lyapunov_weight)
                            .map_err(|e| GuidanceSetupError::Estimator(e.to_string()))?,
                    )
                } else {
                    None
                };
                // A follower that does not realise V_F exactly gets the compensated law.
                let compensated = scenario.follower.model == FollowerModel::Aircraft;
                Ok((
                    Self::Velocity(VelocityGuidance::new(g, estimator, compensated)),
                    notes,
                ))
            }
            GuidanceLawKind::Acceleration => {
                let compensated = scenario.follower.model == FollowerModel::Aircraft;
                let law = AccelerationGuidance::new(&scenario.acceleration, g, compensated);
                notes.extend(law.observer_design().fallback_message());
                Ok((Self::Acceleration(law), notes))
            }
        }
    }

    /// Length of the law's state slice.
    pub fn state_len(&self) -> usize {
        match self {
            Self::Velocity(law) => law.state_len(),
            Self::Acceleration(law) => law.state_len(),
        }
    }

    /// Initial state with the filters started at the first measurement r(0).
    pub fn initial_state(&self, r0: &Vec3) -> Vec<f64> {
        match self {
            Self::Velocity(law) => law.initial_state(r0),
            Self::Acceleration(law) => law.initial_state(r0),
        }
    }

    /// Restarts the filters at the first measurement, keeping the parameter estimates.
    pub fn start_at(&self, x: &mut [f64], r0: &Vec3) {
        match self {
            Self::Velocity(law) => law.start_at(x, r0),
            Self::Acceleration(law) => law.start_at(x, r0),
        }
    }

    /// Before the first measurement: no state moves; the velocity law commands b̂(0) d̂(0),
    /// the acceleration law a_F = 0 (the follower keeps V_F(0)).
    pub fn idle(&self, x: &[f64], dx: &mut [f64]) -> GuidanceOutput {
        match self {
            Self::Velocity(law) => velocity_output(&law.idle(x, dx)),
            Self::Acceleration(law) => acceleration_output(law.idle(x, dx), Vec3::zeros()),
        }
    }

    /// Writes the law's ẋ into `dx` and returns its command.
    pub fn derivative(&self, x: &[f64], input: &GuidanceInput, dx: &mut [f64]) -> GuidanceOutput {
        match self {
            Self::Velocity(law) => velocity_output(&law.derivative(x, input, dx)),
            Self::Acceleration(law) => {
                // The observer's prediction is already in the law's (compensated) coordinates.
                let y_measured = input.r_measured.map_or_else(
                    || AccelerationGuidance::predicted_measurement(x),
                    |r| law.compensated_measurement(x, &r),
                );
                let measured = GuidanceInput {
                    r_measured: Some(y_measured),
                    ..*input
                };
                let out = law.derivative(x, &measured, dx);
                acceleration_output(out, out.y_observer - out.y_model)
            }
        }
    }

    /// Clamps b̂ and d̂ back into their projection bounds after a step.
    pub fn enforce_bounds(&self, x: &mut [f64]) {
        match self {
            Self::Velocity(law) => law.enforce_bounds(x),
            Self::Acceleration(law) => law.enforce_bounds(x),
        }
    }

    /// b̂ of a state slice, ft.
    pub fn b_hat_ft(&self, x: &[f64]) -> f64 {
        match self {
            Self::Velocity(_) => VelocityGuidance::b_hat_ft(x),
            Self::Acceleration(_) => AccelerationGuidance::b_hat_ft(x),
        }
    }

    /// The estimated scaled target velocity V_T/b (the velocity law's d̂, (4.1)); the
    /// acceleration law has no such estimate.
    pub fn scaled_target_velocity(&self, x: &[f64]) -> Option<Vec3> {
        match self {
            Self::Velocity(_) => Some(VelocityGuidance::d_hat(x)),
            Self::Acceleration(_) => None,
        }
    }

    /// d̂ of a state slice: the scaled target velocity in 1/s (velocity law, (4.5)) or the
    /// bound on the filtered target acceleration in ft/s (acceleration law, (5.41)).
    pub fn d_hat(&self, x: &[f64]) -> Vec3 {
        match self {
            Self::Velocity(_) => VelocityGuidance::d_hat(x),
            Self::Acceleration(_) => AccelerationGuidance::d_hat(x),
        }
    }
}

/// The velocity law's output as a [`GuidanceOutput`].
fn velocity_output(out: &VelocityGuidanceOutput) -> GuidanceOutput {
    GuidanceOutput {
        command: FollowerCommand::Velocity(out.velocity_cmd_ned_fps),
        r_command: out.r_command,
        error: out.error,
        estimated_error: out.estimated_error,
        acceleration: None,
    }
}

/// The acceleration law's output as a [`GuidanceOutput`]: its error is the combined output
/// y_a, its estimated error the one given.
fn acceleration_output(out: AccelerationGuidanceOutput, estimated_error: Vec3) -> GuidanceOutput {
    GuidanceOutput {
        command: FollowerCommand::Acceleration(out.accel_cmd_ned_fps2),
        r_command: out.y_command,
        error: out.y_combined,
        estimated_error,
        acceleration: Some(out),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::{AccelerationSection, ObserverGainMode};

    /// The law follows `[guidance] law`; a Riccati observer gain that falls back leaves a
    /// note for the log, as does a covariance estimator gain.
    #[test]
    fn builds_the_law_the_scenario_asks_for() {
        let mut scenario = Scenario::default();
        let (law, notes) = GuidanceLaw::from_scenario(&scenario).expect("builds");
        assert!(matches!(law, GuidanceLaw::Velocity(_)) && notes.is_empty());

        scenario.guidance.estimator = true;
        scenario.guidance.estimator_gain_mode = EstimatorGainMode::Covariance;
        let (law, notes) = GuidanceLaw::from_scenario(&scenario).expect("builds");
        assert_eq!(law.state_len(), 10);
        assert!(notes[0].contains("L_v"), "{notes:?}");

        scenario.guidance.law = GuidanceLawKind::Acceleration;
        scenario.acceleration = AccelerationSection {
            observer_gain_mode: ObserverGainMode::Riccati,
            riccati_process_psd: 1e-4,
            riccati_noise_psd: 1.0,
            ..AccelerationSection::default()
        };
        let (law, notes) = GuidanceLaw::from_scenario(&scenario).expect("builds");
        assert!(matches!(law, GuidanceLaw::Acceleration(_)));
        assert!(notes[0].contains("Riccati gain rejected"), "{notes:?}");
    }

    /// Before the first measurement the acceleration law commands a_F = 0, moves nothing, and
    /// still reports its signals (telemetry columns do not change when the camera's first
    /// frame arrives).
    #[test]
    fn acceleration_law_idles_with_its_signals() {
        let mut scenario = Scenario::default();
        scenario.guidance.law = GuidanceLawKind::Acceleration;
        let (law, _) = GuidanceLaw::from_scenario(&scenario).expect("builds");
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
        let mut scenario = Scenario::default();
        scenario.guidance.law = GuidanceLawKind::Acceleration;
        scenario.guidance.shaping_pole_rps = 0.0;
        let (law, _) = GuidanceLaw::from_scenario(&scenario).expect("builds");
        let r_c = Vec3::new(4.0, 1.0, 0.0);
        let mut x = law.initial_state(&r_c);
        x[crate::guidance::acceleration::layout::B_HAT] = 8.0;
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
