//! Acceleration guidance (Chapter 5, SPEC §5) and its noisy-measurement form (6.39)-(6.42).
//!
//! Per axis i the plant is x_i = [r_i, ṙ_i], ẋ = A x + (1/b) B (a_T - a_F), y = C x = r. The
//! input-filtered coordinates z = x - (1/b) B (w + d) (5.2)-(5.5) have relative degree one;
//! the law tracks a reference model z_m (5.6) with an observer ẑ (5.10), the virtual control
//! w_f = b̂ h - S_f d̂ (5.33)-(5.36) and the backstepping command
//! a_F = -Λ w_f - ẇ_f + y_a (5.38, sign fixed by SPEC §5), with ẇ_f computed exactly from
//! the right-hand sides of every state it depends on.
//!
//! Interception (Remark 6) is the same law with y_c ≡ 0: feed R_c = 0, no excitation and
//! `shaping_pole_rps = 0`; then h = -K ẑ, w_f = -b̂ K ẑ - S_f d̂ and
//! b̂' = ρ Proj(b̂, y_aᵀ K ẑ) exactly as (5.28)-(5.29). With the shaping filter on, y_c decays
//! from r(0) to 0 with the filter's pole instead of jumping to 0.
//!
//! With noisy measurements (6.39)-(6.42) nothing changes but the input: pass y* = r* as
//! `r_measured`; y*_a = 2y* - y_m - C ẑ follows. The observer gain can come from the Riccati
//! equation (6.62), see [`ObserverGainDesign`].
//!
//! Units: w, w_f, d̂ in ft/s (filtered accelerations); y, y_c, y_m, y_a scaled (multiples of b);
//! a_F in ft/s². The seed's (5.38) adds the scaled y_a to accelerations with a unit
//! coefficient (ft/s² per scaled unit); that is kept.
//!
//! State slice layout (see [`layout`]): `[w (3), z_m (6), ẑ (6), S_f (3), b̂, d̂ (3), r_cf (3)]`,
//! 25 values, and χ (3) with compensation; z_m and ẑ are stored per axis as
//! `[z_x1, z_x2, z_y1, z_y2, z_z1, z_z2]` (z_i1 ~ r_i, z_i2 ~ ṙ_i).
//!
//! Compensation for a follower that does not realise a_F (the 6-DOF aircraft; beyond the
//! seed). The law's design assumes the follower flies V_F = V_F(0) + ∫ a_F; an aircraft's
//! velocity V_a lags V_F by a second or two and is bounded. Left alone, the lag enters y
//! as if the target had manoeuvred, the observer, d̂ and b̂ chase it and a_F grows until the
//! follower loses the target (measured). The follower's own navigation gives the shortfall
//! s = V_F - V_a; its leaky integral χ' = s - χ/τ (ft) is how far the follower is behind
//! where a_F would have put it, recently. The law runs on y - χ/b̂, the measurement as if the
//! follower had realised its commands over the last τ (as the velocity law's compensation
//! of command-filtered backstepping does, [`super::velocity`]); a shortfall that lasts
//! longer than τ (a climb the thrust cannot hold) shows in y and is corrected. With V_a = V_F
//! χ stays 0 and this is the seed's law.

use super::law::GuidanceInput;
use super::projection::{BallBound, IntervalBound};
use crate::frames::Vec3;
use crate::linalg::solve_continuous_are;
use crate::scenario::{AccelerationSection, GuidanceSection, ObserverGainMode};
use nalgebra::{DMatrix, Matrix2, Vector2};

/// Offsets into the acceleration law's state slice.
pub mod layout {
    /// w (3): the filtered follower acceleration, ẇ = -Λ w - a_F (5.3), ft/s.
    pub const W: usize = 0;
    /// z_m (6): reference-model state (5.6), two per axis.
    pub const Z_M: usize = 3;
    /// ẑ (6): observer state (5.10), two per axis.
    pub const Z_HAT: usize = 9;
    /// S_f (3): the diagonal of the filtered smooth sign (5.34).
    pub const S_F: usize = 15;
    /// b̂: estimate of the target's size b, ft (5.20).
    pub const B_HAT: usize = 18;
    /// d̂ (3): adaptive bound of the filtered target acceleration d, ft/s (5.41).
    pub const D_HAT: usize = 19;
    /// r_cf (3): command-shaping filter ṙ_cf = -p (r_cf - R_c / b̂) (Chapter 4).
    pub const R_CF: usize = 22;
    /// Length of the slice without compensation.
    pub const LEN: usize = 25;
    /// χ (3), with compensation: leaky integral of the follower's velocity shortfall, ft.
    pub const CHI: usize = 25;
}

