//! Step 1 of the controller with `outer_loop = "energy"`: a total-energy outer loop (TECS,
//! as PX4 and ArduPilot fly it; docs/equations.md, The energy outer loop) in place of
//! (7.1)-(7.3) with (7.20).
//!
//! From the air-relative command V_F - ŵ ([`super::wind`]) it takes a height-rate demand
//! ḣ_d (within the climb, descent and flight-path limits) and a speed demand V_c, the
//! airspeed that flies the command's horizontal speed at ḣ_d. Per unit mass and speed, the
//! specific energy rates are a_h = g sin γ (height) and a_v = V̇ (speed); their sum, the
//! total Ṡ, is what thrust and speed brake change (measured as the specific force along the
//! air velocity), their weighted difference, the balance Ḃ = w_h a_h - w_v a_v, what the
//! flight path changes. Thrust sets Ṡ to its demand; γ_c distributes the Ṡ that the thrust
//! range allows so that Ḃ meets its demand: with thrust (or brake) saturated the weights
//! (`energy_speed_weight`) decide whether speed or height gives. The inner loops get what
//! they get from the Chapter 7 loop: V_m, V̇_m, γ_c, χ_c and a thrust. A command slower than
//! the aircraft flies is stretched by geometry (`weave_half_width_ft`,
//! [`super::velocity_command::slot_weave_side`]), not by the clock's S-turns.

use super::control_law::ControlLaw;
use super::nominal_model::NominalModel;
use super::reference::VelocityReference;
use super::signals::AutopilotInput;
use super::state::AutopilotState;
use super::velocity_command::VelocityReferences;
use super::wind::air_flight_path_rad;
use crate::frames::GRAVITY_FPS2;
use crate::world::aircraft::AirData;

/// The energy loop's demands at one instant, per unit mass and speed, ft/s².
struct EnergyDemands {
    /// a_h,d = g ḣ_d / V.
    height: f64,
    /// a_v,d = V̇_m - k_V (V - V_m), the airspeed law's.
    speed: f64,
    /// Whether the rate or flight-path limits cut ḣ_d.
    rate_limited: bool,
}

/// The specific total energy rates Ṡ = (T cos α cos β - D)/m the thrust range allows (less
/// the margins of `thrust_margin_fraction`), with the learned correction I_E, ft/s².
struct EnergyRange {
    lowest: f64,
    highest: f64,
}

/// The speed and height weights (w_v, w_h) of the priority s: (min(s, 1), min(2 - s, 1)).
pub(super) fn energy_weights(speed_weight: f64) -> (f64, f64) {
    (speed_weight.min(1.0), (2.0 - speed_weight).min(1.0))
}

/// The priority flown at airspeed V: s, moved to 2 (speed only) as V falls from
/// (1 + [`UNDERSPEED_BAND`]) V_min to the lowest airspeed command V_min: the seed's thrust
/// T ∝ V² shrinks with the speed, and a height kept at the speed's expense ends in a stall.
pub(super) fn underspeed_weight(
    speed_weight: f64,
    airspeed_fps: f64,
    min_airspeed_fps: f64,
) -> f64 {
    let band_fps = UNDERSPEED_BAND * min_airspeed_fps;
    let depth = ((min_airspeed_fps + band_fps - airspeed_fps) / band_fps).clamp(0.0, 1.0);
    if depth.is_finite() {
        speed_weight + (2.0 - speed_weight) * depth
    } else {
        speed_weight
    }
}

/// The fraction of V_min over which [`underspeed_weight`] moves the priority to speed.
const UNDERSPEED_BAND: f64 = 0.1;

