//! The aircraft data file (`assets/aircraft/*.toml`): schema, loading and validation.
//!
//! Mass, geometry, aerodynamic and propulsion data are read as they are written (their unit is
//! in every key); actuator limits are written in degrees and kept in radians.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::frames::Mat3;
use crate::scenario::DEFAULT_AIRCRAFT;
use crate::scenario::check::{self, Check, InvalidValue};

use super::actuators::{ActuatorLimits, Actuators};

/// The seed follower's data file, built into the program (`assets/aircraft/follower.toml`,
/// [`DEFAULT_AIRCRAFT`]).
const SEED_FOLLOWER_TOML: &str = include_str!("../../../assets/aircraft/follower.toml");

/// Mass and inertia (seed 7.4; J as in (7.16)).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MassProperties {
    /// Mass m, slug.
    pub mass_slug: f64,
    /// Roll moment of inertia Jxx, slug ft².
    pub jxx_slug_ft2: f64,
    /// Pitch moment of inertia Jyy, slug ft².
    pub jyy_slug_ft2: f64,
    /// Yaw moment of inertia Jzz, slug ft².
    pub jzz_slug_ft2: f64,
    /// Product of inertia Jxz, slug ft² (enters J with a minus sign, (7.16)).
    pub jxz_slug_ft2: f64,
}

impl MassProperties {
    /// J = [[Jxx, 0, -Jxz], [0, Jyy, 0], [-Jxz, 0, Jzz]] (7.16), slug ft².
    pub fn inertia_slug_ft2(&self) -> Mat3 {
        Mat3::new(
            self.jxx_slug_ft2,
            0.0,
            -self.jxz_slug_ft2,
            0.0,
            self.jyy_slug_ft2,
            0.0,
            -self.jxz_slug_ft2,
            0.0,
            self.jzz_slug_ft2,
        )
    }

    fn validate(&self) -> Check {
        check::positive("mass.mass_slug", self.mass_slug)?;
        check::positive("mass.jxx_slug_ft2", self.jxx_slug_ft2)?;
        check::positive("mass.jyy_slug_ft2", self.jyy_slug_ft2)?;
        check::positive("mass.jzz_slug_ft2", self.jzz_slug_ft2)?;
        let bound = (self.jxx_slug_ft2 * self.jzz_slug_ft2).sqrt();
        check::in_open(
            "mass.jxz_slug_ft2",
            self.jxz_slug_ft2,
            -bound,
            bound,
            &format!("(-sqrt(Jxx Jzz), sqrt(Jxx Jzz)) = (-{bound}, {bound})"),
        )
    }
}

/// Reference geometry of (7.19).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Geometry {
    /// Wing reference area S, ft².
    pub wing_area_ft2: f64,
    /// Mean aerodynamic chord c, ft.
    pub chord_ft: f64,
    /// Wing span b_F, ft.
    pub span_ft: f64,
}

impl Geometry {
    /// Aspect ratio b²/S.
    pub fn aspect_ratio(&self) -> f64 {
        self.span_ft * self.span_ft / self.wing_area_ft2
    }

    fn validate(&self) -> Check {
        check::positive("geometry.wing_area_ft2", self.wing_area_ft2)?;
        check::positive("geometry.chord_ft", self.chord_ft)?;
        check::positive("geometry.span_ft", self.span_ft)
    }
}

