//! Acceleration guidance (Chapter 5; docs/equations.md, Acceleration guidance (Chapter 5)) and
//! its noisy-measurement form (6.39)-(6.42).
//!
//! Per axis i the plant is x_i = [r_i, ṙ_i], ẋ = A x + (1/b) B (a_T - a_F), y = C x = r. The
//! input-filtered coordinates z = x - (1/b) B (w + d) (5.2)-(5.5) have relative degree one;
//! the law tracks a reference model z_m (5.6) with an observer ẑ (5.10), the virtual control
//! w_f = b̂ h - S_f d̂ (5.33)-(5.36) and the backstepping command
//! a_F = -Λ w_f - ẇ_f + y_a (5.38, its sign fixed so that the Lyapunov argument
//! (5.12)-(5.15), (5.43) holds), with ẇ_f computed exactly from
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
//! State: [`AccelerationState`], `[w (3), z_m (6), ẑ (6), S_f (3), b̂, d̂ (3), r_cf (3)]`, 25
//! values, and the lead ℓ (3) of [`super::compensation`] for a follower that does not realise
//! a_F (the 6-DOF aircraft): the law then runs on y - ℓ/b̂.

use super::compensation::ShortfallCompensation;
use super::shaping::{CommandShaping, ShapedCommand};
use super::signals::{AccelerationGuidanceOutput, GuidanceInput};
use crate::frames::Vec3;
use crate::linalg::solve_continuous_are;
use crate::projection::{BallBound, EstimateBounds, IntervalBound};
use crate::scenario::{AccelerationSection, GuidanceSection, ObserverGainMode};
use crate::state_block::{StateReader, StateWriter};
use nalgebra::{DMatrix, Matrix2, Vector2};

/// The law's continuous state; holding rates, its derivative. z_m and ẑ are per axis
/// `[z_i1, z_i2]` (z_i1 ~ r_i, z_i2 ~ ṙ_i).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AccelerationState {
    /// w: the filtered follower acceleration, ẇ = -Λ w - a_F (5.3), ft/s.
    pub w_fps: Vec3,
    /// z_m: the reference model's state (5.6), per axis.
    pub z_model: [Vector2<f64>; 3],
    /// ẑ: the observer's state (5.10), per axis.
    pub z_hat: [Vector2<f64>; 3],
    /// S_f: the diagonal of the filtered smooth sign (5.34).
    pub sign_filter: Vec3,
    /// b̂: estimate of the target's size b, ft (5.20).
    pub b_hat_ft: f64,
    /// d̂: adaptive bound of the filtered target acceleration d, ft/s (5.41).
    pub d_hat_fps: Vec3,
    /// r_cf: the shaping filter's state ([`super::shaping`]).
    pub shaping_filter: Vec3,
    /// ℓ: the lead of [`super::compensation`], ft, with compensation.
    pub lead_ft: Option<Vec3>,
}

impl AccelerationState {
    /// Writes the block into its state slice.
    pub fn pack(&self, x: &mut [f64]) {
        let mut w = StateWriter::new(x);
        w.vec3(&self.w_fps);
        for z in self.z_model.iter().chain(&self.z_hat) {
            w.values(z.as_slice());
        }
        w.vec3(&self.sign_filter)
            .scalar(self.b_hat_ft)
            .vec3(&self.d_hat_fps)
            .vec3(&self.shaping_filter)
            .optional_vec3(&self.lead_ft);
    }

    /// C z_m: the reference model's output y_m.
    pub fn y_model(&self) -> Vec3 {
        Vec3::from(self.z_model.map(|z| z[0]))
    }

