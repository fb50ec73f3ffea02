//! The air around the follower: density, steady wind, Dryden turbulence (MIL-F-8785C, low
//! altitude) and the unmodelled perturbations Δ of (7.17)-(7.18) that act on the plant only.
//!
//! Once per simulation tick, [`Atmosphere::sample`] advances the turbulence filters by one tick
//! and returns an [`AtmosphereSample`] that the plant holds constant over that integration step.
//!
//! Dryden model (MIL-F-8785C, §3.7, low altitude, h < 1000 ft), h in ft, W20 the wind speed at
//! 20 ft (light 15 kt, moderate 30 kt, severe 45 kt):
//! ```text
//! σ_w = 0.1 W20,   σ_u = σ_v = σ_w / (0.177 + 0.000823 h)^0.4
//! L_w = h,         L_u = L_v = h / (0.177 + 0.000823 h)^1.2
//! R_u(τ) = σ_u² e^{-Vτ/L_u}
//! R_v(τ) = σ_v² (1 - Vτ/(2 L_v)) e^{-Vτ/L_v}     (R_w likewise with σ_w, L_w)
//! ```
//! Each component is a linear filter of white noise whose state is kept normalised (unit
//! stationary covariance); it is propagated by the exact discrete-time solution over the tick
//! at the current airspeed and altitude (x⁺ = Φ x + w, w ~ N(0, I - Φ Φᵀ)), so the statistics
//! are right for any tick length and stay stationary when V or h change. The gusts are applied
//! along the body axes (u along x, v along y, w along z), as in Beard & McLain 2012 §4.4;
//! angular gust components are not modelled. h is clamped to [10, 1000] ft (below 10 ft the
//! model is undefined; above 1000 ft it would need the medium/high-altitude tables).

use crate::frames::{SEA_LEVEL_DENSITY_SLUG_FT3, Vec3};
pub use crate::scenario::{AtmosphereConfig, DensityModel, DisturbanceConfig, TurbulenceLevel};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

/// One knot in ft/s (1852 m per hour).
pub const FPS_PER_KNOT: f64 = 1852.0 / 0.3048 / 3600.0;
/// Lowest altitude the Dryden low-altitude model is evaluated at, ft.
pub const DRYDEN_MIN_ALTITUDE_FT: f64 = 10.0;
/// Highest altitude the Dryden low-altitude model is evaluated at, ft.
pub const DRYDEN_MAX_ALTITUDE_FT: f64 = 1000.0;
/// Lowest airspeed used for the turbulence time scales L/V, ft/s (keeps them finite at rest).
pub const DRYDEN_MIN_AIRSPEED_FPS: f64 = 1.0;

/// Wind speed at 20 ft, W20, of a turbulence severity, ft/s (0 when off).
pub fn wind_speed_20ft_fps(level: TurbulenceLevel) -> f64 {
    let knots = match level {
        TurbulenceLevel::Off => 0.0,
        TurbulenceLevel::Light => 15.0,
        TurbulenceLevel::Moderate => 30.0,
        TurbulenceLevel::Severe => 45.0,
    };
    knots * FPS_PER_KNOT
}

/// The air as the plant sees it over one integration step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtmosphereSample {
    /// Air density ρ, slug/ft³.
    pub density_slug_ft3: f64,
    /// Steady wind, NED, ft/s.
    pub wind_ned_fps: Vec3,
    /// Turbulent gust velocity along the body axes (u_g, v_g, w_g), ft/s.
    pub gust_body_fps: Vec3,
    /// Factor on drag (Δ of (7.18)).
    pub drag_factor: f64,
    /// Added body moments (ΔL, ΔM, ΔN), lbf ft (Δ of (7.17)).
    pub moment_bias_body_lbf_ft: Vec3,
}

impl AtmosphereSample {
    /// Still air of the given density, no perturbations.
    pub fn calm(density_slug_ft3: f64) -> Self {
        Self {
            density_slug_ft3,
            wind_ned_fps: Vec3::zeros(),
            gust_body_fps: Vec3::zeros(),
            drag_factor: 1.0,
            moment_bias_body_lbf_ft: Vec3::zeros(),
        }
    }
}

impl Default for AtmosphereSample {
    /// Calm air at sea-level density.
    fn default() -> Self {
        Self::calm(SEA_LEVEL_DENSITY_SLUG_FT3)
    }
}

