//! Reference commands from the guidance velocity V_F (seed 7.1, (7.1)-(7.3), Remark 9, (7.14)),
//! and the two additions the 6-DOF follower needs to fly them: the angle of attack that the
//! commanded path needs (from the nominal lift curve, the simplified (7.8)-(7.9)) and limits
//! on the flight path from the thrust range.

use crate::frames::{GRAVITY_FPS2, Vec3, wrap_angle_rad};

/// Below this horizontal speed (ft/s) the course of V_F is undefined and the heading command
/// holds.
pub const MIN_HORIZONTAL_SPEED_FPS: f64 = 1.0;

/// Airspeed, flight path and course of a commanded velocity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityReference {
    /// V_c = ‖V_F‖ (7.1), ft/s.
    pub airspeed_fps: f64,
    /// γ_c = -asin(V_F,z / V_c) (7.2), rad; 0 for a zero command.
    pub flight_path_rad: f64,
    /// χ_c = atan2(V_F,y, V_F,x) (7.3), rad in (-π, π]; `None` when the horizontal speed is
    /// below [`MIN_HORIZONTAL_SPEED_FPS`].
    pub course_rad: Option<f64>,
}

impl VelocityReference {
    /// (7.1)-(7.3) of a commanded NED velocity. A non-finite command gives `None`.
    pub fn from_velocity_ned(velocity_cmd_ned_fps: &Vec3) -> Option<Self> {
        if !velocity_cmd_ned_fps.iter().all(|c| c.is_finite()) {
            return None;
        }
        let airspeed_fps = velocity_cmd_ned_fps.norm();
        let flight_path_rad = if airspeed_fps > 0.0 {
            (-velocity_cmd_ned_fps.z / airspeed_fps)
                .clamp(-1.0, 1.0)
                .asin()
        } else {
            0.0
        };
        let horizontal = velocity_cmd_ned_fps.x.hypot(velocity_cmd_ned_fps.y);
        let course_rad = (horizontal >= MIN_HORIZONTAL_SPEED_FPS)
            .then(|| velocity_cmd_ned_fps.y.atan2(velocity_cmd_ned_fps.x));
        Some(Self {
            airspeed_fps,
            flight_path_rad,
            course_rad,
        })
    }
}

/// The representative of `angle` (mod 2π) nearest `reference`: unwraps a course given in
/// (-π, π] against a continuous filter state, so ψ_c never jumps by 2π.
pub fn unwrap_near_rad(angle: f64, reference: f64) -> f64 {
    reference + wrap_angle_rad(angle - reference)
}

/// Coordinated-turn bank command φ_c = atan(ψ̇_c V / g) ((7.14) with α = β = 0), clamped to
/// ±`max_bank_rad`. Non-finite inputs give 0 (wings level).
pub fn coordinated_turn_bank_rad(
    heading_rate_rps: f64,
    airspeed_fps: f64,
    max_bank_rad: f64,
) -> f64 {
    let bank = (heading_rate_rps * airspeed_fps / GRAVITY_FPS2).atan();
    if bank.is_finite() {
        bank.clamp(-max_bank_rad, max_bank_rad)
    } else {
        0.0
    }
}

/// What the angle-of-attack reference is computed from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AlphaReferenceInput {
    /// m, slug.
    pub mass_slug: f64,
    /// q̄ S, lbf (dynamic pressure times wing area).
    pub dynamic_pressure_area_lbf: f64,
    /// Commanded γ, rad.
    pub flight_path_rad: f64,
    /// Bank φ, rad (the lift must carry the weight through cos φ).
    pub bank_rad: f64,
    /// Thrust T, lbf (T sin α carries part of the weight).
    pub thrust_lbf: f64,
    /// Current α, rad (for T sin α).
    pub alpha_rad: f64,
    /// C_L0.
    pub c_lift_0: f64,
    /// C_Lα, 1/rad.
    pub c_lift_alpha_per_rad: f64,
    /// C_Lδe δe: the lift of the elevator at its present position.
    pub c_lift_elevator: f64,
}

/// The α that the linear lift curve C_L = C_L0 + C_Lα α (+ C_Lδe δe) needs on the commanded
/// path: the quasi-steady normal-force balance of (7.8) with β = 0 and γ̇ neglected,
/// L + T sin α = m g cos γ_c / cos φ, solved for α as the seed does below (7.9).
/// cos φ is floored at cos 60°. `None` when q̄ S or C_Lα is not positive.
pub fn alpha_reference_rad(input: &AlphaReferenceInput) -> Option<f64> {
    if !(input.dynamic_pressure_area_lbf > 0.0 && input.c_lift_alpha_per_rad > 0.0) {
        return None;
    }
    let cos_bank = input.bank_rad.cos().max(0.5);
    let normal_force_lbf = input.mass_slug * GRAVITY_FPS2 * input.flight_path_rad.cos() / cos_bank;
    let lift_lbf = normal_force_lbf - input.thrust_lbf * input.alpha_rad.sin();
    let c_lift = lift_lbf / input.dynamic_pressure_area_lbf;
    let alpha = (c_lift - input.c_lift_0 - input.c_lift_elevator) / input.c_lift_alpha_per_rad;
    alpha.is_finite().then_some(alpha)
}