use layout::*;

/// Gains of one axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisGains {
    /// λ_i > 0 of the input filter (5.3), rad/s.
    pub lambda_rps: f64,
    /// K_i = [k_i1, k_i2] of the reference model (5.6).
    pub k: [f64; 2],
    /// L_i = [l_i1, l_i2] of the observer (5.10).
    pub l: [f64; 2],
}

impl AxisGains {
    /// B̄_i = [1, λ_i]ᵀ (5.4).
    pub fn b_bar(&self) -> Vector2<f64> {
        Vector2::new(1.0, self.lambda_rps)
    }

    /// A_m,i = A - B̄_i K_i (5.6).
    pub fn a_m(&self) -> Matrix2<f64> {
        let [k1, k2] = self.k;
        let l = self.lambda_rps;
        Matrix2::new(-k1, 1.0 - k2, -l * k1, -l * k2)
    }

    /// B_m,i = B̄_i K_i Cᵀ = k_i1 B̄_i (5.6).
    pub fn b_m(&self) -> Vector2<f64> {
        self.b_bar() * self.k[0]
    }

    /// K_i z.
    fn k_dot(&self, z: &Vector2<f64>) -> f64 {
        self.k[0] * z[0] + self.k[1] * z[1]
    }
}

/// Where the observer gain in use came from.
#[derive(Debug, Clone, PartialEq)]
pub enum ObserverGainSource {
    /// The fixed gain of the scenario (Chapter 5).
    Fixed,
    /// The Riccati design (6.62), which met l_i1 ≥ λ_i and l_i2 > 0 on every axis.
    Riccati,
    /// The Riccati design was asked for but failed or broke the conditions; the fixed gain is
    /// used. The reason says which axis and why.
    FallbackToFixed {
        /// What went wrong, for the log.
        reason: String,
    },
}

/// The observer gain per axis and where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct ObserverGainDesign {
    /// L_i = [l_i1, l_i2] for x, y, z.
    pub gains: [[f64; 2]; 3],
    /// Fixed, Riccati, or Riccati that fell back to fixed.
    pub source: ObserverGainSource,
}

impl ObserverGainDesign {
    /// The design a section asks for: fixed, or (6.62) per axis with the fixed gain as fallback.
    pub fn from_section(section: &AccelerationSection) -> Self {
        let fixed = Self {
            gains: [section.observer_gain; 3],
            source: ObserverGainSource::Fixed,
        };
        if section.observer_gain_mode == ObserverGainMode::Fixed {
            return fixed;
        }
        let axis = AxisGains {
            lambda_rps: section.lambda_rps,
            k: section.reference_gain,
            l: section.observer_gain,
        };
        match riccati_observer_gain(
            &axis,
            section.riccati_process_psd,
            section.riccati_noise_psd,
        ) {
            Ok(l) => Self {
                gains: [l; 3],
                source: ObserverGainSource::Riccati,
            },
            Err(reason) => Self {
                source: ObserverGainSource::FallbackToFixed { reason },
                ..fixed
            },
        }
    }

    /// A line for the run's log when the design fell back to the fixed gain.
    pub fn fallback_message(&self) -> Option<String> {
        match &self.source {
            ObserverGainSource::FallbackToFixed { reason } => Some(format!(
                "acceleration observer: Riccati gain rejected ({reason}); using the fixed \
                 gain {:?}",
                self.gains[0]
            )),
            _ => None,
        }
    }
}

