//! Step 1 of the controller: V_F → V_c, γ_c, χ_c (7.1)-(7.3), on the air-relative command
//! of [`super::wind`]; γ in (7.20) is the air-relative flight path, as in (7.15).
//!
//! - γ_c is kept between the steepest descent and climb the thrust range allows at steady
//!   speed ([`super::reference::limit_flight_path`]): a commanded speed change does not bend
//!   the path (with the speed reference's rate V̇_m in the limits, a follower slowing at idle
//!   would be held level or climbing while told to descend); the slowing waits.
//! - V_c is kept within [`min_airspeed_cmd_fps`, `max_airspeed_cmd_fps`]: a margin above the
//!   stall speed, and a top speed the seed's thrust model T ∝ V² lacks (its excess thrust at
//!   full throttle grows with V², so an unbounded command, e.g. from a guidance law closing a
//!   gap, would accelerate the aircraft without end).
//! - Beyond the seed, each off by default: `climb_waits_for_speed` and
//!   `descent_waits_for_speed` keep in the climb and descent limits the acceleration or
//!   deceleration the airspeed law asks for (a slow follower gains speed before it climbs, a
//!   fast one sheds it before it dives); `limited_descent_keeps_horizontal_speed` flies a
//!   descent the limit holds short at the command's horizontal speed, V_c = ‖V_h‖ / cos γ_c,
//!   not at its norm; `weave_period_s` turns a command slower than the aircraft can fly into
//!   S-turns: χ_c ± acos(‖V_h‖ / (V_min cos γ_c)), the side alternating every half period,
//!   which keeps the commanded speed along the course; `weave_half_width_ft` alternates the
//!   side by geometry instead ([`slot_weave_side`]), reversing when the follower is that far
//!   off the slot's line (both loops; the clock's S-turns are the Chapter 7 loop's only),
//!   and, while the target turns at `weave_outside_turn_dps` or faster, keeps every leg to
//!   the outside of that turn.
//!   A side of 0 flies no S-turn: the follower sends it while its slot lies beside the target
//!   ([`crate::follower::SlotLine::behind_the_target`]).
//!   By geometry, `weave_deficit_fps` leaves a command up to that much slower than the
//!   floor along the slot's line to the along-track error, in full at or behind the slot and
//!   not at all from `weave_lead_ft` ahead of it ([`accepted_deficit_fps`]).

use super::control_law::ControlLaw;
use super::nominal_model::NominalModel;
use super::prefilter::FilteredCommand;
use super::reference::{VelocityReference, flight_path_for_thrust_rad, limit_flight_path};
use super::signals::AutopilotInput;
use super::state::AutopilotState;
use super::wind::air_flight_path_rad;
use crate::frames::Vec3;
use crate::world::aircraft::AirData;

/// Largest course offset of an S-turn leg (60°: half the commanded speed along the course).
const MAX_WEAVE_OFFSET_RAD: f64 = std::f64::consts::FRAC_PI_3;

/// Step 1's references.
pub(super) struct VelocityReferences {
    /// χ_c of the air-relative command, rad (None when it is vertical or zero).
    pub(super) course_rad: Option<f64>,
    /// V_c, ft/s.
    pub(super) airspeed_cmd_fps: f64,
    /// V_m and V̇_m.
    pub(super) airspeed_ref: FilteredCommand,
    /// e_V = V - V_m, ft/s.
    pub(super) airspeed_error_fps: f64,
    /// γ of the air-relative velocity, rad.
    pub(super) air_flight_path_rad: f64,
    /// γ_c after the limits, rad.
    pub(super) flight_path_cmd_rad: f64,
    /// Whether a limit changed γ_c (the thrust range's, or the energy loop's rate, angle and
    /// thrust limits).
    pub(super) flight_path_limited: bool,
    /// The thrust the outer loop sets, lbf; `None`: (7.20)'s, from the airspeed error
    /// ([`super::inversion`]).
    pub(super) thrust_cmd_lbf: Option<f64>,
}

/// The S-turn leg after `flown_s` of flight: +1 (right of the commanded course) for the first
/// half of each `weave_period_s`, -1 (left) for the second; +1 without S-turns (period 0).
pub fn weave_side(flown_s: f64, weave_period_s: f64) -> f64 {
    if weave_period_s > 0.0 && (flown_s / weave_period_s).fract() >= 0.5 {
        -1.0
    } else {
        1.0
    }
}

