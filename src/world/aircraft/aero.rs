//! Aerodynamic and propulsive loads (7.19; Beard & McLain 2012, eqs. 4.6-4.19).
//!
//! Lift L, drag D and side force Y act in wind axes (x_w along the air-relative velocity);
//! Y is positive along +y_w (to the right), so the seed's side force C of (7.16) is C = -Y.
//! Moments act about the body axes at the centre of gravity; thrust acts along body x through
//! the centre of gravity (no thrust moments: L_T = M_T = N_T = 0 in (7.17)).
//!
//! Beyond the seed, an optional speed brake (`follower.speed_brake_c_drag`) shares the
//! throttle's channel: δT < 0 deploys it, adding ΔC_D = C_TδT |δT| to the drag, along the
//! airflow (so the channel's force per unit δT is ½ρV² S C_TδT either way, and the flight
//! controller's inversion of (7.20) commands it as it commands thrust). The seed's aircraft
//! has none: its δT stays in [0, 1].

use crate::frames::{Mat3, Vec3};

use super::params::AircraftParams;
use super::state::Controls;

/// Below this airspeed (ft/s) α, β and the nondimensional rates are taken as zero (the loads,
/// which scale with V² or V, vanish there anyway).
const MIN_AIRSPEED_FPS: f64 = 1e-6;

/// Airspeed and aerodynamic angles of an air-relative velocity in body axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirAngles {
    /// Airspeed V, ft/s.
    pub airspeed_fps: f64,
    /// Angle of attack α = atan2(w, u), rad.
    pub alpha_rad: f64,
    /// Sideslip β = asin(v / V), rad.
    pub beta_rad: f64,
}

impl AirAngles {
    /// From the air-relative velocity (u_r, v_r, w_r) in body axes, ft/s.
    pub fn from_air_velocity_body(v_air_body_fps: &Vec3) -> Self {
        let airspeed_fps = v_air_body_fps.norm();
        if airspeed_fps.is_nan() || airspeed_fps <= MIN_AIRSPEED_FPS {
            return Self {
                airspeed_fps: airspeed_fps.max(0.0),
                alpha_rad: 0.0,
                beta_rad: 0.0,
            };
        }
        Self {
            airspeed_fps,
            alpha_rad: v_air_body_fps.z.atan2(v_air_body_fps.x),
            beta_rad: (v_air_body_fps.y / airspeed_fps).clamp(-1.0, 1.0).asin(),
        }
    }

    /// The air-relative velocity in body axes: V [cosα cosβ, sinβ, sinα cosβ].
    pub fn air_velocity_body_fps(&self) -> Vec3 {
        let (sa, ca) = self.alpha_rad.sin_cos();
        let (sb, cb) = self.beta_rad.sin_cos();
        self.airspeed_fps * Vec3::new(ca * cb, sb, sa * cb)
    }

    /// Body from wind axes: columns are x_w, y_w, z_w in body components.
    pub fn body_from_wind(&self) -> Mat3 {
        let (sa, ca) = self.alpha_rad.sin_cos();
        let (sb, cb) = self.beta_rad.sin_cos();
        Mat3::new(ca * cb, -ca * sb, -sa, sb, cb, 0.0, sa * cb, -sa * sb, ca)
    }
}

/// Force and moment coefficients at one flight condition.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoefficientValues {
    /// Lift C_L (with the stall blend, q̂ and δe terms).
    pub lift: f64,
    /// Drag C_D = C_D0 + K (C_L0 + C_Lα α)².
    pub drag: f64,
    /// Side force C_Y (positive along +y_w).
    pub side: f64,
    /// Rolling moment C_l.
    pub roll: f64,
    /// Pitching moment C_m.
    pub pitch: f64,
    /// Yawing moment C_n.
    pub yaw: f64,
}

/// Loads on the airframe at one flight condition.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loads {
    /// Dynamic pressure ½ρV², lbf/ft².
    pub dynamic_pressure_lbf_ft2: f64,
    /// Drag D (after the drag perturbation factor; the speed brake's included), lbf.
    pub drag_lbf: f64,
    /// Lift L, lbf.
    pub lift_lbf: f64,
    /// Side force Y along +y_w, lbf.
    pub side_force_lbf: f64,
    /// Thrust T along body x, lbf (7.19).
    pub thrust_lbf: f64,
    /// Aerodynamic plus thrust force in body axes (no gravity), lbf.
    pub force_body_lbf: Vec3,
    /// Moments (L, M, N) about the body axes, moment biases included, lbf ft.
    pub moment_body_lbf_ft: Vec3,
}

