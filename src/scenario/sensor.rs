//! `[sensor]`: where the guidance's measurement of r comes from, and the noise model of the
//! `noisy` sensor ((6.1)-(6.9); docs/equations.md, Noisy measurements).

use serde::{Deserialize, Serialize};

use super::check::{self, Check};

/// What the guidance measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SensorMode {
    /// r = R / b exactly, continuously (seed Chapters 4-5).
    Perfect,
    /// r* = r + n: the perfect measurement with sampled-and-held white noise (seed Chapter 6),
    /// added to r or to the pixels (yI, zI, bI) (`noise_on`).
    Noisy,
    /// Rendered frames measured by the image pipeline (`[camera]`).
    Camera,
}

/// Where the `noisy` sensor adds its noise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NoiseOn {
    /// On r itself, r* = r + n_r (6.8), at the SNR `snr_db` (the seed's simulations).
    ScaledPosition,
    /// On the image measurements, y*_I = y_I + n_y, z*_I = z_I + n_z, b*_I = b_I + n_b (6.1),
    /// standard deviations `pixel_noise_px`, propagated to r* through the sensing transform
    /// (6.2)-(6.3) with the focal length of `[camera]`.
    Pixels,
}

/// The signal power the SNR of `noise_on = "scaled_position"` is relative to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SnrReference {
    /// The power of the noise-free r at the sampling instant, P_r = ‖r‖² / 3 per axis: the
    /// noise scales with the range, every sample has the stated SNR.
    Signal,
    /// The power of the commanded r_c = R_c / b, P_r = ‖R_c‖² / (3 b²) per axis: one noise
    /// level for the whole run (formation only: interception commands R_c = 0).
    Command,
}

/// `[sensor]`: the measurement model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensorSection {
    /// Measurement model.
    pub mode: SensorMode,
    /// `noisy`: where the noise is added.
    pub noise_on: NoiseOn,
    /// `noisy`, on r: signal-to-noise ratio, dB. Per axis i the noise is zero-mean Gaussian
    /// with variance σ² = P_r / 10^(SNR/10), P_r from `snr_reference`; so
    /// SNR = 10 log10(P_r / σ²) = 10 log10(E‖r‖² / E‖n_r‖²) (seed: 25 dB in Chapter 6).
    pub snr_db: f64,
    /// `noisy`, on r: the power the SNR refers to.
    pub snr_reference: SnrReference,
    /// `noisy`, on pixels: standard deviations of (n_y, n_z, n_b), px.
    pub pixel_noise_px: [f64; 3],
    /// `noisy`: a new noise sample is drawn every this many seconds and held in between
    /// (white noise of power spectral density σ² · period); 0 draws one every tick. A
    /// nonzero value must be a whole number of `run.dt_s`.
    pub sample_period_s: f64,
}

impl Default for SensorSection {
    fn default() -> Self {
        Self {
            mode: SensorMode::Perfect,
            noise_on: NoiseOn::ScaledPosition,
            snr_db: 25.0,
            snr_reference: SnrReference::Signal,
            pixel_noise_px: [0.5, 0.5, 0.5],
            sample_period_s: 0.0,
        }
    }
}

impl SensorSection {
    /// Checks the noise settings (only used by the `noisy` mode, checked in every mode);
    /// `dt_s` is the step the sample period must be a multiple of, `has_command` whether the
    /// run has a nonzero formation command for `snr_reference = "command"`.
    pub fn validate(&self, dt_s: f64, has_command: bool) -> Check {
        // At 0 dB or below the noise is as large as the signal (the scaled position, or the
        // command): no camera measures that, and the estimator's gains follow it out of range.
        check::require(
            self.snr_db > 0.0 && self.snr_db <= 200.0,
            "sensor.snr_db",
            self.snr_db,
            "(0, 200] dB",
        )?;
        for (i, sigma) in self.pixel_noise_px.iter().enumerate() {
            check::in_closed(&format!("sensor.pixel_noise_px[{i}]"), *sigma, 0.0, 1e3)?;
        }
        check::in_closed("sensor.sample_period_s", self.sample_period_s, 0.0, 10.0)?;
        if self.sample_period_s > 0.0 {
            let ticks = self.sample_period_s / dt_s;
            check::require(
                ticks >= 1.0 - 1e-9 && (ticks - ticks.round()).abs() < 1e-6 * ticks,
                "sensor.sample_period_s",
                self.sample_period_s,
                format!("0 or a whole number of run.dt_s = {dt_s} s"),
            )?;
        }
        if self.mode == SensorMode::Noisy
            && self.noise_on == NoiseOn::ScaledPosition
            && self.snr_reference == SnrReference::Command
        {
            check::require(
                has_command,
                "sensor.snr_reference",
                "\"command\"",
                "\"signal\" when the command is zero (interception or guidance.command_ft = 0)",
            )?;
        }
        Ok(())
    }

    /// Simulation ticks between noise samples (1 for every tick).
    pub fn sample_period_ticks(&self, dt_s: f64) -> u64 {
        if self.sample_period_s > 0.0 {
            (self.sample_period_s / dt_s).round().max(1.0) as u64
        } else {
            1
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid() {
        assert_eq!(SensorSection::default().validate(0.001, true), Ok(()));
    }

    /// A sample period that is not a whole number of steps is named with its range.
    #[test]
    fn sample_period_must_divide_into_ticks() {
        let section = SensorSection {
            sample_period_s: 0.0025,
            ..SensorSection::default()
        };
        let err = section.validate(0.001, true).expect_err("invalid");
        assert_eq!(err.key, "sensor.sample_period_s");
        assert!(err.allowed.contains("run.dt_s = 0.001"), "{err}");
        let ok = SensorSection {
            sample_period_s: 0.01,
            ..SensorSection::default()
        };
        assert_eq!(ok.validate(0.001, true), Ok(()));
        assert_eq!(ok.sample_period_ticks(0.001), 10);
    }

    /// The command reference needs a command.
    #[test]
    fn command_reference_needs_a_command() {
        let section = SensorSection {
            mode: SensorMode::Noisy,
            snr_reference: SnrReference::Command,
            ..SensorSection::default()
        };
        assert_eq!(section.validate(0.001, true), Ok(()));
        let err = section.validate(0.001, false).expect_err("invalid");
        assert_eq!(err.key, "sensor.snr_reference");
    }
}