/// Nondimensional aerodynamic derivatives (Beard & McLain 2012, eqs. 4.6-4.15).
///
/// Rate derivatives (`_p`, `_q`, `_r`) multiply the nondimensional rates p̂ = b p / 2V,
/// q̂ = c q / 2V, r̂ = b r / 2V; the others are per radian of α, β or a surface deflection.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AeroCoefficients {
    /// C_L0.
    pub c_lift_0: f64,
    /// C_Lα, 1/rad.
    pub c_lift_alpha_per_rad: f64,
    /// C_Lq.
    pub c_lift_q: f64,
    /// C_Lδe, 1/rad.
    pub c_lift_de_per_rad: f64,
    /// C_D0 (parasitic drag C_Dp of the polar C_D = C_D0 + K C_L²).
    pub c_drag_0: f64,
    /// Oswald efficiency e; K = 1 / (π e AR).
    pub oswald_efficiency: f64,
    /// α0, rad: centre of the blend from the linear lift curve to flat-plate lift.
    pub stall_alpha_rad: f64,
    /// M, 1/rad: sharpness of the stall blend.
    pub stall_transition_per_rad: f64,
    /// C_m0.
    pub c_pitch_0: f64,
    /// C_mα, 1/rad.
    pub c_pitch_alpha_per_rad: f64,
    /// C_mq.
    pub c_pitch_q: f64,
    /// C_mδe, 1/rad.
    pub c_pitch_de_per_rad: f64,
    /// C_Y0.
    pub c_side_0: f64,
    /// C_Yβ, 1/rad.
    pub c_side_beta_per_rad: f64,
    /// C_Yp.
    pub c_side_p: f64,
    /// C_Yr.
    pub c_side_r: f64,
    /// C_Yδa, 1/rad.
    pub c_side_da_per_rad: f64,
    /// C_Yδr, 1/rad.
    pub c_side_dr_per_rad: f64,
    /// C_l0.
    pub c_roll_0: f64,
    /// C_lβ, 1/rad.
    pub c_roll_beta_per_rad: f64,
    /// C_lp.
    pub c_roll_p: f64,
    /// C_lr.
    pub c_roll_r: f64,
    /// C_lδa, 1/rad.
    pub c_roll_da_per_rad: f64,
    /// C_lδr, 1/rad.
    pub c_roll_dr_per_rad: f64,
    /// C_n0.
    pub c_yaw_0: f64,
    /// C_nβ, 1/rad.
    pub c_yaw_beta_per_rad: f64,
    /// C_np.
    pub c_yaw_p: f64,
    /// C_nr.
    pub c_yaw_r: f64,
    /// C_nδa, 1/rad.
    pub c_yaw_da_per_rad: f64,
    /// C_nδr, 1/rad.
    pub c_yaw_dr_per_rad: f64,
}

impl AeroCoefficients {
    fn validate(&self) -> Check {
        let finite = [
            ("aero.c_lift_0", self.c_lift_0),
            ("aero.c_lift_q", self.c_lift_q),
            ("aero.c_lift_de_per_rad", self.c_lift_de_per_rad),
            ("aero.c_pitch_0", self.c_pitch_0),
            ("aero.c_pitch_alpha_per_rad", self.c_pitch_alpha_per_rad),
            ("aero.c_pitch_q", self.c_pitch_q),
            ("aero.c_side_0", self.c_side_0),
            ("aero.c_side_beta_per_rad", self.c_side_beta_per_rad),
            ("aero.c_side_p", self.c_side_p),
            ("aero.c_side_r", self.c_side_r),
            ("aero.c_side_da_per_rad", self.c_side_da_per_rad),
            ("aero.c_side_dr_per_rad", self.c_side_dr_per_rad),
            ("aero.c_roll_0", self.c_roll_0),
            ("aero.c_roll_beta_per_rad", self.c_roll_beta_per_rad),
            ("aero.c_roll_p", self.c_roll_p),
            ("aero.c_roll_r", self.c_roll_r),
            ("aero.c_roll_da_per_rad", self.c_roll_da_per_rad),
            ("aero.c_roll_dr_per_rad", self.c_roll_dr_per_rad),
            ("aero.c_yaw_0", self.c_yaw_0),
            ("aero.c_yaw_beta_per_rad", self.c_yaw_beta_per_rad),
            ("aero.c_yaw_p", self.c_yaw_p),
            ("aero.c_yaw_r", self.c_yaw_r),
            ("aero.c_yaw_da_per_rad", self.c_yaw_da_per_rad),
            ("aero.c_yaw_dr_per_rad", self.c_yaw_dr_per_rad),
        ];
        for (key, value) in finite {
            check::in_closed(key, value, -1e3, 1e3)?;
        }
        // Trim needs a lift slope and a pitch control; the drag polar needs C_D0 ≥ 0, 0 < e ≤ 1.
        check::in_closed(
            "aero.c_lift_alpha_per_rad",
            self.c_lift_alpha_per_rad,
            0.1,
            1e3,
        )?;
        check::require(
            self.c_pitch_de_per_rad.is_finite() && self.c_pitch_de_per_rad.abs() >= 1e-3,
            "aero.c_pitch_de_per_rad",
            self.c_pitch_de_per_rad,
            "a finite number with |value| >= 0.001",
        )?;
        check::in_closed("aero.c_drag_0", self.c_drag_0, 0.0, 10.0)?;
        check::in_closed("aero.oswald_efficiency", self.oswald_efficiency, 0.05, 1.0)?;
        check::in_closed("aero.stall_alpha_rad", self.stall_alpha_rad, 0.05, 1.5)?;
        check::in_closed(
            "aero.stall_transition_per_rad",
            self.stall_transition_per_rad,
            1.0,
            1e3,
        )
    }
}

