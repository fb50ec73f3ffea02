//! `[atmosphere]`: density, steady wind, turbulence severity and the unmodelled perturbations
//! Δ of (7.17)-(7.18) (the physics is in `world::atmosphere`).

use serde::{Deserialize, Serialize};

use super::check::{self, Check};
use crate::frames::{SEA_LEVEL_DENSITY_SLUG_FT3, Vec3};

/// How density varies with altitude.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum DensityModel {
    /// `sea_level_density_slug_ft3` at every altitude (the seed's assumption).
    #[default]
    Constant,
    /// ICAO standard troposphere: ρ = ρ0 (1 - 6.87559e-6 h)^4.25588, h in ft above sea level
    /// (ground at sea level).
    Standard,
}

/// Turbulence severity (MIL-F-8785C low-altitude wind speed at 20 ft).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum TurbulenceLevel {
    /// No turbulence.
    #[default]
    Off,
    /// W20 = 15 kt.
    Light,
    /// W20 = 30 kt.
    Moderate,
    /// W20 = 45 kt.
    Severe,
}

/// Unmodelled perturbations Δ of (7.17)-(7.18): they act on the plant, never on the controller's
/// nominal model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DisturbanceConfig {
    /// Factor on the aerodynamic drag D (1 = nominal).
    pub drag_factor: f64,
    /// Added body moments (ΔL, ΔM, ΔN), lbf ft.
    pub moment_bias_lbf_ft: [f64; 3],
}

impl Default for DisturbanceConfig {
    fn default() -> Self {
        Self {
            drag_factor: 1.0,
            moment_bias_lbf_ft: [0.0; 3],
        }
    }
}

impl DisturbanceConfig {
    /// Checks every value; keys are named as under `[atmosphere.disturbances]`.
    pub fn validate(&self) -> Check {
        check::in_closed(
            "atmosphere.disturbances.drag_factor",
            self.drag_factor,
            0.0,
            10.0,
        )?;
        check::finite_vec(
            "atmosphere.disturbances.moment_bias_lbf_ft",
            &self.moment_bias_lbf_ft,
        )?;
        check::require(
            self.moment_bias_lbf_ft.iter().all(|m| m.abs() <= 100.0),
            "atmosphere.disturbances.moment_bias_lbf_ft",
            format!("{:?}", self.moment_bias_lbf_ft),
            "each component in [-100, 100]",
        )
    }
}

/// `[atmosphere]`: everything the follower's plant feels from the air.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AtmosphereConfig {
    /// Density model.
    pub density_model: DensityModel,
    /// Density at sea level (or everywhere, with `constant`), slug/ft³.
    pub sea_level_density_slug_ft3: f64,
    /// Height above ground of the NED origin, ft (the seed's follower starts at the origin).
    /// Altitude = this minus the NED down coordinate.
    pub origin_altitude_ft: f64,
    /// Steady wind (velocity of the air mass), NED, ft/s.
    pub wind_ned_fps: [f64; 3],
    /// Dryden turbulence severity.
    pub turbulence: TurbulenceLevel,
    /// Unmodelled perturbations Δ.
    pub disturbances: DisturbanceConfig,
}

impl Default for AtmosphereConfig {
    fn default() -> Self {
        Self {
            density_model: DensityModel::Constant,
            sea_level_density_slug_ft3: SEA_LEVEL_DENSITY_SLUG_FT3,
            origin_altitude_ft: 500.0,
            wind_ned_fps: [0.0; 3],
            turbulence: TurbulenceLevel::Off,
            disturbances: DisturbanceConfig::default(),
        }
    }
}

impl AtmosphereConfig {
    /// Checks every value; keys are named as under `[atmosphere]`.
    pub fn validate(&self) -> Check {
        check::in_closed(
            "atmosphere.sea_level_density_slug_ft3",
            self.sea_level_density_slug_ft3,
            1e-4,
            0.01,
        )?;
        check::in_closed(
            "atmosphere.origin_altitude_ft",
            self.origin_altitude_ft,
            0.0,
            30_000.0,
        )?;
        check::finite_vec("atmosphere.wind_ned_fps", &self.wind_ned_fps)?;
        let wind_fps = Vec3::from(self.wind_ned_fps).norm();
        check::require(
            wind_fps <= 200.0,
            "atmosphere.wind_ned_fps",
            format!("{:?}", self.wind_ned_fps),
            "a vector of length <= 200 ft/s",
        )?;
        self.disturbances.validate()
    }
}