/// The steady-state Kalman gain of one axis from (6.62) with a process-noise term:
/// 0 = A_m X + X A_mᵀ - X Cᵀ r⁻¹ C X + q B̄ B̄ᵀ, L = X Cᵀ / r. Without the q term (as the
/// seed prints (6.62)) the stabilising solution for a Hurwitz A_m is X = 0, L = 0, which
/// breaks l_1 ≥ λ: the unknown input (1/b) B̄ (w + d - …) is what the observer must reject, so
/// it is the process noise. Returns [l_1, l_2] or why it is unusable (l_1 ≥ λ, l_2 > 0).
pub fn riccati_observer_gain(
    axis: &AxisGains,
    process_psd: f64,
    noise_psd: f64,
) -> Result<[f64; 2], String> {
    let a_m = axis.a_m();
    let a = DMatrix::from_fn(2, 2, |i, j| a_m[(i, j)]);
    let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
    let b_bar = axis.b_bar();
    let q = DMatrix::from_fn(2, 2, |i, j| process_psd * b_bar[i] * b_bar[j]);
    let r = DMatrix::from_element(1, 1, noise_psd);
    let solution = solve_continuous_are(&a, &c, &q, &r).map_err(|e| e.to_string())?;
    let l = [solution.gain[(0, 0)], solution.gain[(1, 0)]];
    if l[0] >= axis.lambda_rps && l[1] > 0.0 {
        Ok(l)
    } else {
        Err(format!(
            "L = [{:.4}, {:.4}] breaks l1 >= lambda = {}, l2 > 0",
            l[0], l[1], axis.lambda_rps
        ))
    }
}

/// The law's output at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AccelerationGuidanceOutput {
    /// Commanded follower acceleration a_F (5.38), NED, ft/s².
    pub accel_cmd_ned_fps2: Vec3,
    /// The scaled command y_c the law tracks (shaped, excitation included).
    pub y_command: Vec3,
    /// ẏ_c, including -b̂' y_c,ft / b̂², 1/s.
    pub y_command_rate: Vec3,
    /// Reference-model output y_m = C z_m.
    pub y_model: Vec3,
    /// Observer output C ẑ.
    pub y_observer: Vec3,
    /// Combined measurable output y_a = 2y - y_m - C ẑ (SPEC §5).
    pub y_combined: Vec3,
    /// Virtual control w_f = b̂ h - S_f d̂ (5.36), ft/s.
    pub virtual_control_fps: Vec3,
    /// Its exact derivative ẇ_f, ft/s².
    pub virtual_control_rate_fps2: Vec3,
    /// Tracking error of the measurement y - y_c (what the excitation amplitude integrates).
    pub error: Vec3,
    /// b̂', ft/s.
    pub b_hat_rate_fps: f64,
}

/// The scaled command y_c = base + extra / b̂ and its parts' rates.
struct Command {
    y_c: Vec3,
    base_rate: Vec3,
    extra: Vec3,
    extra_rate: Vec3,
    filter_rate: Vec3,
}

/// Acceleration guidance (5.2)-(5.41), Remark 6, noisy form (6.39)-(6.42).
#[derive(Debug, Clone, PartialEq)]
pub struct AccelerationGuidance {
    axes: [AxisGains; 3],
    chi: f64,
    rho: f64,
    gamma_d: f64,
    sign_filter_pole_rps: f64,
    b_bound: IntervalBound,
    d_bound: BallBound,
    shaping_pole_rps: f64,
    b0_ft: f64,
    observer: ObserverGainDesign,
    /// τ of the shortfall's leaky integral, when the law compensates (module docs).
    compensation_time_constant_s: Option<f64>,
}

impl AccelerationGuidance {
    /// The law an `[acceleration]` section describes, with b̂(0), the projection bounds and the
    /// shaping filter's pole from `[guidance]` (d̂(0) = 0 as (5.41), not `guidance.d0_per_s`;
    /// `guidance.d_max_per_s` bounds ‖d̂‖ in ft/s here). The observer gain is designed here;
    /// see [`Self::observer_design`] for where it came from. `compensated`: for a follower
    /// that does not realise a_F (module docs).
    pub fn new(
        section: &AccelerationSection,
        guidance: &GuidanceSection,
        compensated: bool,
    ) -> Self {
        let observer = ObserverGainDesign::from_section(section);
        let axes = observer.gains.map(|l| AxisGains {
            lambda_rps: section.lambda_rps,
            k: section.reference_gain,
            l,
        });
        Self {
            axes,
            chi: section.chi,
            rho: section.rho,
            gamma_d: section.gamma_d,
            sign_filter_pole_rps: section.sign_filter_pole_rps,
            b_bound: IntervalBound {
                min: guidance.b_min_ft,
                max: guidance.b_max_ft,
                epsilon: guidance.b_epsilon_ft2,
            },
            d_bound: BallBound {
                max_norm: guidance.d_max_per_s,
                epsilon: guidance.d_epsilon,
            },
            shaping_pole_rps: guidance.shaping_pole_rps,
            b0_ft: guidance.b0_ft,
            observer,
            compensation_time_constant_s: compensated.then_some(section.shortfall_time_constant_s),
        }
    }