/// Thrust model of (7.19): T = ½ρV² S C_TδT δT along body x.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Propulsion {
    /// C_TδT, thrust coefficient per unit throttle.
    pub c_thrust_throttle: f64,
}

impl Propulsion {
    fn validate(&self) -> Check {
        check::in_closed(
            "propulsion.c_thrust_throttle",
            self.c_thrust_throttle,
            1e-4,
            100.0,
        )
    }
}

/// One control surface's actuator as written in the file (degrees).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceActuatorFile {
    /// Symmetric position limit ±`limit_deg`, degrees.
    pub limit_deg: f64,
    /// Rate limit, degrees per second.
    pub rate_limit_deg_s: f64,
    /// Time constant of the first-order lag, s.
    pub time_constant_s: f64,
}

impl SurfaceActuatorFile {
    fn validate(&self, name: &str) -> Check {
        check::in_closed(&format!("{name}.limit_deg"), self.limit_deg, 0.1, 90.0)?;
        check::in_closed(
            &format!("{name}.rate_limit_deg_s"),
            self.rate_limit_deg_s,
            1.0,
            1e5,
        )?;
        check::in_closed(
            &format!("{name}.time_constant_s"),
            self.time_constant_s,
            1e-4,
            10.0,
        )
    }

    fn limits(&self) -> ActuatorLimits {
        let limit_rad = self.limit_deg.to_radians();
        ActuatorLimits {
            min: -limit_rad,
            max: limit_rad,
            rate_limit_per_s: self.rate_limit_deg_s.to_radians(),
            time_constant_s: self.time_constant_s,
        }
    }
}

/// The throttle's actuator as written in the file (its range is always [0, 1]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThrottleActuatorFile {
    /// Rate limit, throttle fraction per second.
    pub rate_limit_per_s: f64,
    /// Time constant of the first-order lag, s.
    pub time_constant_s: f64,
}

impl ThrottleActuatorFile {
    fn validate(&self) -> Check {
        check::in_closed(
            "actuators.throttle.rate_limit_per_s",
            self.rate_limit_per_s,
            1e-3,
            1e4,
        )?;
        check::in_closed(
            "actuators.throttle.time_constant_s",
            self.time_constant_s,
            1e-4,
            10.0,
        )
    }

    fn limits(&self) -> ActuatorLimits {
        ActuatorLimits {
            min: 0.0,
            max: 1.0,
            rate_limit_per_s: self.rate_limit_per_s,
            time_constant_s: self.time_constant_s,
        }
    }
}

/// `[actuators]` as written in the file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActuatorsFile {
    /// Elevator δe.
    pub elevator: SurfaceActuatorFile,
    /// Aileron δa.
    pub aileron: SurfaceActuatorFile,
    /// Rudder δr.
    pub rudder: SurfaceActuatorFile,
    /// Throttle δT.
    pub throttle: ThrottleActuatorFile,
}

/// The whole aircraft data file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AircraftFile {
    /// `[mass]`.
    pub mass: MassProperties,
    /// `[geometry]`.
    pub geometry: Geometry,
    /// `[aero]`.
    pub aero: AeroCoefficients,
    /// `[propulsion]`.
    pub propulsion: Propulsion,
    /// `[actuators]`.
    pub actuators: ActuatorsFile,
}

impl AircraftFile {
    /// Checks every value; the error names the key, the value and the allowed range.
    pub fn validate(&self) -> Check {
        self.mass.validate()?;
        self.geometry.validate()?;
        self.aero.validate()?;
        self.propulsion.validate()?;
        self.actuators.elevator.validate("actuators.elevator")?;
        self.actuators.aileron.validate("actuators.aileron")?;
        self.actuators.rudder.validate("actuators.rudder")?;
        self.actuators.throttle.validate()
    }
}

/// Validated aircraft data in the simulator's units (actuator limits in radians).
#[derive(Debug, Clone, PartialEq)]
pub struct AircraftParams {
    /// Mass and inertia.
    pub mass: MassProperties,
    /// Reference geometry.
    pub geometry: Geometry,
    /// Aerodynamic derivatives.
    pub aero: AeroCoefficients,
    /// Thrust model.
    pub propulsion: Propulsion,
    /// Actuator limits and lags.
    pub actuators: Actuators,
}