impl ControlLaw {
    /// Step 1 of the energy loop: the wind estimate, the demands, the thrust for the total
    /// energy rate and γ_c for the balance (docs/equations.md, The energy outer loop), with
    /// the integrals' rates written into `rates`.
    pub(super) fn energy_references(
        &self,
        state: &AutopilotState,
        input: &AutopilotInput,
        model: &NominalModel,
        rates: &mut AutopilotState,
    ) -> VelocityReferences {
        let g = &self.gains;
        let air = &input.air_data;
        let air_velocity_cmd = self.air_velocity_cmd_ned_fps(state, input, rates);
        let reference = VelocityReference::from_velocity_ned(&air_velocity_cmd);
        let air_flight_path_rad = air_flight_path_rad(air);
        let speed_fps = air.airspeed_fps.max(g.min_control_airspeed_fps);
        let (climb_rate_fps, rate_limited) = self.height_rate_demand_fps(
            reference.map(|_| -air_velocity_cmd.z),
            speed_fps * air_flight_path_rad.sin(),
            speed_fps,
        );
        let airspeed_cmd_fps = reference
            .map_or(state.airspeed_filter[1], |_| {
                air_velocity_cmd
                    .x
                    .hypot(air_velocity_cmd.y)
                    .hypot(climb_rate_fps)
            })
            .clamp(g.min_airspeed_cmd_fps, g.max_airspeed_cmd_fps);
        let airspeed_ref = self.airspeed_filter.derivative(
            &state.airspeed_filter,
            airspeed_cmd_fps,
            &mut rates.airspeed_filter,
        );
        let airspeed_error_fps = air.airspeed_fps - airspeed_ref.value;
        let demands = EnergyDemands {
            height: GRAVITY_FPS2 * self.shaped_climb_rate_fps(state, climb_rate_fps, rates)
                / speed_fps,
            speed: airspeed_ref.rate - g.airspeed_gain_per_s * airspeed_error_fps,
            rate_limited,
        };
        let (flight_path_cmd_rad, thrust_cmd_lbf, limited) =
            self.energy_commands(state, air, model, &demands, air_flight_path_rad, rates);
        let course_rad = reference.and_then(|r| r.course_rad);
        VelocityReferences {
            // The clock's S-turns are the Chapter 7 loop's only.
            course_rad: if g.weave_half_width_ft > 0.0 {
                self.weave_course_rad(input, &air_velocity_cmd, flight_path_cmd_rad, course_rad)
            } else {
                course_rad
            },
            airspeed_cmd_fps,
            airspeed_ref,
            airspeed_error_fps,
            air_flight_path_rad,
            flight_path_cmd_rad,
            flight_path_limited: limited,
            thrust_cmd_lbf: Some(thrust_cmd_lbf),
        }
    }

    /// ḣ_d, ft/s: the command's climb rate (the present one, `present_fps`, for a
    /// non-finite command) within [-`energy_max_descent_rate_fps`,
    /// `energy_max_climb_rate_fps`] and within V sin γ_max; and whether a limit cut it.
    fn height_rate_demand_fps(
        &self,
        commanded_fps: Option<f64>,
        present_fps: f64,
        speed_fps: f64,
    ) -> (f64, bool) {
        let g = &self.gains;
        let steepest_fps = speed_fps * g.energy_max_flight_path_deg.to_radians().sin();
        let raw = commanded_fps.unwrap_or(present_fps);
        let limited = raw
            .min(g.energy_max_climb_rate_fps)
            .max(-g.energy_max_descent_rate_fps)
            .clamp(-steepest_fps, steepest_fps);
        (limited, limited != raw)
    }

    /// ḣ_d through a first-order lag of `energy_climb_rate_time_constant_s` (ḣ_d itself
    /// with 0), ft/s: a step of the demand would otherwise reach the thrust at once and the
    /// flight path only through the pitch loop's lag, and the difference go into speed.
    fn shaped_climb_rate_fps(
        &self,
        state: &AutopilotState,
        climb_rate_fps: f64,
        rates: &mut AutopilotState,
    ) -> f64 {
        let tau_s = self.gains.energy_climb_rate_time_constant_s;
        if tau_s <= 0.0 {
            return climb_rate_fps;
        }
        let shaped_fps = state.energy_loop[2];
        rates.energy_loop[2] = (climb_rate_fps - shaped_fps) / tau_s;
        shaped_fps
    }

