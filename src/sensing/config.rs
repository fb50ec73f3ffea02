//! What each sensor is built from: the sections of the scenario it reads and the facts of the
//! run it needs, derived from a scenario in one place ([`SensorConfig::of`]) so that the
//! sensors themselves never see the whole scenario.

use crate::scenario::{CameraSection, Scenario, SceneSection, SensorMode, SensorSection};

/// The camera's configuration.
#[derive(Debug, Clone, Copy)]
pub struct CameraConfig<'a> {
    /// `[camera]`: image, optics, pipeline, mesh path, latency.
    pub camera: &'a CameraSection,
    /// The target's true size b, ft (the mesh is scaled to it).
    pub target_size_ft: f64,
    /// The run's seed (pixel noise).
    pub seed: u64,
    /// The integration step, s (the frame period is a whole number of them).
    pub dt_s: f64,
    /// Frames whose index is a multiple of this are saved, so drawn whole (0: none).
    pub frames_every: u32,
    /// `[scene]`: the world behind the target.
    pub scene: &'a SceneSection,
    /// The follower's start's NED down coordinate, ft (the scene's heights refer to it).
    pub start_down_ft: f64,
}

impl<'a> CameraConfig<'a> {
    /// The camera a scenario describes.
    pub fn of(scenario: &'a Scenario) -> Self {
        Self {
            camera: &scenario.camera,
            target_size_ft: scenario.target.size_ft,
            seed: scenario.run.seed,
            dt_s: scenario.run.dt_s,
            frames_every: scenario.output.frames_every,
            scene: &scenario.scene,
            start_down_ft: scenario.follower.initial_position_ft[2],
        }
    }
}

/// The noisy sensor's configuration.
#[derive(Debug, Clone, Copy)]
pub struct NoisyConfig<'a> {
    /// `[sensor]`: where the noise goes, its level and sample period.
    pub sensor: &'a SensorSection,
    /// The focal length of the camera whose pixels are noisy, px.
    pub focal_px: f64,
    /// The target's true size b, ft (the sensor sees the truth).
    pub target_size_ft: f64,
    /// The run's seed (the noise stream).
    pub seed: u64,
    /// The integration step, s (the sample period is a whole number of them).
    pub dt_s: f64,
    /// ‖R_c‖, ft: the formation command the SNR may refer to (`snr_reference = "command"`).
    pub command_norm_ft: f64,
}

impl<'a> NoisyConfig<'a> {
    /// The noisy sensor a scenario describes, its SNR referred to a command of length
    /// `command_norm_ft`.
    pub fn of(scenario: &'a Scenario, command_norm_ft: f64) -> Self {
        Self {
            sensor: &scenario.sensor,
            focal_px: scenario.camera.focal_length_px(),
            target_size_ft: scenario.target.size_ft,
            seed: scenario.run.seed,
            dt_s: scenario.run.dt_s,
            command_norm_ft,
        }
    }
}

/// The sensor stage's configuration: which sensor, and what each is built from.
#[derive(Debug, Clone, Copy)]
pub struct SensorConfig<'a> {
    /// `[sensor] mode`.
    pub mode: SensorMode,
    /// The target's true size b, ft (the perfect sensor's r = R/b).
    pub target_size_ft: f64,
    /// The noisy sensor's configuration.
    pub noisy: NoisyConfig<'a>,
    /// The camera's configuration.
    pub camera: CameraConfig<'a>,
}

impl<'a> SensorConfig<'a> {
    /// The sensor stage a scenario describes; `command_norm_ft` is the length of the formation
    /// command a noisy sensor may refer its SNR to.
    pub fn of(scenario: &'a Scenario, command_norm_ft: f64) -> Self {
        Self {
            mode: scenario.sensor.mode,
            target_size_ft: scenario.target.size_ft,
            noisy: NoisyConfig::of(scenario, command_norm_ft),
            camera: CameraConfig::of(scenario),
        }
    }
}
