//! The sensor stage (`docs/design.md`, One tick; `[sensor] mode`): what the follower measures of the target.
//!
//! - `perfect`: r = R/b exactly, at every instant (seed Chapters 4-5).
//! - `noisy`: r* = r + noise, or noise on (yI, zI, bI), drawn every sample period and held
//!   ([`noisy`], seed Chapter 6).
//! - `camera`: the target rendered as the follower's camera sees it and measured by the image
//!   pipeline, every frame, delivered after its latency ([`camera`]).
//!
//! All three go through the sensing transform (3.3)-(3.12) of [`transform`] (the perfect and
//! noisy sensors in its exact form). The perfect and noisy sensors are continuous: the
//! simulation evaluates them at every integration stage. The camera delivers frames.
//!
//! Each sensor is built from its own configuration ([`config`]), derived from the scenario in
//! one place. What the sensors are given at an instant is a [`CaptureGeometry`]: the truth the
//! camera images and the follower's navigation solution ([`FollowerPose`]) that measurements
//! are turned with ([`geometry`]).

pub mod binning;
pub mod camera;
pub mod config;
pub mod geometry;
pub mod gimbal;
pub mod losses;
pub mod noisy;
pub mod transform;

pub use camera::{CameraSensor, FrameRecord, SensorError};
pub use config::{CameraConfig, NoisyConfig, SensorConfig};
pub use geometry::{CaptureGeometry, FollowerPose, OtherAircraft, TargetExpectation};
pub use noisy::NoisySensor;
pub use transform::{
    bearing_elevation_rad, image_from_relative_position, line_of_sight_body,
    scaled_position_jacobian, scaled_relative_position,
};

use crate::frames::{Mat3, Vec3};
use crate::render::GpuContext;
use crate::scenario::SensorMode;

/// The sensor of a run.
#[derive(Debug)]
pub enum Sensor {
    /// r = R/b, the target's true size b in ft.
    Perfect {
        /// b, ft.
        size_ft: f64,
    },
    /// r* with held noise.
    Noisy(Box<NoisySensor>),
    /// The camera in the loop.
    Camera(Box<CameraSensor>),
}

impl Sensor {
    /// The sensor `config` describes. A camera renders on `gpu` when given, on a device of
    /// its own otherwise.
    pub fn new(config: &SensorConfig, gpu: Option<&GpuContext>) -> Result<Self, SensorError> {
        Ok(match config.mode {
            SensorMode::Perfect => Self::Perfect {
                size_ft: config.target_size_ft,
            },
            SensorMode::Noisy => Self::Noisy(Box::new(NoisySensor::new(&config.noisy))),
            SensorMode::Camera => Self::Camera(Box::new(match gpu {
                Some(gpu) => CameraSensor::on_gpu(&config.camera, gpu)?,
                None => CameraSensor::new(&config.camera)?,
            })),
        })
    }

    /// Whether the sensor measures at every instant (perfect, noisy) rather than at frames.
    pub fn is_continuous(&self) -> bool {
        !matches!(self, Self::Camera(_))
    }

    /// r at an instant with relative position R (NED, ft) and the camera's L_CB L_BE as the
    /// follower's navigation knows it, for the continuous sensors (the noisy one with its held noise); `None` when the noisy sensor's
    /// target is not in front of the camera, and always for the camera, which measures at
    /// frames only.
    pub fn continuous_measurement(
        &self,
        relative_ned_ft: &Vec3,
        body_from_ned: &Mat3,
    ) -> Option<Vec3> {
        match self {
            Self::Perfect { size_ft } => Some(relative_ned_ft / *size_ft),
            Self::Noisy(sensor) => sensor.measure(relative_ned_ft, body_from_ned),
            Self::Camera(_) => None,
        }
    }

    /// Whether a continuous sensor takes a new, independent sample at this tick (the noisy
    /// sensor's sample period; every tick for the perfect one); never for the camera, whose
    /// frames are delivered.
    pub fn is_sample_tick(&self, tick: u64) -> bool {
        match self {
            Self::Perfect { .. } => true,
            Self::Noisy(sensor) => sensor.is_sample_tick(tick),
            Self::Camera(_) => false,
        }
    }

    /// Whether the camera takes a frame at this tick (never for a continuous sensor).
    pub fn is_frame_tick(&self, tick: u64) -> bool {
        matches!(self, Self::Camera(camera) if camera.is_frame_tick(tick))
    }

    /// The per-axis variance of a continuous sensor's measurement r* (scaled units²), from
    /// the measurement itself and the follower's attitude, not from the truth: zero for the
    /// perfect sensor, the noisy sensor's own.
    pub fn continuous_variance(&self, r_star: &Vec3, body_from_ned: &Mat3) -> f64 {
        match self {
            Self::Noisy(sensor) => sensor.variance(r_star, body_from_ned),
            Self::Perfect { .. } | Self::Camera(_) => 0.0,
        }
    }

    /// Acts at the start of tick `tick` in the geometry then: the noisy sensor draws its next
    /// sample when one is due (tick 0's is drawn at set-up, see
    /// [`Self::draw_initial_noise`]); the camera takes a frame when one is due and returns
    /// the record the guidance holds from now on.
    pub fn sample(
        &mut self,
        tick: u64,
        t_s: f64,
        geometry: &CaptureGeometry,
    ) -> Result<Option<FrameRecord>, SensorError> {
        match self {
            Self::Perfect { .. } => Ok(None),
            Self::Noisy(sensor) => {
                if tick > 0 && sensor.is_sample_tick(tick) {
                    let body_from_ned = geometry.camera_from_ned();
                    sensor.draw(&geometry.relative_ned_ft, &body_from_ned);
                }
                Ok(None)
            }
            Self::Camera(camera) if camera.is_frame_tick(tick) => camera.capture(t_s, geometry),
            Self::Camera(_) => Ok(None),
        }
    }

    /// Draws the noisy sensor's first sample, for the measurement the filters start at.
    pub fn draw_initial_noise(&mut self, geometry: &CaptureGeometry) {
        if let Self::Noisy(sensor) = self {
            let body_from_ned = geometry.camera_from_ned();
            sensor.draw(&geometry.relative_ned_ft, &body_from_ned);
        }
    }

    /// The camera, in camera runs.
    pub fn camera(&self) -> Option<&CameraSensor> {
        match self {
            Self::Camera(camera) => Some(camera),
            _ => None,
        }
    }

    /// The camera, in camera runs, to change what it draws.
    pub fn camera_mut(&mut self) -> Option<&mut CameraSensor> {
        match self {
            Self::Camera(camera) => Some(camera),
            _ => None,
        }
    }

    /// The noisy sensor, in noisy runs.
    pub fn noisy(&self) -> Option<&NoisySensor> {
        match self {
            Self::Noisy(sensor) => Some(sensor),
            _ => None,
        }
    }
}