/// Dimensional control effectiveness of (7.19) at a dynamic pressure, for inverting it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ControlEffectiveness {
    /// ∂T/∂δT = ½ρV² S C_TδT, lbf per unit throttle.
    pub thrust_per_throttle_lbf: f64,
    /// ∂[L, M, N]/∂[δa, δe, δr], lbf ft per rad: rows L, M, N; columns δa, δe, δr.
    /// = ½ρV² [[S b C_lδa, 0, S b C_lδr], [0, S c C_mδe, 0], [S b C_nδa, 0, S b C_nδr]].
    pub moment_per_surface_lbf_ft: Mat3,
}

/// Lift blend σ(α) of Beard & McLain (4.10): 0 on the linear part, 1 past the stall.
fn stall_blend(alpha_rad: f64, alpha0_rad: f64, sharpness_per_rad: f64) -> f64 {
    // σ = (1 + e^{-M(α-α0)} + e^{M(α+α0)}) / ((1 + e^{-M(α-α0)})(1 + e^{M(α+α0)})), written
    // with exponentials of non-positive arguments so that it never overflows.
    let a = (-sharpness_per_rad * (alpha_rad - alpha0_rad)).min(700.0);
    let b = (sharpness_per_rad * (alpha_rad + alpha0_rad)).min(700.0);
    let (ea, eb) = (a.exp(), b.exp());
    ((1.0 + ea + eb) / ((1.0 + ea) * (1.0 + eb))).clamp(0.0, 1.0)
}

impl AircraftParams {
    /// Force and moment coefficients (Beard & McLain 2012, 4.9-4.15 with the stall blend on
    /// C_L(α); the drag polar C_D0 + K C_L² on the static C_L, docs/equations.md, The 6-DOF
    /// follower).
    pub fn coefficients(
        &self,
        air: &AirAngles,
        body_rates_rps: &Vec3,
        surfaces: &Controls,
    ) -> CoefficientValues {
        let a = &self.aero;
        let g = &self.geometry;
        let (p_hat, q_hat, r_hat) = if air.airspeed_fps > MIN_AIRSPEED_FPS {
            let half_over_v = 0.5 / air.airspeed_fps;
            (
                g.span_ft * body_rates_rps.x * half_over_v,
                g.chord_ft * body_rates_rps.y * half_over_v,
                g.span_ft * body_rates_rps.z * half_over_v,
            )
        } else {
            (0.0, 0.0, 0.0)
        };
        let (alpha, beta) = (air.alpha_rad, air.beta_rad);
        let (de, da, dr) = (
            surfaces.elevator_rad,
            surfaces.aileron_rad,
            surfaces.rudder_rad,
        );
        let linear_lift = a.c_lift_0 + a.c_lift_alpha_per_rad * alpha;
        let sigma = stall_blend(alpha, a.stall_alpha_rad, a.stall_transition_per_rad);
        let (sa, ca) = alpha.sin_cos();
        let flat_plate = 2.0 * alpha.signum() * sa * sa * ca;
        CoefficientValues {
            lift: (1.0 - sigma) * linear_lift
                + sigma * flat_plate
                + a.c_lift_q * q_hat
                + a.c_lift_de_per_rad * de,
            drag: a.c_drag_0 + self.induced_drag_factor() * linear_lift * linear_lift,
            side: a.c_side_0
                + a.c_side_beta_per_rad * beta
                + a.c_side_p * p_hat
                + a.c_side_r * r_hat
                + a.c_side_da_per_rad * da
                + a.c_side_dr_per_rad * dr,
            roll: a.c_roll_0
                + a.c_roll_beta_per_rad * beta
                + a.c_roll_p * p_hat
                + a.c_roll_r * r_hat
                + a.c_roll_da_per_rad * da
                + a.c_roll_dr_per_rad * dr,
            pitch: a.c_pitch_0
                + a.c_pitch_alpha_per_rad * alpha
                + a.c_pitch_q * q_hat
                + a.c_pitch_de_per_rad * de,
            yaw: a.c_yaw_0
                + a.c_yaw_beta_per_rad * beta
                + a.c_yaw_p * p_hat
                + a.c_yaw_r * r_hat
                + a.c_yaw_da_per_rad * da
                + a.c_yaw_dr_per_rad * dr,
        }
    }

