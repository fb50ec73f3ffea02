//! The air data's errors (`[navigation.air_data] mode = "errors"`; docs/equations.md, The
//! follower's own navigation and sensors): airspeed, α and β each read the truth plus a fixed
//! bias plus white noise drawn at the air-data rate and held until the next sample.

use crate::scenario::AirDataSection;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

/// What the air data reads above the truth at an instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AirDataErrors {
    /// Airspeed error, ft/s.
    pub airspeed_fps: f64,
    /// α error, rad.
    pub alpha_rad: f64,
    /// β error, rad.
    pub beta_rad: f64,
}

/// The pitot and vanes of one run.
#[derive(Debug, Clone)]
pub struct AirDataSensor {
    rng: ChaCha8Rng,
    /// Biases [V ft/s, α rad, β rad].
    bias: [f64; 3],
    /// σ of the noise [V ft/s, α rad, β rad].
    noise_sigma: [f64; 3],
    period_s: f64,
    to_next_sample_s: f64,
    errors: AirDataErrors,
}

impl AirDataSensor {
    /// The sensor `section` states, its noise drawn from `seed`.
    pub fn new(section: &AirDataSection, seed: u64) -> Self {
        let s = section;
        let mut sensor = Self {
            rng: ChaCha8Rng::seed_from_u64(seed),
            bias: [
                s.airspeed_bias_fps,
                s.alpha_bias_deg.to_radians(),
                s.beta_bias_deg.to_radians(),
            ],
            noise_sigma: [
                s.airspeed_noise_fps,
                s.alpha_noise_deg.to_radians(),
                s.beta_noise_deg.to_radians(),
            ],
            period_s: 1.0 / s.rate_hz,
            to_next_sample_s: 0.0,
            errors: AirDataErrors::default(),
        };
        sensor.sample();
        sensor
    }

    fn sample(&mut self) {
        let [v, a, b] = [0, 1, 2].map(|i| {
            let n: f64 = self.rng.sample(StandardNormal);
            self.bias[i] + self.noise_sigma[i] * n
        });
        self.errors = AirDataErrors {
            airspeed_fps: v,
            alpha_rad: a,
            beta_rad: b,
        };
        self.to_next_sample_s += self.period_s;
    }

    /// Advances by `dt_s`, sampling when a sample is due.
    pub fn advance(&mut self, dt_s: f64) {
        self.to_next_sample_s -= dt_s;
        if self.to_next_sample_s <= 1e-9 {
            self.sample();
        }
    }

    /// The errors held now.
    pub fn errors(&self) -> AirDataErrors {
        self.errors
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reading's mean is the bias and its spread the noise σ, sampled at the rate.
    #[test]
    fn reads_the_bias_with_the_stated_noise() {
        let section = AirDataSection {
            rate_hz: 10.0,
            airspeed_noise_fps: 2.0,
            airspeed_bias_fps: -1.0,
            ..AirDataSection::default()
        };
        let mut sensor = AirDataSensor::new(&section, 3);
        let mut samples = Vec::new();
        for tick in 0..200_000 {
            sensor.advance(0.01);
            if tick % 10 == 0 {
                samples.push(sensor.errors().airspeed_fps);
            }
        }
        let n = samples.len() as f64;
        let mean = samples.iter().sum::<f64>() / n;
        let sd = (samples.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / n).sqrt();
        assert!((mean + 1.0).abs() < 0.05, "{mean}");
        assert!((sd - 2.0).abs() < 0.05, "{sd}");
    }
}
