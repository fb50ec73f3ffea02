//! Which figures a run draws and which seed figures their titles cite, decided once from the
//! run's modes (law, mission, sensor, estimator, follower) by [`FigureSet::of`]: the one place
//! that pairs modes with plots; [`super::figures`] draws what the set says.

use crate::scenario::{FollowerModel, GuidanceLawKind, Mission, NoiseOn, Scenario, SensorMode};
use crate::sim::Snapshot;

/// The seed figure numbers a run's panels reproduce, for the titles.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FigureNumbers {
    /// `relative_position.png`.
    pub relative: &'static str,
    /// `parameter_estimates.png`.
    pub estimates: &'static str,
    /// `velocity.png`.
    pub velocity: &'static str,
    /// `acceleration.png`.
    pub acceleration: &'static str,
}

/// What `parameter_estimates.png` shows beside b̂: the law's estimate of the target's motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotionEstimate {
    /// b̂ d̂ against V_T (velocity law).
    ScaledVelocity,
    /// ‖d̂‖ (acceleration law).
    AccelerationBound,
}

/// The figures one run draws. Every run draws `relative_position.png`,
/// `parameter_estimates.png` and `velocity.png`.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureSet {
    /// The seed figures the titles cite.
    pub numbers: FigureNumbers,
    /// The second part of `parameter_estimates.png`.
    pub motion_estimate: MotionEstimate,
    /// `acceleration.png` and `target_acceleration.png` (acceleration law); true: a_F's 1 s
    /// moving mean beside it (a sensor with noise).
    pub acceleration: Option<bool>,
    /// `measurement.png` (noisy sensor), with the noise as its title says it.
    pub measurement: Option<String>,
    /// `size_estimate.png` (a Kalman filter in the telemetry), with the focal length, px, for
    /// the size each frame's silhouette implies (camera runs).
    pub size: Option<Option<f64>>,
    /// The 6-DOF follower's figures (aircraft in the telemetry).
    pub aircraft: bool,
}

impl FigureSet {
    /// The figures `scenario`'s run draws from its telemetry `logged`.
    pub fn of(scenario: &Scenario, logged: &[Snapshot]) -> Self {
        let law = scenario.guidance.law;
        let sensor = &scenario.sensor;
        let measurement = (sensor.mode == SensorMode::Noisy).then(|| match sensor.noise_on {
            NoiseOn::ScaledPosition => format!("SNR {} dB", sensor.snr_db),
            NoiseOn::Pixels => format!("pixel noise {:?} px", sensor.pixel_noise_px),
        });
        let focal_px =
            (sensor.mode == SensorMode::Camera).then(|| scenario.camera.focal_length_px());
        Self {
            numbers: FigureNumbers::of(scenario),
            motion_estimate: match law {
                GuidanceLawKind::Velocity => MotionEstimate::ScaledVelocity,
                GuidanceLawKind::Acceleration => MotionEstimate::AccelerationBound,
            },
            acceleration: (law == GuidanceLawKind::Acceleration)
                .then_some(sensor.mode != SensorMode::Perfect),
            measurement,
            size: logged
                .iter()
                .any(|s| s.filter.is_present())
                .then_some(focal_px),
            aircraft: logged.iter().any(|s| s.aircraft.is_some()),
        }
    }
}

impl FigureNumbers {
    fn of(scenario: &Scenario) -> Self {
        let numbers = |relative, estimates, velocity, acceleration| Self {
            relative,
            estimates,
            velocity,
            acceleration,
        };
        if scenario.follower.model == FollowerModel::Aircraft {
            let ch7 = "seed Ch 7";
            return numbers("seed Ch 7, Figs 7.1-7.13", ch7, ch7, ch7);
        }
        let noisy = scenario.sensor.mode == SensorMode::Noisy;
        let intercept = scenario.guidance.mission == Mission::Intercept;
        let none = "no seed figure";
        match (scenario.guidance.law, noisy) {
            (GuidanceLawKind::Acceleration, _) if intercept => {
                numbers("Remark 6, no seed figure", "Remark 6", none, "Remark 6")
            }
            (GuidanceLawKind::Acceleration, false) => {
                numbers("seed Fig 5.3", "seed Fig 5.4", none, "seed Fig 5.2")
            }
            (GuidanceLawKind::Acceleration, true) => {
                numbers("seed Fig 6.8", "seed Fig 6.9", none, "seed Fig 6.7")
            }
            (GuidanceLawKind::Velocity, true) => {
                numbers("seed Fig 6.5", "seed Fig 6.6", "seed Fig 6.4", "")
            }
            (GuidanceLawKind::Velocity, false)
                if scenario.guidance.estimator && scenario.sensor.mode == SensorMode::Perfect =>
            {
                numbers("seed Fig 6.2", "seed Fig 6.3", "seed Fig 6.1", "")
            }
            (GuidanceLawKind::Velocity, false) => numbers(
                "seed Fig 4.3 / 4.6",
                "seed Fig 4.4",
                "seed Fig 4.5 / 4.7",
                "",
            ),
        }
    }
}
