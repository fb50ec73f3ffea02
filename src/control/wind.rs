//! The wind estimate ŵ: a low-passed measurement of the wind (inertial minus air-relative
//! velocity, from the air data and the attitude). With `wind_compensation`, (7.1)-(7.3) are
//! applied to the air-relative command V_F - ŵ: the seed's V_c = ‖V_F‖ assumes still air, and
//! in wind (or slow turbulence) it would fly the right airspeed and heading but the wrong
//! inertial velocity.

use super::control_law::ControlLaw;
use super::signals::AutopilotInput;
use super::state::AutopilotState;
use crate::frames::Vec3;
use crate::world::aircraft::{AirAngles, AirData};

impl ControlLaw {
    /// The wind estimate's rate, and the command relative to the air: V_F - ŵ (V_F without
    /// wind compensation), NED, ft/s.
    pub(super) fn air_velocity_cmd_ned_fps(
        &self,
        state: &AutopilotState,
        input: &AutopilotInput,
        rates: &mut AutopilotState,
    ) -> Vec3 {
        let g = &self.gains;
        let air = &input.sensed_air_data;
        let wind_measured = measured_wind_ned_fps(air);
        let wind_estimate = state.wind_estimate_ned_fps;
        if wind_measured.iter().all(|w| w.is_finite()) {
            rates.wind_estimate_ned_fps =
                (wind_measured - wind_estimate) / g.wind_filter_time_constant_s;
        }
        if g.wind_compensation {
            input.velocity_cmd_ned_fps - wind_estimate
        } else {
            input.velocity_cmd_ned_fps
        }
    }
}

/// The air-relative velocity in NED: L_BEᵀ V [cos α cos β, sin β, sin α cos β].
pub(super) fn air_velocity_ned_fps(air: &AirData) -> Vec3 {
    let angles = AirAngles {
        airspeed_fps: air.airspeed_fps,
        alpha_rad: air.alpha_rad,
        beta_rad: air.beta_rad,
    };
    air.euler.body_from_ned().transpose() * angles.air_velocity_body_fps()
}

/// γ of the air-relative velocity, rad (0 at rest).
pub(super) fn air_flight_path_rad(air: &AirData) -> f64 {
    if air.airspeed_fps > 0.0 {
        (-air_velocity_ned_fps(air).z / air.airspeed_fps)
            .clamp(-1.0, 1.0)
            .asin()
    } else {
        0.0
    }
}

/// The wind the air data and the inertial velocity imply: inertial minus air-relative
/// velocity, NED, ft/s.
pub(super) fn measured_wind_ned_fps(air: &AirData) -> Vec3 {
    air.velocity_ned_fps - air_velocity_ned_fps(air)
}