    /// The observer gain in use and its source (log [`ObserverGainDesign::fallback_message`]).
    pub fn observer_design(&self) -> &ObserverGainDesign {
        &self.observer
    }

    /// The gains of axis `i` (0 = x, 1 = y, 2 = z).
    pub fn axis(&self, i: usize) -> &AxisGains {
        &self.axes[i.min(2)]
    }

    /// Length of this law's state slice.
    pub fn state_len(&self) -> usize {
        LEN + if self.compensation_time_constant_s.is_some() {
            3
        } else {
            0
        }
    }

    /// The measurement the law runs on: y - χ/b̂ with compensation (module docs), y without.
    pub fn compensated_measurement(&self, x: &[f64], y: &Vec3) -> Vec3 {
        match self.compensation_time_constant_s {
            Some(_) => y - vec3_at(x, CHI) / x[B_HAT],
            None => *y,
        }
    }

    /// Initial state: w = 0, S_f = 0, d̂ = 0 ((5.3), (5.34), (5.41)), b̂ = b0, and z_m, ẑ and the
    /// shaping filter at the first measurement: z(0) = [r(0), ṙ(0)] and ṙ(0) is unknown
    /// (it needs b), so z_i2 starts at 0 (exact when the follower starts at the target's
    /// velocity, as in the seed).
    pub fn initial_state(&self, r0: &Vec3) -> Vec<f64> {
        let mut x = vec![0.0; self.state_len()];
        for i in 0..3 {
            x[Z_M + 2 * i] = r0[i];
            x[Z_HAT + 2 * i] = r0[i];
        }
        x[B_HAT] = self.b0_ft;
        x[R_CF..R_CF + 3].copy_from_slice(r0.as_slice());
        x
    }

    /// Restarts the reference model, the observer and the shaping filter at the first
    /// measurement r(0), keeping b̂, d̂, w and S_f (a camera's first frame arrives after the run
    /// starts).
    pub fn start_at(&self, x: &mut [f64], r0: &Vec3) {
        for i in 0..3 {
            x[Z_M + 2 * i] = r0[i];
            x[Z_M + 2 * i + 1] = 0.0;
            x[Z_HAT + 2 * i] = r0[i];
            x[Z_HAT + 2 * i + 1] = 0.0;
        }
        x[R_CF..R_CF + 3].copy_from_slice(r0.as_slice());
    }

    /// Before the first measurement: no state moves and a_F = 0 (the follower keeps V_F(0)).
    pub fn idle(&self, x: &[f64], dx: &mut [f64]) -> AccelerationGuidanceOutput {
        dx.fill(0.0);
        let zero = Vec3::zeros();
        AccelerationGuidanceOutput {
            accel_cmd_ned_fps2: zero,
            y_command: vec3_at(x, R_CF),
            y_command_rate: zero,
            y_model: Vec3::new(x[Z_M], x[Z_M + 2], x[Z_M + 4]),
            y_observer: Self::predicted_measurement(x),
            y_combined: zero,
            virtual_control_fps: zero,
            virtual_control_rate_fps2: zero,
            error: zero,
            b_hat_rate_fps: 0.0,
        }
    }

    /// The observer's output C ẑ: the law's own prediction of y, which it coasts on while the
    /// target is not measured.
    pub fn predicted_measurement(x: &[f64]) -> Vec3 {
        Vec3::new(x[Z_HAT], x[Z_HAT + 2], x[Z_HAT + 4])
    }

    /// b̂ of a state slice, ft.
    pub fn b_hat_ft(x: &[f64]) -> f64 {
        x[B_HAT]
    }

    /// d̂ of a state slice, ft/s.
    pub fn d_hat(x: &[f64]) -> Vec3 {
        vec3_at(x, D_HAT)
    }

    /// w of a state slice, ft/s.
    pub fn filtered_accel_fps(x: &[f64]) -> Vec3 {
        vec3_at(x, W)
    }

    /// Axis i's two-state block at `at` (Z_M or Z_HAT).
    pub fn axis_state(x: &[f64], at: usize, i: usize) -> Vector2<f64> {
        Vector2::new(x[at + 2 * i], x[at + 2 * i + 1])
    }