/// Turbulence intensities (σ_u, σ_v, σ_w), ft/s, at altitude `altitude_ft` (MIL-F-8785C low
/// altitude; h clamped to [10, 1000] ft).
pub fn dryden_intensities_fps(level: TurbulenceLevel, altitude_ft: f64) -> Vec3 {
    let h = dryden_altitude_ft(altitude_ft);
    let sigma_w = 0.1 * wind_speed_20ft_fps(level);
    let sigma_uv = sigma_w / (0.177 + 0.000823 * h).powf(0.4);
    Vec3::new(sigma_uv, sigma_uv, sigma_w)
}

/// Turbulence scale lengths (L_u, L_v, L_w), ft, at altitude `altitude_ft` (MIL-F-8785C low
/// altitude; h clamped to [10, 1000] ft).
pub fn dryden_scale_lengths_ft(altitude_ft: f64) -> Vec3 {
    let h = dryden_altitude_ft(altitude_ft);
    let l_uv = h / (0.177 + 0.000823 * h).powf(1.2);
    Vec3::new(l_uv, l_uv, h)
}

fn dryden_altitude_ft(altitude_ft: f64) -> f64 {
    if altitude_ft.is_finite() {
        altitude_ft.clamp(DRYDEN_MIN_ALTITUDE_FT, DRYDEN_MAX_ALTITUDE_FT)
    } else {
        DRYDEN_MIN_ALTITUDE_FT
    }
}

/// Dryden gust generator: normalised filter states and their own seeded random stream.
#[derive(Debug, Clone)]
pub struct DrydenTurbulence {
    level: TurbulenceLevel,
    rng: ChaCha8Rng,
    /// First-order filter state of u (unit variance).
    u: f64,
    /// Second-order filter states of v and w (unit covariance).
    v: [f64; 2],
    w: [f64; 2],
    gust_body_fps: Vec3,
}

impl DrydenTurbulence {
    /// A generator at `level`, its random stream seeded with `seed`; the filters start in their
    /// stationary distribution (so the gusts are stationary from the first tick).
    pub fn new(level: TurbulenceLevel, seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let (u, v, w) = if level == TurbulenceLevel::Off {
            (0.0, [0.0; 2], [0.0; 2])
        } else {
            let mut n = || -> f64 { rng.sample(StandardNormal) };
            (n(), [n(), n()], [n(), n()])
        };
        Self {
            level,
            rng,
            u,
            v,
            w,
            gust_body_fps: Vec3::zeros(),
        }
    }

    /// Severity.
    pub fn level(&self) -> TurbulenceLevel {
        self.level
    }

    /// The gust of the last [`Self::step`], body axes, ft/s.
    pub fn gust_body_fps(&self) -> Vec3 {
        self.gust_body_fps
    }

    /// Advances the filters by `dt_s` at airspeed `airspeed_fps` and altitude `altitude_ft`;
    /// returns the gust (u_g, v_g, w_g) along body axes, ft/s, to hold over the next step. Off:
    /// always zero and no random numbers drawn. A non-positive or non-finite `dt_s` does not
    /// advance the filters.
    pub fn step(&mut self, dt_s: f64, airspeed_fps: f64, altitude_ft: f64) -> Vec3 {
        if self.level == TurbulenceLevel::Off {
            return Vec3::zeros();
        }
        let sigma = dryden_intensities_fps(self.level, altitude_ft);
        if dt_s.is_finite() && dt_s > 0.0 {
            let speed = if airspeed_fps.is_finite() {
                airspeed_fps.max(DRYDEN_MIN_AIRSPEED_FPS)
            } else {
                DRYDEN_MIN_AIRSPEED_FPS
            };
            let lengths = dryden_scale_lengths_ft(altitude_ft);
            let mut n = || -> f64 { self.rng.sample(StandardNormal) };
            let (n_u, n_v, n_w) = (n(), [n(), n()], [n(), n()]);
            self.u = first_order_step(self.u, speed * dt_s / lengths.x, n_u);
            self.v = second_order_step(self.v, speed * dt_s / lengths.y, n_v);
            self.w = second_order_step(self.w, speed * dt_s / lengths.z, n_w);
        }
        self.gust_body_fps = Vec3::new(
            sigma.x * self.u,
            sigma.y * second_order_output(self.v),
            sigma.z * second_order_output(self.w),
        );
        self.gust_body_fps
    }
}

