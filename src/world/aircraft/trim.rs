//! Trim for straight and level flight: wings level, β = 0, p = q = r = 0, θ = α (air-relative
//! flight path level), solved by Newton iteration for (α, δe, δT) so that u̇ = ẇ = q̇ = 0 in the
//! plant's own equations (so the trimmed state is an equilibrium of exactly what is integrated).
//! Aileron and rudder stay at zero; a lateral residual (asymmetric data or a roll/yaw moment
//! bias) is reported as an error rather than trimmed.

use nalgebra::{Matrix3, Vector3};

use crate::frames::{EulerAngles, Vec3};
use crate::world::atmosphere::AtmosphereSample;

use super::aero::AirAngles;
use super::dynamics::Aircraft;
use super::state::{AircraftState, BODY_RATES_RPS, Controls, STATE_LEN, VELOCITY_BODY_FPS};

/// Largest acceleration residual accepted as trimmed (ft/s² and rad/s²).
pub const TRIM_TOLERANCE: f64 = 1e-9;
/// Newton iterations before giving up.
const MAX_ITERATIONS: usize = 100;

/// Straight and level flight to trim for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrimRequest {
    /// Airspeed V, ft/s.
    pub airspeed_fps: f64,
    /// Position of the aircraft, NED, ft.
    pub position_ned_ft: Vec3,
    /// Heading ψ, rad (the air-relative velocity points along it).
    pub heading_rad: f64,
    /// The air: density, steady horizontal wind, Δ perturbations (gusts must be zero).
    pub air: AtmosphereSample,
}

/// A trimmed flight condition.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trim {
    /// The equilibrium state (actuators at the trimmed controls).
    pub state: AircraftState,
    /// Commands that hold it.
    pub controls: Controls,
    /// Trimmed angle of attack α (= θ), rad.
    pub alpha_rad: f64,
    /// Largest |u̇|, |v̇|, |ẇ|, |ṗ|, |q̇|, |ṙ| left at the solution.
    pub residual: f64,
    /// Newton iterations used.
    pub iterations: usize,
}

/// Why no trim was found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TrimError {
    /// A request value out of range.
    #[error("trim request: {key} = {value} is invalid: allowed {allowed}")]
    InvalidRequest {
        /// The request field.
        key: &'static str,
        /// Its value.
        value: String,
        /// What it may hold.
        allowed: &'static str,
    },
    /// Newton iteration did not converge.
    #[error(
        "no trim at {airspeed_fps} ft/s: Newton iteration left a residual of {residual:e} after {iterations} iterations"
    )]
    NotConverged {
        /// Requested airspeed, ft/s.
        airspeed_fps: f64,
        /// Residual at the last iterate.
        residual: f64,
        /// Iterations run.
        iterations: usize,
    },
    /// The required throttle lies outside [0, 1].
    #[error("no trim at {airspeed_fps} ft/s: it needs throttle {required}, outside [0, 1]")]
    ThrottleOutOfRange {
        /// Requested airspeed, ft/s.
        airspeed_fps: f64,
        /// Throttle the equilibrium needs.
        required: f64,
    },
    /// The required elevator lies outside its limits.
    #[error(
        "no trim at {airspeed_fps} ft/s: it needs elevator {required_deg}°, outside ±{limit_deg}°"
    )]
    ElevatorOutOfRange {
        /// Requested airspeed, ft/s.
        airspeed_fps: f64,
        /// Elevator the equilibrium needs, degrees.
        required_deg: f64,
        /// The elevator's limit, degrees.
        limit_deg: f64,
    },
    /// The equilibrium lies beyond the stall angle.
    #[error(
        "no trim at {airspeed_fps} ft/s: it needs α = {alpha_deg}°, beyond the stall at {stall_deg}°"
    )]
    BeyondStall {
        /// Requested airspeed, ft/s.
        airspeed_fps: f64,
        /// Angle of attack of the equilibrium, degrees.
        alpha_deg: f64,
        /// Stall angle α0, degrees.
        stall_deg: f64,
    },
    /// Aileron and rudder at zero leave a lateral residual.
    #[error(
        "no symmetric trim: with zero aileron and rudder the lateral residual is {residual:e} (asymmetric data or a roll/yaw moment bias)"
    )]
    LateralResidual {
        /// Largest |v̇|, |ṗ|, |ṙ|.
        residual: f64,
    },
}