    /// Loads (7.19) at one flight condition. `controls` are used as given (the plant passes
    /// actuator positions already inside their limits). `drag_factor` multiplies D and
    /// `moment_bias_body_lbf_ft` adds to (L, M, N): the unmodelled Δ of (7.17)-(7.18).
    pub fn loads(
        &self,
        air: &AirAngles,
        body_rates_rps: &Vec3,
        controls: &Controls,
        density_slug_ft3: f64,
        drag_factor: f64,
        moment_bias_body_lbf_ft: &Vec3,
    ) -> Loads {
        let c = self.coefficients(air, body_rates_rps, controls);
        let qbar = 0.5 * density_slug_ft3 * air.airspeed_fps * air.airspeed_fps;
        let qs = qbar * self.geometry.wing_area_ft2;
        let channel_lbf = qs * self.propulsion.c_thrust_throttle * controls.throttle;
        // δT < 0 is the speed brake's drag, not a reversed thrust.
        let (thrust_lbf, brake_drag_lbf) = if channel_lbf >= 0.0 {
            (channel_lbf, 0.0)
        } else {
            (0.0, -channel_lbf)
        };
        let drag_lbf = drag_factor * qs * c.drag + brake_drag_lbf;
        let lift_lbf = qs * c.lift;
        let side_force_lbf = qs * c.side;
        let aero_body = air.body_from_wind() * Vec3::new(-drag_lbf, side_force_lbf, -lift_lbf);
        let moment = Vec3::new(
            qs * self.geometry.span_ft * c.roll,
            qs * self.geometry.chord_ft * c.pitch,
            qs * self.geometry.span_ft * c.yaw,
        );
        Loads {
            dynamic_pressure_lbf_ft2: qbar,
            drag_lbf,
            lift_lbf,
            side_force_lbf,
            thrust_lbf,
            force_body_lbf: aero_body + Vec3::new(thrust_lbf, 0.0, 0.0),
            moment_body_lbf_ft: moment + moment_bias_body_lbf_ft,
        }
    }

