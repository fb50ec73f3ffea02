//! The `noisy` sensor of the seed's Chapter 6 (`docs/equations.md`, Noisy measurements): the perfect measurement with white
//! noise, r* = r + n_r (6.8), or noise on the image measurements (yI, zI, bI) propagated
//! through the sensing transform (6.1)-(6.3).
//!
//! Noise model: a zero-mean Gaussian sample is drawn from the run's one seeded RNG
//! (`[run] seed`, ChaCha8) every `sensor.sample_period_s` (every tick by default) and held
//! until the next one: band-limited white noise of intensity σ² T_s. The noise-free part is
//! evaluated continuously, at every integration stage, as the `perfect` sensor does, so with
//! zero noise this sensor is the perfect one.
//!
//! SNR (noise on r): per axis, σ² = P_r / 10^(SNR/10) with P_r the signal's power per axis,
//! either the instantaneous ‖r‖²/3 of the noise-free r at the sampling instant (`signal`: each
//! sample has the stated SNR, and the noise grows with the range as a camera's does), or the
//! commanded ‖R_c‖²/(3 b²) (`command`: one level for the run). Either way
//! SNR = 10 log10(E‖r‖² / E‖n_r‖²) in dB; the run reports the SNR it realised.

use super::config::NoisyConfig;
use super::transform::{
    image_from_relative_position, scaled_position_jacobian, scaled_relative_position,
};
use crate::frames::{Mat3, Vec3};
use crate::scenario::{NoiseOn, SnrReference};
use crate::vision::ImageMeasurement;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

/// The noise held between samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HeldNoise {
    /// n_r, added to r (scaled units).
    Scaled(Vec3),
    /// (n_y, n_z, n_b), added to (yI, zI, bI), px.
    Pixels(ImageMeasurement),
}

/// The noisy sensor stage.
#[derive(Debug, Clone)]
pub struct NoisySensor {
    noise_on: NoiseOn,
    snr_reference: SnrReference,
    /// 10^(SNR/10).
    snr_ratio: f64,
    /// ‖R_c‖² / (3 b²): the per-axis power of the commanded r_c.
    command_power: f64,
    pixel_sigma_px: [f64; 3],
    focal_px: f64,
    /// The target's true size b, ft (the sensor sees the truth).
    size_ft: f64,
    period_ticks: u64,
    rng: ChaCha8Rng,
    held: HeldNoise,
    /// Σ ‖r‖² and Σ ‖n_r‖² over the samples drawn so far.
    signal_energy: f64,
    noise_energy: f64,
}

impl NoisySensor {
    /// The sensor `config` describes (seeded from the run's seed), measuring a target of the
    /// true size through a camera of the configured focal length (pixel noise) and referring
    /// the SNR to the configured command length (`snr_reference = "command"`).
    pub fn new(config: &NoisyConfig) -> Self {
        let sensor = config.sensor;
        let size_ft = config.target_size_ft;
        Self {
            noise_on: sensor.noise_on,
            snr_reference: sensor.snr_reference,
            snr_ratio: 10f64.powf(sensor.snr_db / 10.0),
            command_power: (config.command_norm_ft / size_ft).powi(2) / 3.0,
            pixel_sigma_px: sensor.pixel_noise_px,
            focal_px: config.focal_px,
            size_ft,
            period_ticks: sensor.sample_period_ticks(config.dt_s),
            rng: ChaCha8Rng::seed_from_u64(config.seed),
            held: match sensor.noise_on {
                NoiseOn::ScaledPosition => HeldNoise::Scaled(Vec3::zeros()),
                NoiseOn::Pixels => HeldNoise::Pixels(ImageMeasurement::default()),
            },
            signal_energy: 0.0,
            noise_energy: 0.0,
        }
    }

    /// Whether a new sample is due at this tick.
    pub fn is_sample_tick(&self, tick: u64) -> bool {
        tick.is_multiple_of(self.period_ticks)
    }

    /// The noise held now.
    pub fn held(&self) -> HeldNoise {
        self.held
    }

    /// Per-axis standard deviation of n_r for a noise-free r (noise on r).
    pub fn scaled_sigma(&self, r: &Vec3) -> f64 {
        let power = match self.snr_reference {
            SnrReference::Signal => r.norm_squared() / 3.0,
            SnrReference::Command => self.command_power,
        };
        (power / self.snr_ratio).sqrt()
    }

    fn standard_normal_vec(&mut self) -> Vec3 {
        let mut draw = || -> f64 { self.rng.sample(StandardNormal) };
        let (a, b, c) = (draw(), draw(), draw());
        Vec3::new(a, b, c)
    }