    /// The scaled command and the rates of its parts (everything but b̂').
    fn command(&self, x: &[f64], input: &GuidanceInput) -> Command {
        let b_hat = x[B_HAT];
        let r_cf = vec3_at(x, R_CF);
        if self.shaping_pole_rps > 0.0 {
            let filter_rate = (input.command_ned_ft / b_hat - r_cf) * self.shaping_pole_rps;
            let extra = input.excitation_ned_ft;
            Command {
                y_c: r_cf + input.excitation_scaled + extra / b_hat,
                base_rate: filter_rate + input.excitation_scaled_rate,
                extra,
                extra_rate: input.excitation_rate_ned_fps,
                filter_rate,
            }
        } else {
            let extra = input.command_ned_ft + input.excitation_ned_ft;
            Command {
                y_c: input.excitation_scaled + extra / b_hat,
                base_rate: input.excitation_scaled_rate,
                extra,
                extra_rate: input.command_rate_ned_fps + input.excitation_rate_ned_fps,
                filter_rate: Vec3::zeros(),
            }
        }
    }

    /// Writes ẋ into `dx` and returns the command.
    ///
    /// Order of evaluation (there is no algebraic loop): y_c depends on the state only, so
    /// h = -K ẑ + K Cᵀ y_c (5.9) and b̂' = ρ Proj(b̂, -y_aᵀ h) (5.20) come first; then
    /// ẏ_c = base' + extra'/b̂ - b̂' extra/b̂² uses that b̂'; then ż̂ (5.10), ḣ = -K ż̂ + K Cᵀ ẏ_c,
    /// Ṡ_f (5.34), d̂' (5.41), ẇ_f = b̂' h + b̂ ḣ - S_f d̂' - Ṡ_f d̂ and a_F (5.38).
    pub fn derivative(
        &self,
        x: &[f64],
        input: &GuidanceInput,
        dx: &mut [f64],
    ) -> AccelerationGuidanceOutput {
        let b_hat = x[B_HAT];
        let d_hat = vec3_at(x, D_HAT);
        let s_f = vec3_at(x, S_F);
        let w = vec3_at(x, W);
        // y (or y* with noise), in the law's compensated coordinates; coasting on the
        // observer's prediction while the target is lost.
        let y = input
            .r_measured
            .unwrap_or_else(|| Self::predicted_measurement(x));
        let cmd = self.command(x, input);

        let mut y_model = Vec3::zeros();
        let mut y_observer = Vec3::zeros();
        let mut h = Vec3::zeros();
        for (i, axis) in self.axes.iter().enumerate() {
            let z_hat = Self::axis_state(x, Z_HAT, i);
            y_model[i] = x[Z_M + 2 * i];
            y_observer[i] = z_hat[0];
            h[i] = -axis.k_dot(&z_hat) + axis.k[0] * cmd.y_c[i];
        }
        let y_a = y * 2.0 - y_model - y_observer;
        let b_hat_rate = self.rho * self.b_bound.project(b_hat, -y_a.dot(&h));
        let y_c_rate =
            cmd.base_rate + cmd.extra_rate / b_hat - cmd.extra * (b_hat_rate / (b_hat * b_hat));

        let mut h_rate = Vec3::zeros();
        for (i, axis) in self.axes.iter().enumerate() {
            let (a_m, b_m) = (axis.a_m(), axis.b_m());
            let z_m = Self::axis_state(x, Z_M, i);
            let z_hat = Self::axis_state(x, Z_HAT, i);
            let z_m_rate = a_m * z_m + b_m * cmd.y_c[i];
            let innovation = y[i] - z_hat[0];
            let z_hat_rate = a_m * z_hat + b_m * cmd.y_c[i] + Vector2::from(axis.l) * innovation;
            h_rate[i] = -axis.k_dot(&z_hat_rate) + axis.k[0] * y_c_rate[i];
            dx[Z_M + 2 * i..Z_M + 2 * i + 2].copy_from_slice(z_m_rate.as_slice());
            dx[Z_HAT + 2 * i..Z_HAT + 2 * i + 2].copy_from_slice(z_hat_rate.as_slice());
        }

        let s_chi = y_a.map(|v| smooth_sign(v, self.chi));
        let s_f_rate = (s_f - s_chi) * self.sign_filter_pole_rps;
        // S(y_a) y_a = |y_a| componentwise (5.41).
        let d_rate = self.d_bound.project(&d_hat, &y_a.abs()) * self.gamma_d;
        let w_f = h * b_hat - s_f.component_mul(&d_hat);
        let w_f_rate = h * b_hat_rate + h_rate * b_hat
            - s_f.component_mul(&d_rate)
            - s_f_rate.component_mul(&d_hat);
        let lambda = Vec3::from(self.axes.map(|a| a.lambda_rps));
        let a_f = -lambda.component_mul(&w_f) - w_f_rate + y_a;
        let w_rate = -lambda.component_mul(&w) - a_f;

        dx[W..W + 3].copy_from_slice(w_rate.as_slice());
        dx[S_F..S_F + 3].copy_from_slice(s_f_rate.as_slice());
        dx[B_HAT] = b_hat_rate;
        dx[D_HAT..D_HAT + 3].copy_from_slice(d_rate.as_slice());
        dx[R_CF..R_CF + 3].copy_from_slice(cmd.filter_rate.as_slice());
        if let Some(tau) = self.compensation_time_constant_s {
            let shortfall = input
                .follower_velocity_shortfall_ned_fps
                .unwrap_or_else(Vec3::zeros);
            let chi_rate = shortfall - vec3_at(x, CHI) / tau;
            dx[CHI..CHI + 3].copy_from_slice(chi_rate.as_slice());
        }

        AccelerationGuidanceOutput {
            accel_cmd_ned_fps2: a_f,
            y_command: cmd.y_c,
            y_command_rate: y_c_rate,
            y_model,
            y_observer,
            y_combined: y_a,
            virtual_control_fps: w_f,
            virtual_control_rate_fps2: w_f_rate,
            error: y - cmd.y_c,
            b_hat_rate_fps: b_hat_rate,
        }
    }