/// Why an aircraft data file could not be used. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum AircraftFileError {
    /// The file could not be read.
    #[error("{}: cannot read aircraft file: {source}", path.display())]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// TOML syntax error, a missing key, or a key the schema does not accept.
    #[error("{}: {}", path.display(), check::one_line(source))]
    Schema {
        /// The file.
        path: PathBuf,
        /// The parser's error (key and line included).
        source: toml::de::Error,
    },
    /// A value out of its allowed range.
    #[error("{path}: {invalid}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// The key, value and allowed range.
        invalid: InvalidValue,
    },
}

impl AircraftParams {
    /// Reads, parses and validates an aircraft data file.
    pub fn load(path: &Path) -> Result<Self, AircraftFileError> {
        let text =
            std::fs::read_to_string(path).map_err(|source| AircraftFileError::Unreadable {
                path: path.to_path_buf(),
                source,
            })?;
        Self::from_toml_str(&text, path)
    }

    /// Parses aircraft data as if read from `path` (used in messages only).
    pub fn from_toml_str(text: &str, path: &Path) -> Result<Self, AircraftFileError> {
        let file: AircraftFile =
            toml::from_str(text).map_err(|source| AircraftFileError::Schema {
                path: path.to_path_buf(),
                source,
            })?;
        Self::from_file(file).map_err(|invalid| AircraftFileError::Invalid {
            path: path.to_path_buf(),
            invalid,
        })
    }

    /// The seed's follower (seed 7.4 with the Aerosonde derivatives), from the data file built
    /// into the program.
    pub fn seed_follower() -> Result<Self, AircraftFileError> {
        Self::from_toml_str(SEED_FOLLOWER_TOML, Path::new(DEFAULT_AIRCRAFT))
    }

    /// The aircraft a scenario's path names (`follower.aircraft`): the file, or the copy of
    /// the seed's aircraft built into the program when the path is the shipped default and
    /// there is no such file.
    pub fn from_scenario_path(path: &str) -> Result<Self, AircraftFileError> {
        if path == DEFAULT_AIRCRAFT && !Path::new(path).exists() {
            Self::seed_follower()
        } else {
            Self::load(Path::new(path))
        }
    }

    /// These parameters with a speed brake of ΔC_D = `c_drag` at full deflection on the
    /// throttle's channel (see [`super::aero`]): δT's range becomes [-c_drag / C_TδT, 1].
    /// 0 leaves the aircraft as it is.
    pub fn with_speed_brake(mut self, c_drag: f64) -> Self {
        if c_drag > 0.0 {
            self.actuators.throttle.min = -c_drag / self.propulsion.c_thrust_throttle;
        }
        self
    }

    /// Validates parsed file contents and converts them to the simulator's units.
    pub fn from_file(file: AircraftFile) -> Result<Self, InvalidValue> {
        file.validate()?;
        Ok(Self {
            actuators: Actuators {
                elevator: file.actuators.elevator.limits(),
                aileron: file.actuators.aileron.limits(),
                rudder: file.actuators.rudder.limits(),
                throttle: file.actuators.throttle.limits(),
            },
            mass: file.mass,
            geometry: file.geometry,
            aero: file.aero,
            propulsion: file.propulsion,
        })
    }

    /// Re-checks data that may have been edited after loading (the fields are public).
    pub fn validate(&self) -> Check {
        self.mass.validate()?;
        self.geometry.validate()?;
        self.aero.validate()?;
        self.propulsion.validate()?;
        self.actuators.validate()
    }

    /// Induced-drag factor K = 1 / (π e AR) of C_D = C_D0 + K C_L².
    pub fn induced_drag_factor(&self) -> f64 {
        1.0 / (std::f64::consts::PI * self.aero.oswald_efficiency * self.geometry.aspect_ratio())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_follower_parses_with_seed_numbers() {
        let p = AircraftParams::seed_follower().expect("built-in file is valid");
        assert_eq!(p.mass.mass_slug, 0.6293);
        assert_eq!(p.geometry.span_ft, 9.1);
        assert!((p.actuators.rudder.max - 20f64.to_radians()).abs() < 1e-15);
        assert_eq!(p.actuators.throttle.min, 0.0);
        assert!(p.validate().is_ok());
    }

    #[test]
    fn inertia_has_minus_jxz_off_diagonal() {
        let mut p = AircraftParams::seed_follower().expect("valid");
        p.mass.jxz_slug_ft2 = 0.01;
        let j = p.mass.inertia_slug_ft2();
        assert_eq!(j[(0, 2)], -0.01);
        assert_eq!(j[(2, 0)], -0.01);
    }
}
