//! `[navigation]`: what the follower knows of its own state (docs/equations.md, The follower's
//! own navigation and sensors; `crate::navigation`). The INS/GPS keys live in `[navigation]`
//! itself, the air data in `[navigation.air_data]`, the camera's own geometry (mount, gimbal
//! encoders, exposure stamps) in `[navigation.camera]`. Each is `perfect` by default: the
//! follower then knows the truth, as in the seed.
//!
//! The defaults of every error are figures typical of a consumer-grade (MEMS) INS with a
//! standard-positioning-service GPS, for `mode = "ins_gps"`. A tactical-grade INS (ring-laser
//! or fibre-optic gyros, with the same GPS) is, typical of the class:
//! `gyro_bias_deg_per_h = 1`, `angle_random_walk_deg_per_sqrt_h = 0.1`,
//! `accel_bias_milli_g = 1`, `velocity_sigma_fps = 0.15`, `velocity_time_constant_s = 5`,
//! `attitude_sigma_deg = 0.05`, `heading_sigma_deg = 0.2`, `position_time_constant_s = 5`
//! (the GPS keys unchanged). The figures are "typical of the class", not of any one product.

use super::check::{self, Check};
use serde::{Deserialize, Serialize};

/// How the follower's navigation solution is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NavigationMode {
    /// The truth (the seed's assumption).
    Perfect,
    /// A loosely coupled INS/GPS: the truth plus the errors of the keys below, seeded from
    /// `run.seed` with a stream of its own.
    InsGps,
}

/// Whether a group of the follower's own sensors errs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SensorErrors {
    /// The sensors read the truth.
    Perfect,
    /// The stated noise and biases act (noise seeded from `run.seed`).
    Errors,
}

/// `[navigation]`: the INS/GPS error model. Defaults: consumer-grade MEMS INS with an SPS GPS
/// (see the module's comment for tactical grade).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NavigationSection {
    /// `perfect` (default) or `ins_gps`.
    pub mode: NavigationMode,
    /// σ of the GPS's slowly varying position error per horizontal axis, ft, in [0, 1000]
    /// (a first-order Gauss-Markov process). 6.6 ft (2 m): typical of an SPS receiver
    /// (2-3 m horizontal without augmentation).
    pub gps_position_sigma_ft: f64,
    /// Correlation time of that error, s, in [1, 1e5]. 300 s: ionospheric, tropospheric and
    /// orbit errors change over minutes.
    pub gps_correlation_time_s: f64,
    /// σ of each fix's white position noise per horizontal axis, ft, in [0, 1000]; held
    /// between fixes. 1.6 ft (0.5 m): receiver noise and fast multipath of the class.
    pub gps_noise_sigma_ft: f64,
    /// GPS fixes per second, Hz, in [0.1, 100]. 5 Hz: consumer receivers give 1-10 Hz.
    pub gps_rate_hz: f64,
    /// The vertical error's σ (both parts) over the horizontal's, in [0.5, 5]. 1.5: GPS
    /// geometry makes the vertical 1.5-2 times worse.
    pub gps_vertical_scale: f64,
    /// The INS/GPS filter's position time constant, s, in [0.01, 100]: the solution follows
    /// the GPS fixes through this lag and the INS velocity between them, so that it moves
    /// smoothly. 1 s for a consumer INS whose filter trusts the GPS.
    pub position_time_constant_s: f64,
    /// σ of the velocity error per axis, ft/s, in [0, 100] (GPS Doppler aided: a
    /// Gauss-Markov error). 0.33 ft/s (0.1 m/s): typical of the class.
    pub velocity_sigma_fps: f64,
    /// Correlation time of the velocity error, s, in [0.01, 1000], which is also the time
    /// over which the accelerometer bias enters the velocity before the aiding removes it.
    /// 2 s: a consumer filter weights the GPS velocity heavily.
    pub velocity_time_constant_s: f64,
    /// σ of each accelerometer's bias, milli-g, in [0, 100] (drawn per run, constant). It
    /// shifts the velocity error by b τ_v and tilts the level reference by b/g. 5 mg: typical
    /// of consumer MEMS accelerometers (1-10 mg).
    pub accel_bias_milli_g: f64,
    /// σ of each gyro's bias, deg/h, in [0, 10000] (drawn per run, constant): the attitude
    /// error drifts at it until the aiding bounds it. 10 deg/h: typical in-run bias of
    /// consumer MEMS gyros.
    pub gyro_bias_deg_per_h: f64,
    /// Each gyro's angle random walk, deg/√h, in [0, 100]. 0.3 deg/√h: typical of consumer
    /// MEMS gyros (0.1-0.5).
    pub angle_random_walk_deg_per_sqrt_h: f64,
    /// σ of the roll and pitch errors the gravity aiding leaves (its response to manoeuvres
    /// and vibration), deg, in [0, 30]. 0.5 deg: consumer AHRS accuracy in flight.
    pub attitude_sigma_deg: f64,
    /// Time constant of the gravity aiding of roll and pitch (and correlation time of their
    /// error), s, in [0.1, 1e5]. 30 s: a level loop slow enough not to follow manoeuvres.
    pub attitude_time_constant_s: f64,
    /// σ of the heading error the GPS-track aiding leaves, deg, in [0, 90]. 1 deg: a
    /// consumer INS without a magnetometer in steady flight.
    pub heading_sigma_deg: f64,
    /// Time constant of the GPS-track aiding of heading (and correlation time of its error),
    /// s, in [0.1, 1e6]: heading is observable only in manoeuvres, so it is slower than the
    /// level loop. 120 s.
    pub heading_time_constant_s: f64,
    /// The air data's errors.
    pub air_data: AirDataSection,
    /// The camera's own geometry errors.
    pub camera: CameraNavigationSection,
}

