//! What the follower gets wrong about its camera (`[navigation.camera] mode = "errors"`;
//! docs/equations.md, The follower's own navigation and sensors): the mount is turned from its
//! nominal orientation by a fixed misalignment the sensing transform does not know; each
//! gimbal encoder reads its angle plus a fixed bias and white noise drawn every tick (a roll
//! axis' encoder, where the gimbal has one, with the pan encoder's bias and noise); each
//! frame is stamped at its exposure time plus white jitter.

use crate::frames::{EulerAngles, Mat3};
use crate::scenario::CameraNavigationSection;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

/// The camera's geometry errors of one run.
#[derive(Debug, Clone)]
pub struct CameraGeometryErrors {
    rng: ChaCha8Rng,
    /// The true camera axes from the nominal ones.
    true_from_nominal: Mat3,
    /// Encoder biases [pan, tilt, roll], rad (the roll's 0 without a roll axis).
    encoder_bias_rad: [f64; 3],
    /// Whether the gimbal has a roll axis, whose encoder draws its noise too.
    roll_axis: bool,
    encoder_noise_rad: f64,
    jitter_s: f64,
    /// What the encoders read above the truth now [pan, tilt, roll], rad.
    encoder_error_rad: [f64; 3],
}

impl CameraGeometryErrors {
    /// The errors `section` states for a gimbal with a roll axis or without (`roll_axis`), the
    /// noise drawn from `seed`.
    pub fn new(section: &CameraNavigationSection, roll_axis: bool, seed: u64) -> Self {
        let [roll, pitch, yaw] = section.mount_misalignment_deg.map(f64::to_radians);
        let mut errors = Self {
            rng: ChaCha8Rng::seed_from_u64(seed),
            true_from_nominal: EulerAngles::new(roll, pitch, yaw).body_from_ned(),
            encoder_bias_rad: {
                let [pan, tilt] = section.gimbal_encoder_bias_deg.map(f64::to_radians);
                [pan, tilt, if roll_axis { pan } else { 0.0 }]
            },
            roll_axis,
            encoder_noise_rad: section.gimbal_encoder_noise_deg.to_radians(),
            jitter_s: section.exposure_jitter_ms * 1e-3,
            encoder_error_rad: [0.0; 3],
        };
        errors.advance();
        errors
    }

    /// A new encoder reading (every tick).
    pub fn advance(&mut self) {
        let axes = if self.roll_axis { 3 } else { 2 };
        for axis in 0..axes {
            let n: f64 = self.rng.sample(StandardNormal);
            self.encoder_error_rad[axis] = self.encoder_bias_rad[axis] + self.encoder_noise_rad * n;
        }
    }

    /// The true mount L_CB from the nominal one the follower believes in.
    pub fn true_mount(&self, nominal: &Mat3) -> Mat3 {
        self.true_from_nominal * nominal
    }

    /// What the encoders read above the true [pan, tilt, roll] now, rad.
    pub fn encoder_error_rad(&self) -> [f64; 3] {
        self.encoder_error_rad
    }

    /// The stamp of a frame exposed at `t_s`: the true time plus a jitter draw, s.
    pub fn stamp_s(&mut self, t_s: f64) -> f64 {
        let n: f64 = self.rng.sample(StandardNormal);
        t_s + self.jitter_s * n
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::Vec3;

    /// A yaw misalignment turns the camera's axes about its z: a point straight ahead in
    /// the true camera lies off the nominal axis by the misalignment.
    #[test]
    fn a_yaw_misalignment_turns_the_camera() {
        let section = CameraNavigationSection {
            mount_misalignment_deg: [0.0, 0.0, 2.0],
            ..CameraNavigationSection::default()
        };
        let errors = CameraGeometryErrors::new(&section, false, 1);
        let true_mount = errors.true_mount(&Mat3::identity());
        let ahead_in_body = true_mount.transpose() * Vec3::new(1.0, 0.0, 0.0);
        let bearing_deg = ahead_in_body.y.atan2(ahead_in_body.x).to_degrees();
        assert!((bearing_deg - 2.0).abs() < 1e-12, "{bearing_deg}");
    }
}