    /// Control effectiveness of (7.19) at dynamic pressure ½ρV² (lbf/ft²).
    pub fn control_effectiveness(&self, dynamic_pressure_lbf_ft2: f64) -> ControlEffectiveness {
        let qs = dynamic_pressure_lbf_ft2 * self.geometry.wing_area_ft2;
        let (a, b, c) = (&self.aero, self.geometry.span_ft, self.geometry.chord_ft);
        ControlEffectiveness {
            thrust_per_throttle_lbf: qs * self.propulsion.c_thrust_throttle,
            moment_per_surface_lbf_ft: qs
                * Mat3::new(
                    b * a.c_roll_da_per_rad,
                    0.0,
                    b * a.c_roll_dr_per_rad,
                    0.0,
                    c * a.c_pitch_de_per_rad,
                    0.0,
                    b * a.c_yaw_da_per_rad,
                    0.0,
                    b * a.c_yaw_dr_per_rad,
                ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> AircraftParams {
        AircraftParams::seed_follower().expect("valid")
    }

    #[test]
    fn angles_round_trip() {
        let air = AirAngles {
            airspeed_fps: 50.0,
            alpha_rad: 0.1,
            beta_rad: -0.05,
        };
        let back = AirAngles::from_air_velocity_body(&air.air_velocity_body_fps());
        assert!((back.alpha_rad - 0.1).abs() < 1e-14 && (back.beta_rad + 0.05).abs() < 1e-14);
        // x_w is the direction of the air-relative velocity, and body_from_wind is a rotation.
        let m = air.body_from_wind();
        let x_w = m.column(0).into_owned() * 50.0;
        assert!((x_w - air.air_velocity_body_fps()).norm() < 1e-12);
        assert!((m * m.transpose() - Mat3::identity()).norm() < 1e-14);
        assert!((m.determinant() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn stall_blend_is_off_at_small_alpha_and_on_past_stall() {
        assert!(stall_blend(0.1, 0.4712, 50.0) < 1e-6);
        assert!(stall_blend(0.8, 0.4712, 50.0) > 1.0 - 1e-6);
        assert!(stall_blend(-0.8, 0.4712, 50.0) > 1.0 - 1e-6);
        assert!(stall_blend(100.0, 0.4712, 50.0).is_finite());
    }

    /// A negative δT is the speed brake: no thrust, ΔD = ½ρV² S C_TδT |δT| along the airflow,
    /// the moments untouched; with a brake the channel's range reaches -ΔC_D / C_TδT.
    #[test]
    fn negative_throttle_is_drag_along_the_airflow() {
        let p = params().with_speed_brake(0.06);
        assert!(
            (p.actuators.throttle.min + 0.2).abs() < 1e-12,
            "0.06 / C_TδT 0.3"
        );
        let air = AirAngles {
            airspeed_fps: 50.0,
            alpha_rad: 0.1,
            beta_rad: 0.02,
        };
        let controls = |throttle: f64| Controls {
            throttle,
            elevator_rad: -0.1,
            aileron_rad: 0.0,
            rudder_rad: 0.0,
        };
        let rates = Vec3::zeros();
        let loads = |t: f64| p.loads(&air, &rates, &controls(t), 0.002377, 1.0, &Vec3::zeros());
        let (clean, braked) = (loads(0.0), loads(-0.2));
        let qs = 0.5 * 0.002377 * 2500.0 * p.geometry.wing_area_ft2;
        assert_eq!(braked.thrust_lbf, 0.0);
        assert!((braked.drag_lbf - clean.drag_lbf - qs * 0.06).abs() < 1e-12);
        let along_airflow = air.body_from_wind() * Vec3::new(-qs * 0.06, 0.0, 0.0);
        assert!((braked.force_body_lbf - clean.force_body_lbf - along_airflow).norm() < 1e-12);
        assert_eq!(braked.moment_body_lbf_ft, clean.moment_body_lbf_ft);
        assert_eq!(params().with_speed_brake(0.0).actuators.throttle.min, 0.0);
    }

    #[test]
    fn zero_airspeed_gives_zero_loads() {
        let air = AirAngles::from_air_velocity_body(&Vec3::zeros());
        let loads = params().loads(
            &air,
            &Vec3::new(1.0, 1.0, 1.0),
            &Controls {
                throttle: 1.0,
                elevator_rad: 0.2,
                aileron_rad: 0.2,
                rudder_rad: 0.2,
            },
            0.002377,
            1.0,
            &Vec3::zeros(),
        );
        assert_eq!(loads.force_body_lbf, Vec3::zeros());
        assert_eq!(loads.moment_body_lbf_ft, Vec3::zeros());
    }

    #[test]
    fn effectiveness_matches_finite_difference_of_loads() {
        let p = params();
        let air = AirAngles {
            airspeed_fps: 50.0,
            alpha_rad: 0.08,
            beta_rad: 0.01,
        };
        let rates = Vec3::new(0.1, -0.05, 0.02);
        let base = Controls {
            throttle: 0.4,
            elevator_rad: -0.1,
            aileron_rad: 0.02,
            rudder_rad: -0.01,
        };
        let moment = |c: &Controls| {
            p.loads(&air, &rates, c, 0.002377, 1.0, &Vec3::zeros())
                .moment_body_lbf_ft
        };
        let eff = p.control_effectiveness(0.5 * 0.002377 * 2500.0);
        let h = 1e-6;
        let columns = [
            Controls {
                aileron_rad: base.aileron_rad + h,
                ..base
            },
            Controls {
                elevator_rad: base.elevator_rad + h,
                ..base
            },
            Controls {
                rudder_rad: base.rudder_rad + h,
                ..base
            },
        ];
        for (j, c) in columns.iter().enumerate() {
            let fd = (moment(c) - moment(&base)) / h;
            let exact = eff.moment_per_surface_lbf_ft.column(j).into_owned();
            assert!(
                (fd - exact).norm() < 1e-6 * exact.norm().max(1.0),
                "column {j}"
            );
        }
    }
}