/// Exact step of the unit-variance Gauss-Markov process with correlation e^{-τ/T} over
/// `steps_of_t` = Δt/T: x⁺ = a x + √(1 - a²) n, a = e^{-Δt/T}.
fn first_order_step(x: f64, steps_of_t: f64, noise: f64) -> f64 {
    let a = (-steps_of_t).exp();
    a * x + (-(-2.0 * steps_of_t).exp_m1()).max(0.0).sqrt() * noise
}

/// Exact step of the normalised Dryden v/w filter over s = Δt/T (T = L/V).
///
/// With s1, s2 the states of ẋ = (1/T) [[0, 1], [-1, -2]] x + (2/T) [0, 1]ᵀ η (η white with
/// intensity T), the stationary covariance is I and the output y = (s1 + √3 s2)/2 has variance 1
/// and R(τ) = (1 - τ/2T) e^{-τ/T}, i.e. the Dryden lateral/vertical correlation. The transition
/// matrix is Φ = e^{-s} [[1 + s, s], [-s, 1 - s]], the noise covariance Q = I - Φ Φᵀ.
fn second_order_step(x: [f64; 2], s: f64, noise: [f64; 2]) -> [f64; 2] {
    let e = (-s).exp();
    let phi = [[e * (1.0 + s), e * s], [-e * s, e * (1.0 - s)]];
    let e2 = (-2.0 * s).exp();
    let em1 = -(-2.0 * s).exp_m1(); // 1 - e^{-2s}, accurate for small s
    let q11 = (em1 - e2 * (2.0 * s + 2.0 * s * s)).max(0.0);
    let q12 = 2.0 * s * s * e2;
    let q22 = (em1 + e2 * (2.0 * s - 2.0 * s * s)).max(0.0);
    // Cholesky factor of Q (lower triangular).
    let l11 = q11.sqrt();
    let l21 = if l11 > 0.0 { q12 / l11 } else { 0.0 };
    let l22 = (q22 - l21 * l21).max(0.0).sqrt();
    [
        phi[0][0] * x[0] + phi[0][1] * x[1] + l11 * noise[0],
        phi[1][0] * x[0] + phi[1][1] * x[1] + l21 * noise[0] + l22 * noise[1],
    ]
}

/// Output of the normalised second-order filter: (s1 + √3 s2) / 2.
fn second_order_output(x: [f64; 2]) -> f64 {
    0.5 * (x[0] + 3f64.sqrt() * x[1])
}

/// The atmosphere of one run: configuration plus the turbulence generator.
#[derive(Debug, Clone)]
pub struct Atmosphere {
    config: AtmosphereConfig,
    turbulence: DrydenTurbulence,
}

impl Atmosphere {
    /// An atmosphere from a validated configuration; `seed` seeds the turbulence's random stream
    /// (derive it from the run's seed).
    pub fn new(
        config: &AtmosphereConfig,
        seed: u64,
    ) -> Result<Self, crate::scenario::check::InvalidValue> {
        config.validate()?;
        Ok(Self {
            config: config.clone(),
            turbulence: DrydenTurbulence::new(config.turbulence, seed),
        })
    }

    /// The configuration.
    pub fn config(&self) -> &AtmosphereConfig {
        &self.config
    }

    /// Height above ground of a NED position, ft.
    pub fn altitude_ft(&self, position_ned_ft: &Vec3) -> f64 {
        self.config.origin_altitude_ft - position_ned_ft.z
    }

    /// Density at an altitude (ft), slug/ft³.
    pub fn density_slug_ft3(&self, altitude_ft: f64) -> f64 {
        let rho0 = self.config.sea_level_density_slug_ft3;
        match self.config.density_model {
            DensityModel::Constant => rho0,
            DensityModel::Standard => {
                // Troposphere only (h < 36 089 ft); clamped at both ends.
                let h = altitude_ft.clamp(0.0, 36_089.0);
                rho0 * (1.0 - 6.875_59e-6 * h).powf(4.255_88)
            }
        }
    }

    /// Still air at the altitude of `position_ned_ft` with the steady wind and the Δ
    /// perturbations but no turbulence (for trim).
    pub fn steady_sample(&self, position_ned_ft: &Vec3) -> AtmosphereSample {
        AtmosphereSample {
            density_slug_ft3: self.density_slug_ft3(self.altitude_ft(position_ned_ft)),
            wind_ned_fps: Vec3::from(self.config.wind_ned_fps),
            gust_body_fps: Vec3::zeros(),
            drag_factor: self.config.disturbances.drag_factor,
            moment_bias_body_lbf_ft: Vec3::from(self.config.disturbances.moment_bias_lbf_ft),
        }
    }