    /// Draws the next sample for the geometry at the sampling instant (R = R_T - R_F and the
    /// follower's L_BE) and holds it.
    pub fn draw(&mut self, relative_ned_ft: &Vec3, body_from_ned: &Mat3) {
        let unit = self.standard_normal_vec();
        let r = relative_ned_ft / self.size_ft;
        self.held = match self.noise_on {
            NoiseOn::ScaledPosition => HeldNoise::Scaled(unit * self.scaled_sigma(&r)),
            NoiseOn::Pixels => {
                let [sy, sz, sb] = self.pixel_sigma_px;
                HeldNoise::Pixels(ImageMeasurement {
                    y_i_px: unit.x * sy,
                    z_i_px: unit.y * sz,
                    b_i_px: unit.z * sb,
                })
            }
        };
        if let Some(r_star) = self.measure(relative_ned_ft, body_from_ned) {
            self.signal_energy += r.norm_squared();
            self.noise_energy += (r_star - r).norm_squared();
        }
    }

    /// r* for the geometry now with the held noise; `None` when the target is not in front of
    /// the camera or its noisy length is not positive (pixel noise only).
    pub fn measure(&self, relative_ned_ft: &Vec3, body_from_ned: &Mat3) -> Option<Vec3> {
        match self.held {
            HeldNoise::Scaled(n) => Some(relative_ned_ft / self.size_ft + n),
            HeldNoise::Pixels(n) => {
                let image = image_from_relative_position(
                    relative_ned_ft,
                    body_from_ned,
                    self.size_ft,
                    self.focal_px,
                )?;
                let noisy = ImageMeasurement {
                    y_i_px: image.y_i_px + n.y_i_px,
                    z_i_px: image.z_i_px + n.z_i_px,
                    b_i_px: image.b_i_px + n.b_i_px,
                };
                (noisy.b_i_px > 0.0)
                    .then(|| scaled_relative_position(&noisy, self.focal_px, body_from_ned))
            }
        }
    }

    /// The per-axis variance of a measurement r* taken with the follower at `body_from_ned`,
    /// scaled units²: σ² of the noise on r (its power from r* where the SNR refers to the
    /// signal), or the mean diagonal of J Σ Jᵀ for noise on the pixels (J the sensing
    /// transform's Jacobian at the image r* implies). A filter knows r*, not R and b, so the
    /// variance is computed from what it knows.
    pub fn variance(&self, r_star: &Vec3, body_from_ned: &Mat3) -> f64 {
        match self.noise_on {
            NoiseOn::ScaledPosition => self.scaled_sigma(r_star).powi(2),
            NoiseOn::Pixels => {
                // The image of r* seen as a target of size 1 at R = r*: b cancels in (3.12),
                // so the variance needs neither the true range nor the true size.
                let Some(image) =
                    image_from_relative_position(r_star, body_from_ned, 1.0, self.focal_px)
                else {
                    return f64::INFINITY;
                };
                let j = scaled_position_jacobian(&image, self.focal_px, &body_from_ned.transpose());
                let [sy, sz, sb] = self.pixel_sigma_px;
                let sigma = Mat3::from_diagonal(&Vec3::new(sy * sy, sz * sz, sb * sb));
                (j * sigma * j.transpose()).trace() / 3.0
            }
        }
    }