/// The S-turn leg flown by geometry: the side (+1 right, -1 left of the commanded course) is
/// kept until the follower is `half_width_ft` to that side of the slot's line
/// (`cross_track_ft`, positive right of the target's estimated track), then reversed; while
/// the target turns at `outside_turn_rps` or faster (`turn_rate_rps`, positive to the right)
/// the side is the turn's outside, whatever the offset (`outside_turn_rps` 0: never).
pub fn slot_weave_side(
    side: f64,
    cross_track_ft: f64,
    turn_rate_rps: f64,
    geometry: &WeaveGeometry,
) -> f64 {
    let half_width_ft = geometry.half_width_ft;
    if geometry.outside_turn_rps > 0.0 && turn_rate_rps.abs() >= geometry.outside_turn_rps {
        -turn_rate_rps.signum()
    } else if side > 0.0 && cross_track_ft > half_width_ft {
        -1.0
    } else if side < 0.0 && cross_track_ft < -half_width_ft {
        1.0
    } else {
        side
    }
}

/// Where the S-turns by geometry reverse (`autopilot.weave_half_width_ft`) and from which
/// turn rate of the target their legs keep to its outside (`weave_outside_turn_dps`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeaveGeometry {
    /// Half width about the slot's line, ft (0: no S-turns by geometry).
    pub half_width_ft: f64,
    /// Turn rate from which the legs keep to the outside, rad/s (0: never).
    pub outside_turn_rps: f64,
}

/// The speed deficit along the slot's line a leg leaves to the slot's along-track error,
/// ft/s (`weave_deficit_fps` with the lead budget `weave_lead_ft`): all of it while the
/// follower is at or behind its slot (`ahead_ft` ≤ 0), none once it is the budget ahead,
/// linearly between.
fn accepted_deficit_fps(deficit_fps: f64, lead_budget_ft: f64, ahead_ft: f64) -> f64 {
    deficit_fps * (1.0 - ahead_ft / lead_budget_ft).clamp(0.0, 1.0)
}

impl ControlLaw {
    /// Step 1: the wind estimate, then V_F → V_c, γ_c, χ_c (held at the filter states for a
    /// non-finite command), the airspeed prefilter, the flight-path limits and the S-turn's
    /// course offset.
    pub(super) fn velocity_references(
        &self,
        state: &AutopilotState,
        input: &AutopilotInput,
        model: &NominalModel,
        rates: &mut AutopilotState,
    ) -> VelocityReferences {
        let g = &self.gains;
        let air = &input.air_data;
        let air_velocity_cmd = self.air_velocity_cmd_ned_fps(state, input, rates);
        let air_flight_path_rad = air_flight_path_rad(air);
        let reference = VelocityReference::from_velocity_ned(&air_velocity_cmd);
        let norm_cmd_fps = reference
            .map_or(state.airspeed_filter[1], |r| r.airspeed_fps)
            .clamp(g.min_airspeed_cmd_fps, g.max_airspeed_cmd_fps);
        let raw_flight_path_rad = reference.map_or(air_flight_path_rad, |r| r.flight_path_rad);
        // What the airspeed law (7.20) asks of the thrust beyond holding the speed, for the
        // norm of the command (the flight-path limits keep it).
        let norm_ref = self.airspeed_filter.derivative(
            &state.airspeed_filter,
            norm_cmd_fps,
            &mut rates.airspeed_filter,
        );
        let airspeed_error_fps = air.airspeed_fps - norm_ref.value;
        let speed_demand_fps2 = norm_ref.rate - g.airspeed_gain_per_s * airspeed_error_fps;
        let flight_path_cmd_rad =
            self.limited_flight_path(raw_flight_path_rad, air, model, speed_demand_fps2);
        // A descent held short of the command (the descent limit raised it).
        let descent_limited = reference.is_some() && flight_path_cmd_rad > raw_flight_path_rad;
        let (airspeed_cmd_fps, airspeed_ref) =
            if descent_limited && g.limited_descent_keeps_horizontal_speed {
                let cmd = self.horizontal_airspeed_cmd_fps(&air_velocity_cmd, flight_path_cmd_rad);
                let filtered = self.airspeed_filter.derivative(
                    &state.airspeed_filter,
                    cmd,
                    &mut rates.airspeed_filter,
                );
                (cmd, filtered)
            } else {
                (norm_cmd_fps, norm_ref)
            };
        VelocityReferences {
            course_rad: self.weave_course_rad(
                input,
                &air_velocity_cmd,
                flight_path_cmd_rad,
                reference.and_then(|r| r.course_rad),
            ),
            airspeed_cmd_fps,
            airspeed_ref,
            airspeed_error_fps,
            air_flight_path_rad,
            flight_path_cmd_rad,
            flight_path_limited: flight_path_cmd_rad != raw_flight_path_rad,
            thrust_cmd_lbf: None,
        }
    }