    /// C ẑ: the observer's output, the law's own prediction of y, which it coasts on while
    /// the target is not measured.
    pub fn y_observer(&self) -> Vec3 {
        Vec3::from(self.z_hat.map(|z| z[0]))
    }
}

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
    /// used.
    FallbackToFixed {
        /// What went wrong, for the log.
        reason: ObserverGainRejected,
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

/// Why the Riccati observer gain (6.62) cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ObserverGainRejected {
    /// The Riccati equation has no stabilising solution.
    #[error("{0}")]
    NoSolution(#[from] crate::linalg::LinalgError),
    /// The gain breaks the conditions of (5.13).
    #[error("L = [{:.4}, {:.4}] breaks l1 >= lambda = {lambda_rps}, l2 > 0", gain[0], gain[1])]
    Conditions {
        /// The gain L = [l_1, l_2].
        gain: [f64; 2],
        /// λ of the axis, rad/s.
        lambda_rps: f64,
    },
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
) -> Result<[f64; 2], ObserverGainRejected> {
    let a_m = axis.a_m();
    let a = DMatrix::from_fn(2, 2, |i, j| a_m[(i, j)]);
    let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
    let b_bar = axis.b_bar();
    let q = DMatrix::from_fn(2, 2, |i, j| process_psd * b_bar[i] * b_bar[j]);
    let r = DMatrix::from_element(1, 1, noise_psd);
    let solution = solve_continuous_are(&a, &c, &q, &r)?;
    let l = [solution.gain[(0, 0)], solution.gain[(1, 0)]];
    if l[0] >= axis.lambda_rps && l[1] > 0.0 {
        Ok(l)
    } else {
        Err(ObserverGainRejected::Conditions {
            gain: l,
            lambda_rps: axis.lambda_rps,
        })
    }
}

/// Acceleration guidance (5.2)-(5.41), Remark 6, noisy form (6.39)-(6.42), with compensation
/// for a follower that does not realise a_F.
#[derive(Debug, Clone, PartialEq)]
pub struct AccelerationGuidance {
    axes: [AxisGains; 3],
    chi: f64,
    rho: f64,
    gamma_d: f64,
    sign_filter_pole_rps: f64,
    bounds: EstimateBounds,
    shaping: CommandShaping,
    b0_ft: f64,
    observer: ObserverGainDesign,
    compensation: Option<ShortfallCompensation>,
}

/// The per-axis parts of one evaluation: outputs of the reference model and the observer and
/// the virtual control's h = -K ẑ + K Cᵀ y_c (5.9).
struct AxisOutputs {
    y_model: Vec3,
    y_observer: Vec3,
    h: Vec3,
}

impl AccelerationGuidance {
    /// The law an `[acceleration]` section describes, with b̂(0), its projection bound and the
    /// shaping filter's pole from `[guidance]` (d̂(0) = 0 as (5.41), not `guidance.d0_per_s`).
    /// The observer gain is designed here; see [`Self::observer_design`] for where it came
    /// from.
    pub fn new(
        section: &AccelerationSection,
        guidance: &GuidanceSection,
        compensation: Option<ShortfallCompensation>,
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
            bounds: EstimateBounds {
                b: IntervalBound {
                    min: guidance.b_min_ft,
                    max: guidance.b_max_ft,
                    epsilon: guidance.b_epsilon_ft2,
                },
                d: BallBound {
                    max_norm: section.d_hat_max_fps,
                    epsilon: section.d_hat_epsilon_fps2,
                },
            },
            shaping: CommandShaping::of(guidance),
            b0_ft: guidance.b0_ft,
            observer,
            compensation,
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
        25 + 3 * usize::from(self.compensation.is_some())
    }

    /// The typed state of a state slice.
    pub fn unpack(&self, x: &[f64]) -> AccelerationState {
        let mut r = StateReader::new(x);
        let w_fps = r.vec3();
        let z_model = [(); 3].map(|_| Vector2::from(r.array::<2>()));
        let z_hat = [(); 3].map(|_| Vector2::from(r.array::<2>()));
        AccelerationState {
            w_fps,
            z_model,
            z_hat,
            sign_filter: r.vec3(),
            b_hat_ft: r.scalar(),
            d_hat_fps: r.vec3(),
            shaping_filter: r.vec3(),
            lead_ft: r.optional_vec3(self.compensation.is_some()),
        }
    }

    /// Initial state: w = 0, S_f = 0, d̂ = 0 ((5.3), (5.34), (5.41)), b̂ = b0, and z_m, ẑ and the
    /// shaping filter at the first measurement: z(0) = [r(0), ṙ(0)] and ṙ(0) is unknown
    /// (it needs b), so z_i2 starts at 0 (exact when the follower starts at the target's
    /// velocity, as in the seed).
    pub fn initial_state(&self, r0: &Vec3) -> Vec<f64> {
        let at_rest = [0, 1, 2].map(|i| Vector2::new(r0[i], 0.0));
        let mut x = vec![0.0; self.state_len()];
        AccelerationState {
            w_fps: Vec3::zeros(),
            z_model: at_rest,
            z_hat: at_rest,
            sign_filter: Vec3::zeros(),
            b_hat_ft: self.b0_ft,
            d_hat_fps: Vec3::zeros(),
            shaping_filter: *r0,
            lead_ft: self.compensation.map(|_| Vec3::zeros()),
        }
        .pack(&mut x);
        x
    }

    /// Restarts the reference model, the observer and the shaping filter at the first
    /// measurement r(0), keeping b̂, d̂, w and S_f (a camera's first frame arrives after the run
    /// starts).
    pub fn start_at(&self, x: &mut [f64], r0: &Vec3) {
        let at_rest = [0, 1, 2].map(|i| Vector2::new(r0[i], 0.0));
        AccelerationState {
            z_model: at_rest,
            z_hat: at_rest,
            shaping_filter: *r0,
            ..self.unpack(x)
        }
        .pack(x);
    }

    /// Before the first measurement: no state moves and a_F = 0 (the follower keeps V_F(0)).
    pub fn idle(&self, x: &[f64], dx: &mut [f64]) -> AccelerationGuidanceOutput {
        dx.fill(0.0);
        let state = self.unpack(x);
        let zero = Vec3::zeros();
        AccelerationGuidanceOutput {
            accel_cmd_ned_fps2: zero,
            y_command: state.shaping_filter,
            y_command_rate: zero,
            y_model: state.y_model(),
            y_observer: state.y_observer(),
            y_combined: zero,
            virtual_control_fps: zero,
            virtual_control_rate_fps2: zero,
            error: zero,
            b_hat_rate_fps: 0.0,
        }
    }

    /// The y the law runs on: the measurement (y - ℓ/b̂ with compensation), or the observer's
    /// prediction C ẑ while the target is not measured.
    fn measurement(&self, state: &AccelerationState, input: &GuidanceInput) -> Vec3 {
        match (input.r_measured, self.compensation.zip(state.lead_ft)) {
            (None, _) => state.y_observer(),
            (Some(y), None) => y,
            (Some(y), Some((c, lead))) => c.measurement(&y, &lead, state.b_hat_ft),
        }
    }

    /// y_m, C ẑ and h = -K ẑ + K Cᵀ y_c (5.9).
    fn axis_outputs(&self, state: &AccelerationState, y_c: &Vec3) -> AxisOutputs {
        let mut out = AxisOutputs {
            y_model: state.y_model(),
            y_observer: state.y_observer(),
            h: Vec3::zeros(),
        };
        for (i, axis) in self.axes.iter().enumerate() {
            out.h[i] = -axis.k_dot(&state.z_hat[i]) + axis.k[0] * y_c[i];
        }
        out
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
        let state = self.unpack(x);
        let b_hat = state.b_hat_ft;
        let y = self.measurement(&state, input);
        let cmd = self.shaping.command(&state.shaping_filter, b_hat, input);
        let axes = self.axis_outputs(&state, &cmd.value);
        let y_a = y * 2.0 - axes.y_model - axes.y_observer;
        let b_hat_rate = self.rho * self.bounds.b.project(b_hat, -y_a.dot(&axes.h));
        let y_c_rate = cmd.rate(b_hat_rate);
        let mut rates = self.model_and_observer_rates(&state, &y, &cmd);
        let h_rate = Vec3::from(
            [0, 1, 2]
                .map(|i| -self.axes[i].k_dot(&rates.z_hat[i]) + self.axes[i].k[0] * y_c_rate[i]),
        );
        let s_chi = y_a.map(|v| smooth_sign(v, self.chi));
        let s_f_rate = (state.sign_filter - s_chi) * self.sign_filter_pole_rps;
        // S(y_a) y_a = |y_a| componentwise (5.41).
        let d_rate = self.bounds.d.project(&state.d_hat_fps, &y_a.abs()) * self.gamma_d;
        let s_f = state.sign_filter;
        let w_f = axes.h * b_hat - s_f.component_mul(&state.d_hat_fps);
        let w_f_rate = axes.h * b_hat_rate + h_rate * b_hat
            - s_f.component_mul(&d_rate)
            - s_f_rate.component_mul(&state.d_hat_fps);
        let lambda = Vec3::from(self.axes.map(|a| a.lambda_rps));
        let a_f = -lambda.component_mul(&w_f) - w_f_rate + y_a;
        rates.w_fps = -lambda.component_mul(&state.w_fps) - a_f;
        rates.sign_filter = s_f_rate;
        rates.b_hat_ft = b_hat_rate;
        rates.d_hat_fps = d_rate;
        rates.lead_ft = self.lead_rate(&state, input);
        rates.pack(dx);
        AccelerationGuidanceOutput {
            accel_cmd_ned_fps2: a_f,
            y_command: cmd.value,
            y_command_rate: y_c_rate,
            y_model: axes.y_model,
            y_observer: axes.y_observer,
            y_combined: y_a,
            virtual_control_fps: w_f,
            virtual_control_rate_fps2: w_f_rate,
            error: y - cmd.value,
            b_hat_rate_fps: b_hat_rate,
        }
    }

    /// The rates of the reference model (5.6), the observer (5.10) and the shaping filter;
    /// the other fields are zero for [`Self::derivative`] to fill.
    fn model_and_observer_rates(
        &self,
        state: &AccelerationState,
        y: &Vec3,
        cmd: &ShapedCommand,
    ) -> AccelerationState {
        let zero = Vector2::zeros();
        let mut rates = AccelerationState {
            w_fps: Vec3::zeros(),
            z_model: [zero; 3],
            z_hat: [zero; 3],
            sign_filter: Vec3::zeros(),
            b_hat_ft: 0.0,
            d_hat_fps: Vec3::zeros(),
            shaping_filter: cmd.filter_rate,
            lead_ft: None,
        };
        for (i, axis) in self.axes.iter().enumerate() {
            let (a_m, b_m) = (axis.a_m(), axis.b_m());
            let z_hat = state.z_hat[i];
            rates.z_model[i] = a_m * state.z_model[i] + b_m * cmd.value[i];
            let innovation = y[i] - z_hat[0];
            rates.z_hat[i] = a_m * z_hat + b_m * cmd.value[i] + Vector2::from(axis.l) * innovation;
        }
        rates
    }

    /// ℓ' of the compensation (zero shortfall when the follower reports none).
    fn lead_rate(&self, state: &AccelerationState, input: &GuidanceInput) -> Option<Vec3> {
        let shortfall = input
            .follower
            .map_or(Vec3::zeros(), |f| f.velocity_shortfall_ned_fps);
        self.compensation
            .zip(state.lead_ft)
            .map(|(c, lead)| c.lead_rate(&lead, &shortfall))
    }

    /// Clamps b̂ and d̂ back into Ω_1 after an integration step (see [`crate::projection`]).
    pub fn enforce_bounds(&self, x: &mut [f64]) {
        let mut state = self.unpack(x);
        (state.b_hat_ft, state.d_hat_fps) = self.bounds.clamp(state.b_hat_ft, &state.d_hat_fps);
        state.pack(x);
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

impl AccelerationGuidance {
    /// The names of the state slice's elements, in [`AccelerationState`]'s order (for
    /// messages).
    pub fn state_names(&self) -> Vec<String> {
        use crate::state_block::{XYZ, element_names};
        let per_axis: &[&str] = &["x, r", "x, ṙ", "y, r", "y, ṙ", "z, r", "z, ṙ"];
        let mut groups = vec![
            ("w (filtered follower acceleration), ft/s", XYZ),
            ("reference model z_m", per_axis),
            ("observer ẑ", per_axis),
            ("filtered sign S_f", XYZ),
            ("b̂ (target size estimate), ft", &[]),
            ("d̂ (filtered acceleration bound), ft/s", XYZ),
            ("shaping filter r_cf", XYZ),
        ];
        if self.compensation.is_some() {
            groups.push(("lead, ft", XYZ));
        }
        element_names("guidance", &groups)
    }
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
        AccelerationGuidance::new(section, &guidance, None)
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

    /// Sign check of (5.38) as fixed here (module docs): a target further ahead than commanded
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