    /// Advances the turbulence by one tick of `dt_s` at the follower's position and airspeed
    /// and returns the sample to hold over the coming integration step.
    pub fn sample(
        &mut self,
        dt_s: f64,
        position_ned_ft: &Vec3,
        airspeed_fps: f64,
    ) -> AtmosphereSample {
        let altitude_ft = self.altitude_ft(position_ned_ft);
        let gust = self.turbulence.step(dt_s, airspeed_fps, altitude_ft);
        AtmosphereSample {
            gust_body_fps: gust,
            ..self.steady_sample(position_ned_ft)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intensities_and_lengths_follow_mil_f_8785c() {
        // At 1000 ft: σ_u = σ_w and L_u = L_w = 1000 ft (0.177 + 0.823 = 1).
        let s = dryden_intensities_fps(TurbulenceLevel::Moderate, 1000.0);
        assert!((s.z - 3.0 * FPS_PER_KNOT).abs() < 1e-12);
        assert!((s.x - s.z).abs() < 1e-12);
        let l = dryden_scale_lengths_ft(1000.0);
        assert!((l.x - 1000.0).abs() < 1e-9 && (l.z - 1000.0).abs() < 1e-12);
        // Below 10 ft the 10 ft values hold.
        assert_eq!(dryden_scale_lengths_ft(0.0), dryden_scale_lengths_ft(10.0));
    }

    #[test]
    fn second_order_noise_keeps_unit_covariance() {
        // Stationarity: Φ I Φᵀ + Q = I, checked through the Cholesky factor for several Δt/T.
        for s in [1e-4, 0.01, 0.3, 1.0, 5.0] {
            let phi_x = |x: [f64; 2]| second_order_step(x, s, [0.0, 0.0]);
            let noise_x = |n: [f64; 2]| second_order_step([0.0, 0.0], s, n);
            let mut cov = [[0.0; 2]; 2];
            for basis in [[1.0, 0.0], [0.0, 1.0]] {
                let a = phi_x(basis);
                let b = noise_x(basis);
                for i in 0..2 {
                    for j in 0..2 {
                        cov[i][j] += a[i] * a[j] + b[i] * b[j];
                    }
                }
            }
            assert!((cov[0][0] - 1.0).abs() < 1e-12, "s={s} {cov:?}");
            assert!((cov[1][1] - 1.0).abs() < 1e-12, "s={s} {cov:?}");
            assert!(cov[0][1].abs() < 1e-12, "s={s} {cov:?}");
        }
    }

    #[test]
    fn standard_density_falls_with_altitude() {
        let config = AtmosphereConfig {
            density_model: DensityModel::Standard,
            ..AtmosphereConfig::default()
        };
        let atm = Atmosphere::new(&config, 1).expect("valid");
        assert_eq!(atm.density_slug_ft3(0.0), SEA_LEVEL_DENSITY_SLUG_FT3);
        // Standard atmosphere at 10 000 ft: 0.0017556 slug/ft³.
        assert!((atm.density_slug_ft3(10_000.0) - 0.0017556).abs() < 2e-6);
    }

    #[test]
    fn validation_names_key_value_and_range() {
        let config = AtmosphereConfig {
            disturbances: DisturbanceConfig {
                drag_factor: -1.0,
                ..DisturbanceConfig::default()
            },
            ..AtmosphereConfig::default()
        };
        let err = config
            .validate()
            .expect_err("negative drag factor")
            .to_string();
        assert!(
            err.contains("atmosphere.disturbances.drag_factor = -1"),
            "{err}"
        );
        assert!(err.contains("[0, 10]"), "{err}");
    }

    #[test]
    fn config_parses_with_defaults_and_rejects_unknown_keys() {
        let c: AtmosphereConfig = toml::from_str("turbulence = \"light\"\n").expect("valid");
        assert_eq!(c.turbulence, TurbulenceLevel::Light);
        assert_eq!(c.disturbances, DisturbanceConfig::default());
        assert!(toml::from_str::<AtmosphereConfig>("turbulance = \"light\"\n").is_err());
    }
}