    /// γ_c kept between the steepest descent and climb that (7.20) can hold with the
    /// throttle inside its range less the margins ([`limit_flight_path`]); unchanged with
    /// `flight_path_limits` off. The limits are those of steady speed (module docs), with
    /// the drag correction Ŵ_DᵀΦ; with `climb_waits_for_speed` the climb's also keeps the
    /// acceleration `speed_demand_fps2` the airspeed law asks for (when positive).
    fn limited_flight_path(
        &self,
        raw_rad: f64,
        air: &AirData,
        model: &NominalModel,
        speed_demand_fps2: f64,
    ) -> f64 {
        let g = &self.gains;
        if !g.flight_path_limits {
            return raw_rad;
        }
        let thrust_per_throttle_lbf = model.effectiveness.thrust_per_throttle_lbf;
        let full = thrust_per_throttle_lbf * self.params.actuators.throttle.max;
        let idle = thrust_per_throttle_lbf * self.params.actuators.throttle.min;
        let margin = g.thrust_margin_fraction * (full - idle);
        let at_thrust = |thrust: f64, specific_force_fps2: f64| {
            flight_path_for_thrust_rad(
                thrust,
                air.alpha_rad,
                air.beta_rad,
                model.nominal_drag_lbf,
                self.params.mass.mass_slug,
                specific_force_fps2,
            )
        };
        let steady = model.drag_correction_fps2;
        let climbing = if g.climb_waits_for_speed {
            steady + speed_demand_fps2.max(0.0)
        } else {
            steady
        };
        let descending = if g.descent_waits_for_speed {
            steady + speed_demand_fps2.min(0.0)
        } else {
            steady
        };
        limit_flight_path(
            raw_rad,
            at_thrust(idle + margin, descending),
            at_thrust(full - margin, climbing),
        )
    }

    /// V_c = ‖V_h‖ / cos γ_c: the command's horizontal air speed on the limited path, within
    /// [`min_airspeed_cmd_fps`, `max_airspeed_cmd_fps`], ft/s.
    fn horizontal_airspeed_cmd_fps(&self, air_velocity_cmd: &Vec3, flight_path_rad: f64) -> f64 {
        let g = &self.gains;
        (air_velocity_cmd.x.hypot(air_velocity_cmd.y) / flight_path_rad.cos())
            .clamp(g.min_airspeed_cmd_fps, g.max_airspeed_cmd_fps)
    }

    /// χ_c with the S-turn's offset: about the command's course `course_rad`, or, with S-turns
    /// by geometry and the slot's line known, about the line's course χ_s, at
    /// acos((V_a·u_s + ΔV) / (V_min cos γ_c)) (at most [`MAX_WEAVE_OFFSET_RAD`]), which keeps
    /// the command's speed along the line (u_s its horizontal direction) but for the deficit
    /// ΔV the slot's along-track error takes ([`accepted_deficit_fps`]; docs/equations.md,
    /// Path stretching with a lead budget). Unchanged without an S-turn.
    pub(super) fn weave_course_rad(
        &self,
        input: &AutopilotInput,
        air_velocity_cmd: &Vec3,
        flight_path_cmd_rad: f64,
        course_rad: Option<f64>,
    ) -> Option<f64> {
        let g = &self.gains;
        if input.weave_side == 0.0 {
            return course_rad;
        }
        let offset_rad = self.weave_offset_rad(air_velocity_cmd, flight_path_cmd_rad);
        match input.slot_line {
            Some(line) if offset_rad > 0.0 && g.weave_half_width_ft > 0.0 => {
                let track_rad = line.track_rad;
                let along_fps =
                    air_velocity_cmd.x * track_rad.cos() + air_velocity_cmd.y * track_rad.sin();
                let slowest_fps = g.min_airspeed_cmd_fps * flight_path_cmd_rad.cos();
                let accepted_fps = accepted_deficit_fps(
                    g.weave_deficit_fps,
                    g.weave_lead_ft,
                    line.ahead_of_slot_ft,
                );
                let offset_rad = ((along_fps + accepted_fps) / slowest_fps)
                    .clamp(-1.0, 1.0)
                    .acos()
                    .min(MAX_WEAVE_OFFSET_RAD);
                Some(track_rad + input.weave_side * offset_rad)
            }
            _ => course_rad.map(|course| course + input.weave_side * offset_rad),
        }
    }