/// Trims `aircraft` for straight and level flight as `request` asks.
pub fn trim_level_flight(aircraft: &Aircraft, request: &TrimRequest) -> Result<Trim, TrimError> {
    validate(request)?;
    let params = aircraft.params();
    let v = request.airspeed_fps;
    let air = AtmosphereSample {
        gust_body_fps: Vec3::zeros(),
        ..request.air
    };

    // Initial guess from the linear model: lift = weight, C_m = 0, thrust = drag.
    let qs = 0.5 * air.density_slug_ft3 * v * v * params.geometry.wing_area_ft2;
    let weight = params.mass.mass_slug * crate::frames::GRAVITY_FPS2;
    let a = &params.aero;
    let alpha0 = ((weight / qs - a.c_lift_0) / a.c_lift_alpha_per_rad).clamp(-0.3, 0.3);
    let de0 = -(a.c_pitch_0 + a.c_pitch_alpha_per_rad * alpha0) / a.c_pitch_de_per_rad;
    let lift0 = a.c_lift_0 + a.c_lift_alpha_per_rad * alpha0;
    let drag0 = a.c_drag_0 + params.induced_drag_factor() * lift0 * lift0;
    let dt0 = air.drag_factor * drag0 / params.propulsion.c_thrust_throttle;
    let mut z = Vector3::new(alpha0, de0.clamp(-1.0, 1.0), dt0.clamp(0.0, 2.0));

    let residual_of = |z: &Vector3<f64>| longitudinal_residual(aircraft, request, &air, z);
    let mut r = residual_of(&z);
    let mut iterations = 0;
    while r.amax() > TRIM_TOLERANCE {
        if iterations >= MAX_ITERATIONS || !r.iter().all(|c| c.is_finite()) {
            return Err(TrimError::NotConverged {
                airspeed_fps: v,
                residual: r.amax(),
                iterations,
            });
        }
        iterations += 1;
        let jacobian = central_jacobian(&residual_of, &z);
        let Some(step) = jacobian.lu().solve(&(-r)) else {
            return Err(TrimError::NotConverged {
                airspeed_fps: v,
                residual: r.amax(),
                iterations,
            });
        };
        // Limit the step (α by 0.05 rad, δe by 0.1 rad, δT by 0.5) to stay near the linear part.
        let scale = [0.05 / step.x.abs(), 0.1 / step.y.abs(), 0.5 / step.z.abs()]
            .into_iter()
            .fold(1.0f64, f64::min);
        z += step * scale;
        r = residual_of(&z);
    }

    let controls = Controls {
        throttle: z.z,
        elevator_rad: z.y,
        aileron_rad: 0.0,
        rudder_rad: 0.0,
    };
    let state = level_state(request, z.x, &controls);
    check_limits(aircraft, v, z.x, &controls)?;

    // Full residual with the actual plant derivative (actuators at rest on their commands).
    let mut dx = [0.0; STATE_LEN];
    aircraft.derivative(&state.pack(), &controls, &air, &mut dx);
    let (vel, rates) = (VELOCITY_BODY_FPS, BODY_RATES_RPS);
    let lateral = [dx[vel + 1], dx[rates], dx[rates + 2]]
        .into_iter()
        .fold(0.0f64, |m, c| m.max(c.abs()));
    if !dx.iter().all(|c| c.is_finite()) || lateral > 1e3 * TRIM_TOLERANCE {
        return Err(TrimError::LateralResidual { residual: lateral });
    }
    let residual = dx[vel..vel + 3]
        .iter()
        .chain(&dx[rates..rates + 3])
        .fold(0.0f64, |m, c| m.max(c.abs()));
    Ok(Trim {
        state,
        controls,
        alpha_rad: z.x,
        residual,
        iterations,
    })
}

