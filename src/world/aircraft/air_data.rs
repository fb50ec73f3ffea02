//! Air data of the plant: the quantities of the seed's wind/body form (7.15)-(7.19) that a
//! flight controller and the telemetry use.

use crate::frames::{EulerAngles, Vec3};

use super::aero::{AirAngles, Loads};
use super::state::AircraftState;

/// Airspeed, angles, rates and loads at one instant (true values, perturbations included).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirData {
    /// Airspeed V (air-relative), ft/s.
    pub airspeed_fps: f64,
    /// Angle of attack α, rad.
    pub alpha_rad: f64,
    /// Sideslip β, rad.
    pub beta_rad: f64,
    /// 3-2-1 Euler angles φ, θ, ψ.
    pub euler: EulerAngles,
    /// Body rates (p, q, r), rad/s.
    pub body_rates_rps: Vec3,
    /// Flight-path angle γ of the inertial velocity (positive climbing), rad; 0 at rest.
    pub flight_path_rad: f64,
    /// Course χ of the inertial velocity (from north, positive east), rad; 0 at rest.
    pub course_rad: f64,
    /// Inertial velocity, NED, ft/s.
    pub velocity_ned_fps: Vec3,
    /// Drag D (wind axes, drag perturbation included), lbf.
    pub drag_lbf: f64,
    /// Lift L (wind axes), lbf.
    pub lift_lbf: f64,
    /// Side force Y along +y_w, lbf (the seed's C of (7.16) is -Y).
    pub side_force_lbf: f64,
    /// Thrust T along body x, lbf (7.19).
    pub thrust_lbf: f64,
    /// Dynamic pressure ½ρV², lbf/ft².
    pub dynamic_pressure_lbf_ft2: f64,
    /// Body moments (L, M, N), moment biases included, lbf ft.
    pub moment_body_lbf_ft: Vec3,
}

impl AirData {
    pub(super) fn new(state: &AircraftState, air: &AirAngles, loads: &Loads) -> Self {
        let velocity_ned_fps = state.velocity_ned_fps();
        let speed = velocity_ned_fps.norm();
        let (flight_path_rad, course_rad) = if speed > 0.0 {
            (
                (-velocity_ned_fps.z / speed).clamp(-1.0, 1.0).asin(),
                velocity_ned_fps.y.atan2(velocity_ned_fps.x),
            )
        } else {
            (0.0, 0.0)
        };
        Self {
            airspeed_fps: air.airspeed_fps,
            alpha_rad: air.alpha_rad,
            beta_rad: air.beta_rad,
            euler: state.euler(),
            body_rates_rps: state.body_rates_rps,
            flight_path_rad,
            course_rad,
            velocity_ned_fps,
            drag_lbf: loads.drag_lbf,
            lift_lbf: loads.lift_lbf,
            side_force_lbf: loads.side_force_lbf,
            thrust_lbf: loads.thrust_lbf,
            dynamic_pressure_lbf_ft2: loads.dynamic_pressure_lbf_ft2,
            moment_body_lbf_ft: loads.moment_body_lbf_ft,
        }
    }
}