    /// Clamps b̂ and d̂ back into Ω_1 after an integration step (see [`super::projection`]).
    pub fn enforce_bounds(&self, x: &mut [f64]) {
        x[B_HAT] = self.b_bound.clamp(x[B_HAT]);
        let d = self.d_bound.clamp(&vec3_at(x, D_HAT));
        x[D_HAT..D_HAT + 3].copy_from_slice(d.as_slice());
    }
}

/// The smooth sign s_χ (5.31): sgn(v) for |v| > χ, (3/(2χ)) v - v³/(2χ³) inside; C¹ at ±χ.
pub fn smooth_sign(v: f64, chi: f64) -> f64 {
    if v.abs() > chi {
        v.signum()
    } else {
        (1.5 / chi) * v - v.powi(3) / (2.0 * chi.powi(3))
    }
}

/// The 3-vector stored at `x[at..at + 3]`.
fn vec3_at(x: &[f64], at: usize) -> Vec3 {
    Vec3::new(x[at], x[at + 1], x[at + 2])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(section: &AccelerationSection) -> AccelerationGuidance {
        let guidance = GuidanceSection {
            shaping_pole_rps: 0.0,
            b0_ft: 8.0,
            ..GuidanceSection::default()
        };
        AccelerationGuidance::new(section, &guidance, false)
    }

    fn input(y: Vec3) -> GuidanceInput {
        GuidanceInput::steady(y, Vec3::new(32.0, 8.0, 0.0))
    }

    /// s_χ is odd, within [-1, 1], and C¹ at ±χ (5.32): value 1 and slope 0 from inside.
    #[test]
    fn smooth_sign_is_c1_at_chi() {
        let chi = 1.5;
        assert_eq!(smooth_sign(0.0, chi), 0.0);
        assert!((smooth_sign(chi, chi) - 1.0).abs() < 1e-15);
        let h = 1e-6;
        let slope = (smooth_sign(chi, chi) - smooth_sign(chi - h, chi)) / h;
        assert!(slope.abs() < 1e-5, "slope {slope}");
        for i in -40..=40 {
            let v = i as f64 * 0.1;
            let s = smooth_sign(v, chi);
            assert!(s.abs() <= 1.0 && (s + smooth_sign(-v, chi)).abs() < 1e-15);
        }
    }

    /// At the equilibrium z = z_m = ẑ = [y_c, 0], y = y_c, S_f = 0, d̂ = 0 the command is zero
    /// and no state moves (the reference model has unit DC gain, (5.7)).
    #[test]
    fn at_equilibrium_nothing_moves() {
        let law = law(&AccelerationSection::default());
        let y_c = Vec3::new(4.0, 1.0, 0.0);
        let x = law.initial_state(&y_c);
        let mut dx = vec![0.0; law.state_len()];
        let out = law.derivative(&x, &input(y_c), &mut dx);
        assert!(out.accel_cmd_ned_fps2.norm() < 1e-12);
        assert!(dx.iter().all(|v| v.abs() < 1e-12), "{dx:?}");
    }

    /// Sign check of (5.38) as SPEC fixes it: a target further ahead than commanded
    /// (y = y_c + δ, δ > 0 on x) makes the follower accelerate towards it: at the equilibrium
    /// a_F,x = (b̂ K L + 2) δ > 0, and only the x axis reacts.
    #[test]
    fn error_ahead_accelerates_forward() {
        let law = law(&AccelerationSection::default());
        let y_c = Vec3::new(4.0, 1.0, 0.0);
        let x = law.initial_state(&y_c);
        let mut dx = vec![0.0; law.state_len()];
        let delta = 0.01;
        let out = law.derivative(&x, &input(y_c + Vec3::new(delta, 0.0, 0.0)), &mut dx);
        let expected = (8.0 * (1.75 * 2.0 + 0.5 * 1.6) + 2.0) * delta;
        assert!(
            (out.accel_cmd_ned_fps2.x - expected).abs() < 1e-12,
            "{out:?}"
        );
        assert!(out.accel_cmd_ned_fps2.yz().norm() < 1e-12);
    }

    /// The default Riccati weights give a gain that meets l1 ≥ λ, l2 > 0, and A - L C with it
    /// has the SPR observer transfer (s + λ)/(s² + l1 s + l2) of (5.13).
    #[test]
    fn riccati_design_meets_conditions() {
        let section = AccelerationSection {
            observer_gain_mode: ObserverGainMode::Riccati,
            ..AccelerationSection::default()
        };
        let design = ObserverGainDesign::from_section(&section);
        assert_eq!(design.source, ObserverGainSource::Riccati);
        let [l1, l2] = design.gains[0];
        assert!(l1 >= 2.0 && l2 > 0.0, "{:?}", design.gains);
        assert!(design.fallback_message().is_none());
        assert_eq!(law(&section).axis(1).l, design.gains[1]);
    }

    /// (e) With measurement noise much stronger than the process noise the Kalman gain is
    /// small (l1 < λ): the design falls back to the fixed gain and says so.
    #[test]
    fn riccati_fallback_when_conditions_fail() {
        let section = AccelerationSection {
            observer_gain_mode: ObserverGainMode::Riccati,
            riccati_process_psd: 1e-4,
            riccati_noise_psd: 1.0,
            ..AccelerationSection::default()
        };
        let design = ObserverGainDesign::from_section(&section);
        assert!(matches!(
            design.source,
            ObserverGainSource::FallbackToFixed { .. }
        ));
        assert_eq!(design.gains, [[2.0, 1.6]; 3]);
        let message = design.fallback_message().expect("a message for the log");
        assert!(message.contains("l1 >= lambda"), "{message}");
        let law = law(&section);
        assert_eq!(law.axis(0).l, [2.0, 1.6]);
    }

    /// The Riccati gain is the steady-state Kalman gain: X with
    /// A_m X + X A_mᵀ - X Cᵀ C X / r + q B̄ B̄ᵀ = 0 (relative residual below 1e-9) gives
    /// L = X Cᵀ / r.
    #[test]
    fn riccati_gain_solves_6_62() {
        let axis = AxisGains {
            lambda_rps: 2.0,
            k: [1.75, 0.5],
            l: [2.0, 1.6],
        };
        let (q, r) = (0.04, 1.8e-5);
        let l = riccati_observer_gain(&axis, q, r).expect("conditions hold");
        let a_m = axis.a_m();
        let a = DMatrix::from_fn(2, 2, |i, j| a_m[(i, j)]);
        let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
        let b = axis.b_bar();
        let qm = DMatrix::from_fn(2, 2, |i, j| q * b[i] * b[j]);
        let rm = DMatrix::from_element(1, 1, r);
        let sol = solve_continuous_are(&a, &c, &qm, &rm).expect("solvable");
        assert!(crate::linalg::riccati_residual(&a, &c, &qm, &rm, &sol.x) < 1e-9);
        assert!((sol.x[(0, 0)] / r - l[0]).abs() < 1e-9 * l[0]);
        assert!((sol.x[(1, 0)] / r - l[1]).abs() < 1e-9 * l[1]);
    }
}