    /// The thrust for the total energy rate demand and γ_c for the balance, with the
    /// integrals' rates; and whether a limit (rates, flight path, thrust range) shaped γ_c.
    fn energy_commands(
        &self,
        state: &AutopilotState,
        air: &AirData,
        model: &NominalModel,
        demands: &EnergyDemands,
        air_flight_path_rad: f64,
        rates: &mut AutopilotState,
    ) -> (f64, f64, bool) {
        let g = &self.gains;
        let mass = self.params.mass.mass_slug;
        let [total_integral, balance_integral, _] = state.energy_loop;
        let cos_alpha_beta = (air.alpha_rad.cos() * air.beta_rad.cos()).max(0.1);
        // Ṡ = (T cos α cos β - D)/m: the specific force along the air velocity.
        let total_fps2 = (air.thrust_lbf * cos_alpha_beta - air.drag_lbf) / mass;
        let height_fps2 = GRAVITY_FPS2 * air_flight_path_rad.sin();
        let total_demand = demands.height + demands.speed;
        let resisting_lbf = model.nominal_drag_lbf + mass * model.drag_correction_fps2;
        let thrust_cmd_lbf =
            (resisting_lbf + mass * (total_demand + total_integral)) / cos_alpha_beta;
        let range = self.energy_range(model, cos_alpha_beta, resisting_lbf, total_integral);
        let available = total_demand.clamp(range.lowest, range.highest);
        let total_error = total_demand - total_fps2;
        let thrust_saturated = (total_demand > range.highest && total_error > 0.0)
            || (total_demand < range.lowest && total_error < 0.0);
        if !thrust_saturated {
            rates.energy_loop[0] = g.energy_thrust_integral_gain_per_s * total_error;
        }
        let (w_speed, w_height) = energy_weights(underspeed_weight(
            g.energy_speed_weight,
            air.airspeed_fps,
            g.min_airspeed_cmd_fps,
        ));
        let balance_demand = w_height * demands.height - w_speed * demands.speed;
        let sin_cmd = (balance_demand + w_speed * available + balance_integral)
            / ((w_height + w_speed) * GRAVITY_FPS2);
        let max_rad = g.energy_max_flight_path_deg.to_radians();
        let flight_path_cmd_rad = sin_cmd.clamp(-1.0, 1.0).asin().clamp(-max_rad, max_rad);
        let angle_limited = sin_cmd.abs() > max_rad.sin();
        if !angle_limited {
            let balance = w_height * height_fps2 - w_speed * (total_fps2 - height_fps2);
            rates.energy_loop[1] =
                g.energy_balance_integral_gain_per_s * (balance_demand - balance);
        }
        let limited = demands.rate_limited || angle_limited || available != total_demand;
        (flight_path_cmd_rad, thrust_cmd_lbf, limited)
    }

    /// The Ṡ range of the throttle channel (speed brake to full thrust) less the margins.
    fn energy_range(
        &self,
        model: &NominalModel,
        cos_alpha_beta: f64,
        resisting_lbf: f64,
        total_integral: f64,
    ) -> EnergyRange {
        let per_throttle = model.effectiveness.thrust_per_throttle_lbf;
        let limits = &self.params.actuators.throttle;
        let (idle, full) = (per_throttle * limits.min, per_throttle * limits.max);
        let margin = self.gains.thrust_margin_fraction * (full - idle);
        let mass = self.params.mass.mass_slug;
        let at =
            |thrust_lbf: f64| (thrust_lbf * cos_alpha_beta - resisting_lbf) / mass - total_integral;
        EnergyRange {
            lowest: at(idle + margin),
            highest: at(full - margin),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{energy_weights, underspeed_weight};

    #[test]
    fn weights_follow_the_tecs_priority() {
        assert_eq!(energy_weights(0.0), (0.0, 1.0));
        assert_eq!(energy_weights(1.0), (1.0, 1.0));
        assert_eq!(energy_weights(2.0), (1.0, 0.0));
        assert_eq!(energy_weights(1.5), (1.0, 0.5));
    }

    #[test]
    fn underspeed_gives_the_speed_priority() {
        assert_eq!(underspeed_weight(0.0, 40.0, 35.0), 0.0);
        assert_eq!(underspeed_weight(0.0, 38.5, 35.0), 0.0);
        assert!((underspeed_weight(0.0, 36.75, 35.0) - 1.0).abs() < 1e-12);
        assert_eq!(underspeed_weight(0.0, 35.0, 35.0), 2.0);
        assert_eq!(underspeed_weight(1.0, 20.0, 35.0), 2.0);
    }
}