impl Default for NavigationSection {
    fn default() -> Self {
        Self {
            mode: NavigationMode::Perfect,
            gps_position_sigma_ft: 6.6,
            gps_correlation_time_s: 300.0,
            gps_noise_sigma_ft: 1.6,
            gps_rate_hz: 5.0,
            gps_vertical_scale: 1.5,
            position_time_constant_s: 1.0,
            velocity_sigma_fps: 0.33,
            velocity_time_constant_s: 2.0,
            accel_bias_milli_g: 5.0,
            gyro_bias_deg_per_h: 10.0,
            angle_random_walk_deg_per_sqrt_h: 0.3,
            attitude_sigma_deg: 0.5,
            attitude_time_constant_s: 30.0,
            heading_sigma_deg: 1.0,
            heading_time_constant_s: 120.0,
            air_data: AirDataSection::default(),
            camera: CameraNavigationSection::default(),
        }
    }
}

impl NavigationSection {
    /// Checks every value.
    pub fn validate(&self) -> Check {
        for (key, value, lo, hi) in [
            (
                "gps_position_sigma_ft",
                self.gps_position_sigma_ft,
                0.0,
                1000.0,
            ),
            (
                "gps_correlation_time_s",
                self.gps_correlation_time_s,
                1.0,
                1e5,
            ),
            ("gps_noise_sigma_ft", self.gps_noise_sigma_ft, 0.0, 1000.0),
            ("gps_rate_hz", self.gps_rate_hz, 0.1, 100.0),
            ("gps_vertical_scale", self.gps_vertical_scale, 0.5, 5.0),
            (
                "position_time_constant_s",
                self.position_time_constant_s,
                0.01,
                100.0,
            ),
            ("velocity_sigma_fps", self.velocity_sigma_fps, 0.0, 100.0),
            (
                "velocity_time_constant_s",
                self.velocity_time_constant_s,
                0.01,
                1000.0,
            ),
            ("accel_bias_milli_g", self.accel_bias_milli_g, 0.0, 100.0),
            (
                "gyro_bias_deg_per_h",
                self.gyro_bias_deg_per_h,
                0.0,
                10_000.0,
            ),
            (
                "angle_random_walk_deg_per_sqrt_h",
                self.angle_random_walk_deg_per_sqrt_h,
                0.0,
                100.0,
            ),
            ("attitude_sigma_deg", self.attitude_sigma_deg, 0.0, 30.0),
            (
                "attitude_time_constant_s",
                self.attitude_time_constant_s,
                0.1,
                1e5,
            ),
            ("heading_sigma_deg", self.heading_sigma_deg, 0.0, 90.0),
            (
                "heading_time_constant_s",
                self.heading_time_constant_s,
                0.1,
                1e6,
            ),
        ] {
            check::in_closed(&format!("navigation.{key}"), value, lo, hi)?;
        }
        self.air_data.validate()?;
        self.camera.validate()
    }
}

/// `[navigation.air_data]`: the pitot and vanes the autopilot's wind estimate is built from
/// (the wind is the navigated velocity less the air-relative velocity of V, α, β). Defaults
/// for `mode = "errors"`: typical of a small UAV's pitot-static probe and vanes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AirDataSection {
    /// `perfect` (default) or `errors`.
    pub mode: SensorErrors,
    /// Samples per second, Hz, in [1, 1000]; each sample's noise is held until the next.
    /// 50 Hz: a typical air-data computer's output rate.
    pub rate_hz: f64,
    /// σ of the airspeed's white noise, ft/s, in [0, 50]. 1 ft/s (0.3 m/s): a small pitot's
    /// differential-pressure noise at these speeds.
    pub airspeed_noise_fps: f64,
    /// The airspeed's bias (a calibration error, signed), ft/s, in [-50, 50]. 1 ft/s.
    pub airspeed_bias_fps: f64,
    /// σ of α's white noise, deg, in [0, 20]. 0.5 deg: a vane's resolution and flutter.
    pub alpha_noise_deg: f64,
    /// α's bias (the vane's alignment, signed), deg, in [-20, 20]. 1 deg.
    pub alpha_bias_deg: f64,
    /// σ of β's white noise, deg, in [0, 20]. 0.5 deg.
    pub beta_noise_deg: f64,
    /// β's bias, deg, in [-20, 20]. 0.5 deg.
    pub beta_bias_deg: f64,
}