    /// The SNR realised over the samples drawn so far, 10 log10(Σ‖r‖² / Σ‖n_r‖²), dB (None
    /// before a sample or without noise).
    pub fn realised_snr_db(&self) -> Option<f64> {
        (self.noise_energy > 0.0).then(|| 10.0 * (self.signal_energy / self.noise_energy).log10())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::EulerAngles;
    use crate::scenario::{Scenario, SensorMode};

    /// ‖[32, 8, 0]‖ ft, the seed's formation command.
    const SEED_COMMAND_FT: f64 = 32.984845004941285;

    fn sensor(scenario: &Scenario) -> NoisySensor {
        NoisySensor::new(&NoisyConfig::of(scenario, SEED_COMMAND_FT))
    }

    fn scenario(noise_on: NoiseOn, reference: SnrReference) -> Scenario {
        let mut s = Scenario::default();
        s.sensor.mode = SensorMode::Noisy;
        s.sensor.noise_on = noise_on;
        s.sensor.snr_reference = reference;
        s
    }

    /// Over many samples the realised SNR is the stated one (25 dB) for both references: the
    /// mean of ‖n‖² over 20 000 samples has a relative standard error of 0.6%, 0.03 dB, so
    /// 0.15 dB is five of them.
    #[test]
    fn realised_snr_is_the_stated_one() {
        for reference in [SnrReference::Signal, SnrReference::Command] {
            let mut sensor = sensor(&scenario(NoiseOn::ScaledPosition, reference));
            let relative = Vec3::new(32.0, 8.0, 0.0);
            for _ in 0..20_000 {
                sensor.draw(&relative, &Mat3::identity());
            }
            let snr = sensor.realised_snr_db().expect("noise drawn");
            assert!((snr - 25.0).abs() < 0.15, "{reference:?}: {snr} dB");
        }
    }

    /// Signal reference: σ scales with ‖r‖; command reference: it does not.
    #[test]
    fn sigma_follows_its_reference() {
        let signal = sensor(&scenario(NoiseOn::ScaledPosition, SnrReference::Signal));
        let command = sensor(&scenario(NoiseOn::ScaledPosition, SnrReference::Command));
        let r_c = Vec3::new(4.0, 1.0, 0.0);
        let expected = (r_c.norm_squared() / 3.0 / 10f64.powf(2.5)).sqrt();
        assert!((signal.scaled_sigma(&r_c) - expected).abs() < 1e-15);
        assert!((command.scaled_sigma(&r_c) - expected).abs() < 1e-15);
        assert!((signal.scaled_sigma(&(r_c * 5.0)) - 5.0 * expected).abs() < 1e-14);
        assert_eq!(
            command.scaled_sigma(&(r_c * 5.0)),
            command.scaled_sigma(&r_c)
        );
    }

    /// The variance a filter is given depends on the measurement r* and the attitude only:
    /// targets of 4 and 8 ft give the same variance for the same r*, and for noise on the
    /// pixels it is the pixel noise mapped through the Jacobian at the image r* implies (the
    /// image of an 8 ft target at R = 8 r*).
    #[test]
    fn variance_is_computed_from_the_measurement_not_the_truth() {
        let r_star = Vec3::new(4.0, 1.0, -0.5);
        let attitude = EulerAngles::new(0.1, -0.05, 0.2).body_from_ned();
        for noise_on in [NoiseOn::ScaledPosition, NoiseOn::Pixels] {
            let mut small = scenario(noise_on, SnrReference::Signal);
            small.target.size_ft = 4.0;
            let large = scenario(noise_on, SnrReference::Signal);
            let (small, large) = (sensor(&small), sensor(&large));
            let v = large.variance(&r_star, &attitude);
            assert!(v.is_finite() && v > 0.0, "{noise_on:?}: {v}");
            assert_eq!(small.variance(&r_star, &attitude), v, "{noise_on:?}");
        }
        let pixels = sensor(&scenario(NoiseOn::Pixels, SnrReference::Signal));
        let image = image_from_relative_position(&(r_star * 8.0), &attitude, 8.0, pixels.focal_px)
            .expect("in front");
        let j = scaled_position_jacobian(&image, pixels.focal_px, &attitude.transpose());
        let [sy, sz, sb] = pixels.pixel_sigma_px;
        let sigma = Mat3::from_diagonal(&Vec3::new(sy * sy, sz * sz, sb * sb));
        let expected = (j * sigma * j.transpose()).trace() / 3.0;
        let v = pixels.variance(&r_star, &attitude);
        assert!(
            (v - expected).abs() <= 1e-12 * expected,
            "{v} vs {expected}"
        );
    }

    /// Same seed, same noise; another seed, other noise.
    #[test]
    fn noise_is_deterministic_per_seed() {
        let draws = |seed: u64| {
            let mut s = scenario(NoiseOn::ScaledPosition, SnrReference::Signal);
            s.run.seed = seed;
            let mut sensor = sensor(&s);
            (0..5)
                .map(|_| {
                    sensor.draw(&Vec3::new(200.0, 50.0, 30.0), &Mat3::identity());
                    sensor.held()
                })
                .collect::<Vec<_>>()
        };
        assert_eq!(draws(1), draws(1));
        assert_ne!(draws(1), draws(2));
    }

    /// Pixel noise reaches r* through (6.2)-(6.3): without noise r* = R/b; with small noise the
    /// error is the linearisation (6.4) S_n n_I: a bI error of δ px scales r by -δ/bI, a yI
    /// error moves it sideways by aI δ/l (at the image centre, level attitude).
    #[test]
    fn pixel_noise_propagates_through_the_sensing_transform() {
        let mut sensor = sensor(&scenario(NoiseOn::Pixels, SnrReference::Signal));
        let attitude = EulerAngles::new(0.1, -0.05, 0.3);
        let l_be = attitude.body_from_ned();
        let relative = l_be.transpose() * Vec3::new(100.0, 0.0, 0.0);
        sensor.held = HeldNoise::Pixels(ImageMeasurement::default());
        let r = sensor.measure(&relative, &l_be).expect("in front");
        assert!((r - relative / 8.0).norm() < 1e-12);

        let focal = sensor.focal_px;
        let b_i = 8.0 * focal / 100.0;
        let delta = 1e-4;
        sensor.held = HeldNoise::Pixels(ImageMeasurement {
            b_i_px: delta,
            ..ImageMeasurement::default()
        });
        let r_b = sensor.measure(&relative, &l_be).expect("in front");
        let expected = relative / 8.0 * (-delta / b_i);
        // The linearisation's relative error is of the order δ/bI ≈ 2.3e-6.
        assert!((r_b - relative / 8.0 - expected).norm() < 1e-5 * expected.norm());

        sensor.held = HeldNoise::Pixels(ImageMeasurement {
            y_i_px: delta,
            ..ImageMeasurement::default()
        });
        let r_y = sensor.measure(&relative, &l_be).expect("in front");
        let sideways = l_be.transpose() * Vec3::new(0.0, 100.0 / 8.0 * delta / focal, 0.0);
        assert!((r_y - relative / 8.0 - sideways).norm() < 1e-5 * sideways.norm());

        // Behind the camera: lost.
        assert!(sensor.measure(&(-relative), &l_be).is_none());
    }
}