    /// The course offset of an S-turn, rad: when the commanded horizontal air speed is below
    /// the slowest the aircraft flies on the commanded path, V_min cos γ_c, the aircraft flies
    /// V_min at acos(V_h,cmd / (V_min cos γ_c)) (at most [`MAX_WEAVE_OFFSET_RAD`]) off the
    /// commanded course, which keeps the commanded speed along it. 0 with neither
    /// `weave_period_s` nor `weave_half_width_ft`.
    fn weave_offset_rad(&self, air_velocity_cmd: &Vec3, flight_path_cmd_rad: f64) -> f64 {
        let g = &self.gains;
        if g.weave_period_s <= 0.0 && g.weave_half_width_ft <= 0.0 {
            return 0.0;
        }
        let slowest_horizontal_fps = g.min_airspeed_cmd_fps * flight_path_cmd_rad.cos();
        let horizontal_fps = air_velocity_cmd.x.hypot(air_velocity_cmd.y);
        (horizontal_fps / slowest_horizontal_fps)
            .min(1.0)
            .acos()
            .min(MAX_WEAVE_OFFSET_RAD)
    }
}

#[cfg(test)]
mod tests {
    use super::{WeaveGeometry, accepted_deficit_fps, slot_weave_side};

    /// The deficit left to the along-track error: all of it at or behind the slot, half of
    /// it half the budget ahead, none from the budget on.
    #[test]
    fn the_accepted_deficit_falls_with_the_lead() {
        assert_eq!(accepted_deficit_fps(2.0, 5.0, -3.0), 2.0);
        assert_eq!(accepted_deficit_fps(2.0, 5.0, 0.0), 2.0);
        assert!((accepted_deficit_fps(2.0, 5.0, 2.5) - 1.0).abs() < 1e-12);
        assert_eq!(accepted_deficit_fps(2.0, 5.0, 5.0), 0.0);
        assert_eq!(accepted_deficit_fps(2.0, 5.0, 9.0), 0.0);
    }

    const GEOMETRY: WeaveGeometry = WeaveGeometry {
        half_width_ft: 10.0,
        outside_turn_rps: 0.03,
    };

    #[test]
    fn the_slot_weave_reverses_beyond_its_half_width() {
        let side = |side, cross_ft| slot_weave_side(side, cross_ft, 0.0, &GEOMETRY);
        assert_eq!(side(1.0, 9.0), 1.0);
        assert_eq!(side(1.0, 11.0), -1.0);
        assert_eq!(side(-1.0, 11.0), -1.0);
        assert_eq!(side(-1.0, -9.0), -1.0);
        assert_eq!(side(-1.0, -11.0), 1.0);
    }

    /// In a turn from the threshold on, the leg is the outside one (left of a right turn),
    /// however far out the follower is; below it, and with the rule off, it reverses as on
    /// a straight track.
    #[test]
    fn in_a_turn_the_legs_keep_to_its_outside() {
        let off = WeaveGeometry {
            outside_turn_rps: 0.0,
            ..GEOMETRY
        };
        assert_eq!(slot_weave_side(1.0, 0.0, 0.05, &GEOMETRY), -1.0);
        assert_eq!(slot_weave_side(-1.0, -60.0, 0.05, &GEOMETRY), -1.0);
        assert_eq!(slot_weave_side(-1.0, 60.0, -0.03, &GEOMETRY), 1.0);
        assert_eq!(slot_weave_side(1.0, 0.0, 0.029, &GEOMETRY), 1.0);
        assert_eq!(slot_weave_side(-1.0, -60.0, 0.05, &off), 1.0);
    }
}