/// The flight path the airspeed law (7.20) can hold with thrust `thrust_lbf`:
/// sin γ = (T cos α cos β - D_n - m Ŵ_DᵀΦ - m V̇_c) / (m g), as an angle (rad, in
/// [-π/2, π/2]). With T near full thrust it is the steepest climb, with T near idle the steepest
/// descent: beyond them the throttle would saturate and the speed run away, so the flight-path
/// command is held between them (see [`limit_flight_path`]; the autopilot passes V̇_c = 0, the
/// limits of steady speed).
pub fn flight_path_for_thrust_rad(
    thrust_lbf: f64,
    alpha_rad: f64,
    beta_rad: f64,
    drag_lbf: f64,
    mass_slug: f64,
    specific_force_fps2: f64,
) -> f64 {
    let excess =
        thrust_lbf * alpha_rad.cos() * beta_rad.cos() - drag_lbf - mass_slug * specific_force_fps2;
    (excess / (mass_slug * GRAVITY_FPS2))
        .clamp(-1.0, 1.0)
        .asin()
}

/// γ_c held inside [`lowest`, `highest`] (from [`flight_path_for_thrust_rad`] at the thrust
/// margins), except that a limit never pushes the command past level flight: an acceleration
/// demand must not turn a level command into a dive, nor a deceleration demand into a climb.
/// Non-finite limits leave the command alone.
pub fn limit_flight_path(raw_rad: f64, lowest_rad: f64, highest_rad: f64) -> f64 {
    let mut gamma = raw_rad;
    if highest_rad.is_finite() {
        gamma = gamma.min(highest_rad.max(raw_rad.min(0.0)));
    }
    if lowest_rad.is_finite() {
        gamma = gamma.max(lowest_rad.min(raw_rad.max(0.0)));
    }
    gamma
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn references_of_simple_velocities() {
        let r = VelocityReference::from_velocity_ned(&Vec3::new(0.0, 40.0, -30.0)).expect("ok");
        assert!((r.airspeed_fps - 50.0).abs() < 1e-12);
        assert!((r.flight_path_rad - (0.6f64).asin()).abs() < 1e-12);
        assert!((r.course_rad.expect("horizontal") - PI / 2.0).abs() < 1e-12);
        let vertical = VelocityReference::from_velocity_ned(&Vec3::new(0.0, 0.0, 5.0));
        assert_eq!(vertical.expect("finite").course_rad, None);
        assert!(VelocityReference::from_velocity_ned(&Vec3::new(f64::NAN, 0.0, 0.0)).is_none());
    }

    #[test]
    fn unwrap_follows_the_reference() {
        assert!((wrap_angle_rad(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_angle_rad(-PI) - PI).abs() < 1e-12);
        // Course -179° seen from a filter state at 179°: 181°.
        let a = unwrap_near_rad((-179f64).to_radians(), 179f64.to_radians());
        assert!((a - 181f64.to_radians()).abs() < 1e-12);
        let b = unwrap_near_rad(0.1, 4.0 * PI);
        assert!((b - (4.0 * PI + 0.1)).abs() < 1e-12);
    }

    #[test]
    fn bank_of_a_standard_turn() {
        // ψ̇ V = g: 45°.
        let bank = coordinated_turn_bank_rad(GRAVITY_FPS2 / 50.0, 50.0, 1.0);
        assert!((bank - PI / 4.0).abs() < 1e-12);
        assert_eq!(coordinated_turn_bank_rad(10.0, 50.0, 0.5), 0.5);
        assert_eq!(coordinated_turn_bank_rad(f64::NAN, 50.0, 0.5), 0.0);
    }

    #[test]
    fn flight_path_limits_stop_at_level() {
        // Inside the limits: unchanged.
        assert_eq!(limit_flight_path(0.05, -0.1, 0.1), 0.05);
        // A climb above the steepest climb is lowered to it.
        assert_eq!(limit_flight_path(0.2, -0.1, 0.1), 0.1);
        // A limit below level (acceleration demand) lowers a climb only to level…
        assert_eq!(limit_flight_path(0.2, -0.5, -0.3), 0.0);
        // …and leaves a descent alone.
        assert_eq!(limit_flight_path(-0.2, -0.5, -0.3), -0.2);
        // Descents likewise: raised to the steepest descent, never above level.
        assert_eq!(limit_flight_path(-0.2, -0.1, 0.1), -0.1);
        assert_eq!(limit_flight_path(-0.2, 0.3, 0.5), 0.0);
        // A climb is never steepened by the descent limit.
        assert_eq!(limit_flight_path(0.2, 0.3, 0.5), 0.2);
        assert_eq!(limit_flight_path(0.2, f64::NAN, f64::NAN), 0.2);
        // Level flight with thrust = drag: γ = 0.
        assert!(flight_path_for_thrust_rad(2.0, 0.0, 0.0, 2.0, 1.0, 0.0).abs() < 1e-15);
    }

    #[test]
    fn level_alpha_balances_weight() {
        let input = AlphaReferenceInput {
            mass_slug: 1.0,
            dynamic_pressure_area_lbf: 10.0 * GRAVITY_FPS2,
            flight_path_rad: 0.0,
            bank_rad: 0.0,
            thrust_lbf: 0.0,
            alpha_rad: 0.0,
            c_lift_0: 0.0,
            c_lift_alpha_per_rad: 2.0,
            c_lift_elevator: 0.0,
        };
        // C_L = m g / (q̄ S) = 0.1, α = 0.05.
        assert!((alpha_reference_rad(&input).expect("defined") - 0.05).abs() < 1e-12);
    }
}
