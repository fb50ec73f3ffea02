//! What the follower knows of its own state (`[navigation]`; docs/equations.md, The follower's
//! own navigation and sensors): its INS/GPS solution ([`ins_gps`]), its air data
//! ([`air_data`]) and its camera's geometry ([`camera_geometry`]), each the truth (`perfect`,
//! the default) or the truth plus a seeded error model with a random stream of its own.
//!
//! The simulation advances [`OwnSensors`] once a tick and holds its errors over the step. The
//! navigation solution feeds every consumer of the follower's own state: the estimator (its
//! velocity and displacement), the sensing transform (attitude, camera mount, gimbal angles,
//! frame stamps), the gimbal's pointing, the guidance (attitude of the command frame, velocity
//! feedback) and the autopilot's wind estimate (with the air data). The plant, the flight
//! controller's inner loops and the renderer keep the truth: they are the physics, not
//! anything the follower believes.

pub mod air_data;
pub mod camera_geometry;
pub mod gauss_markov;
pub mod ins_gps;

pub use air_data::{AirDataErrors, AirDataSensor};
pub use camera_geometry::CameraGeometryErrors;
pub use ins_gps::InsGps;

use crate::frames::{EulerAngles, Vec3};
use crate::scenario::{NavigationMode, Scenario, SensorErrors};
use crate::world::aircraft::AirData;

/// Mixed into `[run] seed` for the INS/GPS's random stream ("ins_gps" in ASCII).
pub const INS_GPS_SEED_SALT: u64 = 0x0069_6e73_5f67_7073;
/// Mixed into `[run] seed` for the air data's random stream ("airdata").
pub const AIR_DATA_SEED_SALT: u64 = 0x0061_6972_6461_7461;
/// Mixed into `[run] seed` for the camera geometry's random stream ("camgeom").
pub const CAMERA_GEOMETRY_SEED_SALT: u64 = 0x0063_616d_6765_6f6d;

/// The navigation solution less the truth at an instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NavigationErrors {
    /// Position error, NED, ft.
    pub position_ned_ft: Vec3,
    /// Velocity error, NED, ft/s.
    pub velocity_ned_fps: Vec3,
    /// Roll, pitch and heading errors [δφ, δθ, δψ], rad.
    pub attitude_rad: Vec3,
    /// Error of the position the INS carries from its velocity alone since the start,
    /// ∫ e_v dt, NED, ft (`estimator.own_motion = "inertial"`).
    pub inertial_position_ned_ft: Vec3,
}

impl NavigationErrors {
    /// The navigated attitude of a follower at `truth`.
    pub fn attitude(&self, truth: &EulerAngles) -> EulerAngles {
        let e = &self.attitude_rad;
        EulerAngles::new(
            truth.phi_rad + e.x,
            truth.theta_rad + e.y,
            truth.psi_rad + e.z,
        )
    }
}

/// What the follower's own sensors get wrong over a tick, as the autopilot's wind estimate
/// reads them: the navigation's errors (zero when it is perfect) and the air data's.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OwnStateErrors {
    /// The INS/GPS's errors.
    pub navigation: NavigationErrors,
    /// The air data's errors.
    pub air_data: AirDataErrors,
}

impl OwnStateErrors {
    /// The air data as the follower senses it: airspeed, α and β with the air data's errors,
    /// attitude and inertial velocity from its navigation; the rest (loads, rates) as they are.
    pub fn sensed_air_data(&self, truth: &AirData) -> AirData {
        AirData {
            airspeed_fps: truth.airspeed_fps + self.air_data.airspeed_fps,
            alpha_rad: truth.alpha_rad + self.air_data.alpha_rad,
            beta_rad: truth.beta_rad + self.air_data.beta_rad,
            euler: self.navigation.attitude(&truth.euler),
            velocity_ned_fps: truth.velocity_ned_fps + self.navigation.velocity_ned_fps,
            ..*truth
        }
    }
}

/// The follower's own sensors of one run: each `None` when perfect.
#[derive(Debug, Clone)]
pub struct OwnSensors {
    ins: Option<InsGps>,
    air_data: Option<AirDataSensor>,
    camera: Option<CameraGeometryErrors>,
}