impl Default for AirDataSection {
    fn default() -> Self {
        Self {
            mode: SensorErrors::Perfect,
            rate_hz: 50.0,
            airspeed_noise_fps: 1.0,
            airspeed_bias_fps: 1.0,
            alpha_noise_deg: 0.5,
            alpha_bias_deg: 1.0,
            beta_noise_deg: 0.5,
            beta_bias_deg: 0.5,
        }
    }
}

impl AirDataSection {
    /// Checks every value.
    pub fn validate(&self) -> Check {
        for (key, value, lo, hi) in [
            ("rate_hz", self.rate_hz, 1.0, 1000.0),
            ("airspeed_noise_fps", self.airspeed_noise_fps, 0.0, 50.0),
            ("airspeed_bias_fps", self.airspeed_bias_fps, -50.0, 50.0),
            ("alpha_noise_deg", self.alpha_noise_deg, 0.0, 20.0),
            ("alpha_bias_deg", self.alpha_bias_deg, -20.0, 20.0),
            ("beta_noise_deg", self.beta_noise_deg, 0.0, 20.0),
            ("beta_bias_deg", self.beta_bias_deg, -20.0, 20.0),
        ] {
            check::in_closed(&format!("navigation.air_data.{key}"), value, lo, hi)?;
        }
        Ok(())
    }
}

/// `[navigation.camera]`: what the follower gets wrong about its camera. Defaults for
/// `mode = "errors"`: typical of a small UAV's pan/tilt payload.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CameraNavigationSection {
    /// `perfect` (default) or `errors`.
    pub mode: SensorErrors,
    /// The camera's true mount turned from its nominal one by [roll, pitch, yaw] (3-2-1
    /// about the camera's nominal axes), deg, each in [-10, 10]: the renderer draws with the
    /// true mount, the sensing transform and the pointing law use the nominal. 0.5 deg each:
    /// a mount fitted without a boresight calibration.
    pub mount_misalignment_deg: [f64; 3],
    /// σ of each gimbal encoder's white noise, deg, in [0, 10], a new reading every tick.
    /// 0.03 deg: a 12-bit encoder's quantisation (0.088 deg / √12).
    pub gimbal_encoder_noise_deg: f64,
    /// Each gimbal encoder's bias [pan, tilt] (its zero, signed), deg, each in [-10, 10].
    /// 0.2 deg: an index found by a limit switch.
    pub gimbal_encoder_bias_deg: [f64; 2],
    /// σ of the exposure timestamp's jitter, ms, in [0, 100]: the frame is taken at the true
    /// time and stamped at the jittered one. 5 ms: software stamping of a USB camera.
    pub exposure_jitter_ms: f64,
}

impl Default for CameraNavigationSection {
    fn default() -> Self {
        Self {
            mode: SensorErrors::Perfect,
            mount_misalignment_deg: [0.5, 0.5, 0.5],
            gimbal_encoder_noise_deg: 0.03,
            gimbal_encoder_bias_deg: [0.2, 0.2],
            exposure_jitter_ms: 5.0,
        }
    }
}

impl CameraNavigationSection {
    /// Checks every value.
    pub fn validate(&self) -> Check {
        let within =
            |values: &[f64], bound: f64| values.iter().all(|v| v.is_finite() && v.abs() <= bound);
        check::require(
            within(&self.mount_misalignment_deg, 10.0),
            "navigation.camera.mount_misalignment_deg",
            format!("{:?}", self.mount_misalignment_deg),
            "three angles in [-10, 10]",
        )?;
        check::require(
            within(&self.gimbal_encoder_bias_deg, 10.0),
            "navigation.camera.gimbal_encoder_bias_deg",
            format!("{:?}", self.gimbal_encoder_bias_deg),
            "two angles in [-10, 10]",
        )?;
        check::in_closed(
            "navigation.camera.gimbal_encoder_noise_deg",
            self.gimbal_encoder_noise_deg,
            0.0,
            10.0,
        )?;
        check::in_closed(
            "navigation.camera.exposure_jitter_ms",
            self.exposure_jitter_ms,
            0.0,
            100.0,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every default is perfect and valid; a bad value names its key and range.
    #[test]
    fn defaults_are_perfect_and_bad_values_name_their_key() {
        let n = NavigationSection::default();
        assert_eq!(n.mode, NavigationMode::Perfect);
        assert_eq!(n.air_data.mode, SensorErrors::Perfect);
        assert_eq!(n.camera.mode, SensorErrors::Perfect);
        n.validate().expect("defaults are valid");
        let bad = NavigationSection {
            gps_rate_hz: 0.0,
            ..n.clone()
        };
        let e = bad.validate().unwrap_err();
        assert_eq!(e.key, "navigation.gps_rate_hz");
        assert_eq!(e.allowed, "[0.1, 100]");
        let mut bad = n;
        bad.camera.mount_misalignment_deg[1] = f64::NAN;
        let e = bad.validate().unwrap_err();
        assert_eq!(e.key, "navigation.camera.mount_misalignment_deg");
    }
}