fn validate(request: &TrimRequest) -> Result<(), TrimError> {
    let fail = |key, value: String, allowed| {
        Err(TrimError::InvalidRequest {
            key,
            value,
            allowed,
        })
    };
    if !(request.airspeed_fps.is_finite() && request.airspeed_fps > 0.0) {
        return fail(
            "airspeed_fps",
            request.airspeed_fps.to_string(),
            "a finite number > 0",
        );
    }
    if !request.heading_rad.is_finite() {
        return fail(
            "heading_rad",
            request.heading_rad.to_string(),
            "a finite number",
        );
    }
    if !request.position_ned_ft.iter().all(|c| c.is_finite()) {
        return fail(
            "position_ned_ft",
            format!("{:?}", request.position_ned_ft),
            "three finite numbers",
        );
    }
    let air = &request.air;
    if !(air.density_slug_ft3.is_finite() && air.density_slug_ft3 > 0.0) {
        return fail(
            "air.density_slug_ft3",
            air.density_slug_ft3.to_string(),
            "a finite number > 0",
        );
    }
    if !(air.wind_ned_fps.iter().all(|c| c.is_finite()) && air.wind_ned_fps.z == 0.0) {
        return fail(
            "air.wind_ned_fps",
            format!("{:?}", air.wind_ned_fps),
            "finite and horizontal (zero down component)",
        );
    }
    if !(air.drag_factor.is_finite() && air.drag_factor >= 0.0) {
        return fail(
            "air.drag_factor",
            air.drag_factor.to_string(),
            "a finite number >= 0",
        );
    }
    if !air.moment_bias_body_lbf_ft.iter().all(|c| c.is_finite()) {
        return fail(
            "air.moment_bias_body_lbf_ft",
            format!("{:?}", air.moment_bias_body_lbf_ft),
            "three finite numbers",
        );
    }
    Ok(())
}

/// Wings level, θ = α, air-relative velocity V along the heading, inertial = air + wind.
fn level_state(request: &TrimRequest, alpha_rad: f64, controls: &Controls) -> AircraftState {
    let euler = EulerAngles::new(0.0, alpha_rad, request.heading_rad);
    let air = AirAngles {
        airspeed_fps: request.airspeed_fps,
        alpha_rad,
        beta_rad: 0.0,
    };
    let velocity_body_fps =
        air.air_velocity_body_fps() + euler.body_from_ned() * request.air.wind_ned_fps;
    AircraftState::from_euler(
        request.position_ned_ft,
        &euler,
        velocity_body_fps,
        Vec3::zeros(),
        *controls,
    )
}

/// (u̇, ẇ, q̇) at z = (α, δe, δT), controls not clamped.
fn longitudinal_residual(
    aircraft: &Aircraft,
    request: &TrimRequest,
    air: &AtmosphereSample,
    z: &Vector3<f64>,
) -> Vector3<f64> {
    let controls = Controls {
        throttle: z.z,
        elevator_rad: z.y,
        aileron_rad: 0.0,
        rudder_rad: 0.0,
    };
    let x = level_state(request, z.x, &controls).pack();
    let rates = aircraft.rigid_body_rates(&x, &controls, air);
    Vector3::new(
        rates.velocity_rate_body_fps2.x,
        rates.velocity_rate_body_fps2.z,
        rates.body_rates_rate_rps2.y,
    )
}

fn central_jacobian<F>(f: &F, z: &Vector3<f64>) -> Matrix3<f64>
where
    F: Fn(&Vector3<f64>) -> Vector3<f64>,
{
    let h = 1e-6;
    let mut jacobian = Matrix3::zeros();
    for j in 0..3 {
        let mut plus = *z;
        let mut minus = *z;
        plus[j] += h;
        minus[j] -= h;
        jacobian.set_column(j, &((f(&plus) - f(&minus)) / (2.0 * h)));
    }
    jacobian
}

fn check_limits(
    aircraft: &Aircraft,
    airspeed_fps: f64,
    alpha_rad: f64,
    controls: &Controls,
) -> Result<(), TrimError> {
    let params = aircraft.params();
    let throttle = &params.actuators.throttle;
    if !(controls.throttle >= throttle.min && controls.throttle <= throttle.max) {
        return Err(TrimError::ThrottleOutOfRange {
            airspeed_fps,
            required: controls.throttle,
        });
    }
    let elevator = &params.actuators.elevator;
    if !(controls.elevator_rad >= elevator.min && controls.elevator_rad <= elevator.max) {
        return Err(TrimError::ElevatorOutOfRange {
            airspeed_fps,
            required_deg: controls.elevator_rad.to_degrees(),
            limit_deg: elevator.max.to_degrees(),
        });
    }
    let stall = params.aero.stall_alpha_rad;
    if alpha_rad.abs() >= stall {
        return Err(TrimError::BeyondStall {
            airspeed_fps,
            alpha_deg: alpha_rad.to_degrees(),
            stall_deg: stall.to_degrees(),
        });
    }
    Ok(())
}