impl OwnSensors {
    /// The sensors `[navigation]` states, for a follower starting at `attitude`.
    pub fn new(scenario: &Scenario, attitude: &EulerAngles) -> Self {
        let n = &scenario.navigation;
        let seed = scenario.run.seed;
        Self {
            ins: (n.mode == NavigationMode::InsGps)
                .then(|| InsGps::new(n, seed ^ INS_GPS_SEED_SALT, attitude)),
            air_data: (n.air_data.mode == SensorErrors::Errors)
                .then(|| AirDataSensor::new(&n.air_data, seed ^ AIR_DATA_SEED_SALT)),
            camera: (n.camera.mode == SensorErrors::Errors).then(|| {
                let roll_axis = scenario.camera.gimbal.kind.has_roll_axis();
                CameraGeometryErrors::new(&n.camera, roll_axis, seed ^ CAMERA_GEOMETRY_SEED_SALT)
            }),
        }
    }

    /// Advances every error model by one tick of `dt_s` for a follower at `attitude`.
    pub fn advance(&mut self, dt_s: f64, attitude: &EulerAngles) {
        if let Some(ins) = &mut self.ins {
            ins.advance(dt_s, attitude);
        }
        if let Some(air) = &mut self.air_data {
            air.advance(dt_s);
        }
        if let Some(camera) = &mut self.camera {
            camera.advance();
        }
    }

    /// The INS/GPS, when the navigation is not perfect.
    pub fn ins(&self) -> Option<&InsGps> {
        self.ins.as_ref()
    }

    /// The navigation's errors now (`None`: perfect).
    pub fn navigation_errors(&self) -> Option<NavigationErrors> {
        self.ins.as_ref().map(InsGps::errors)
    }

    /// The errors the autopilot's wind estimate reads through (`None`: navigation and air
    /// data both perfect).
    pub fn own_state_errors(&self) -> Option<OwnStateErrors> {
        (self.ins.is_some() || self.air_data.is_some()).then(|| OwnStateErrors {
            navigation: self.navigation_errors().unwrap_or_default(),
            air_data: self
                .air_data
                .as_ref()
                .map_or_else(AirDataErrors::default, AirDataSensor::errors),
        })
    }

    /// The camera's geometry errors (`None`: perfect).
    pub fn camera(&self) -> Option<&CameraGeometryErrors> {
        self.camera.as_ref()
    }

    /// The camera's geometry errors, to stamp a frame (`None`: perfect).
    pub fn camera_mut(&mut self) -> Option<&mut CameraGeometryErrors> {
        self.camera.as_mut()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sensed air data carries the air data's errors on V, α, β and the navigation's on
    /// attitude and inertial velocity, and the truth in everything else.
    #[test]
    fn the_sensed_air_data_carries_every_error() {
        let truth = AirData {
            airspeed_fps: 50.0,
            alpha_rad: 0.2,
            beta_rad: 0.01,
            euler: EulerAngles::new(0.1, 0.05, 1.0),
            body_rates_rps: Vec3::new(0.1, 0.2, 0.3),
            flight_path_rad: 0.0,
            course_rad: 1.0,
            velocity_ned_fps: Vec3::new(30.0, 40.0, 0.0),
            drag_lbf: 1.0,
            lift_lbf: 2.0,
            side_force_lbf: 3.0,
            thrust_lbf: 4.0,
            dynamic_pressure_lbf_ft2: 5.0,
            moment_body_lbf_ft: Vec3::new(6.0, 7.0, 8.0),
        };
        let errors = OwnStateErrors {
            navigation: NavigationErrors {
                position_ned_ft: Vec3::new(9.0, 9.0, 9.0),
                velocity_ned_fps: Vec3::new(0.5, -0.5, 0.25),
                attitude_rad: Vec3::new(0.01, 0.02, 0.03),
                inertial_position_ned_ft: Vec3::zeros(),
            },
            air_data: AirDataErrors {
                airspeed_fps: 1.5,
                alpha_rad: -0.02,
                beta_rad: 0.03,
            },
        };
        let sensed = errors.sensed_air_data(&truth);
        assert_eq!(sensed.airspeed_fps, 51.5);
        assert_eq!(sensed.alpha_rad, 0.2 - 0.02);
        assert_eq!(sensed.beta_rad, 0.01 + 0.03);
        let e = &sensed.euler;
        let attitude_error = Vec3::new(e.phi_rad - 0.1, e.theta_rad - 0.05, e.psi_rad - 1.0);
        assert!((attitude_error - Vec3::new(0.01, 0.02, 0.03)).norm() < 1e-15);
        assert_eq!(sensed.velocity_ned_fps, Vec3::new(30.5, 39.5, 0.25));
        assert_eq!(sensed.body_rates_rps, truth.body_rates_rps);
        assert_eq!(sensed.moment_body_lbf_ft, truth.moment_body_lbf_ft);
        assert_eq!(
            sensed.dynamic_pressure_lbf_ft2,
            truth.dynamic_pressure_lbf_ft2
        );
    }
}
