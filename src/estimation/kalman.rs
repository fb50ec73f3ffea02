//! Range and size from the follower's own motion (docs/equations.md): a Kalman filter on
//! x = [r (3), d (3), a (3), β, g (3)], with r = R/b the scaled relative position, d = V_T/b the
//! scaled velocity of the target's path (1/s), a = a_T/b its acceleration (1/s²), β = 1/b (1/ft)
//! and g = u_T/b the target's gust velocity about its path (1/s):
//! ```text
//! ṙ = d + g - β V_F(t)    ḋ = a    ȧ = w_j    β̇ = w_β    ġ = -g/τ_g + w_g    r* = r + v
//! ```
//! V_F is the follower's own velocity, known to its navigation, so the model is linear in x and
//! the filter exact for it. Over an interval Δ in which the follower moved by ΔR_F = ∫ V_F dt
//! (its navigation's positions at both ends), the transition is exact too:
//! ```text
//! r⁺ = r + Δ d + Δ²/2 a - ΔR_F β      d⁺ = d + Δ a      a⁺ = a      β⁺ = β
//! ```
//! so the filter never integrates V_F itself: a frame is fused at its capture time from the
//! follower's position then, and the estimate for any later instant (latency, the instants
//! between frames) is the same prediction to the follower's position now
//! ([`TargetFilter::estimate_at`]). Process noise: white jerk w_j of intensity q_j on each axis
//! (the target's manoeuvres) and a random walk w_β of intensity q_β on β (the apparent size, which
//! the camera measures, wanders with the target's aspect, seed 8.2); the β noise enters r
//! through -∫ w_β V_F, taken with V_F constant over the interval. The gust velocity is a
//! first-order Gauss-Markov process (docs/equations.md, The target's gust velocity): an
//! aircraft in turbulence wanders about its path by a bounded velocity σ_g with a correlation
//! time τ_g, which a white jerk cannot express without letting the path's velocity wander
//! without bound (and β with it). Its intensity q_g = 2 σ_g² β̂² / τ_g keeps σ_g stationary in
//! feet per second whatever b is; σ_g = 0 (the default) leaves g at zero.
//!
//! A leader that swings across its track at a known period T_L (a teammate's own excitation)
//! may be given a swing (p, q) = (s, ṡ)/b per axis, a damped oscillator at ω_L = 2π/T_L whose
//! amplitude and phase wander over τ_s (docs/equations.md, The leader's swing in its model):
//! ```text
//! ṙ = d + g + q - β V_F    ṗ = q    q̇ = -ω_L² p - (2/τ_s) q + w_s
//! ```
//! so the relative motion at ω_L is explained as the leader's, whatever the follower's own
//! motion does there; its noise keeps the swing velocity's stationary σ at σ_s ft/s.
//!
//! Observability: with V_F constant, -β V_F t cannot be told from d t; β is learned only while
//! the follower's velocity changes differently from the target's (the excitation's job).

use crate::frames::{Mat3, Vec3};
use nalgebra::{Matrix2, SMatrix, SVector};

/// Length of the filter's state.
pub const FILTER_STATE_LEN: usize = 19;

type State = SVector<f64, FILTER_STATE_LEN>;
type Covariance = SMatrix<f64, FILTER_STATE_LEN, FILTER_STATE_LEN>;
type Gain = SMatrix<f64, FILTER_STATE_LEN, 3>;

/// Offsets of the blocks in the state.
const R: usize = 0;
const D: usize = 3;
const A: usize = 6;
const BETA: usize = 9;
const G: usize = 10;
const SWING: usize = 13;
const SWING_RATE: usize = 16;

/// Iterations of the lateral acceleration's iterated update.
const LATERAL_ITERATIONS: usize = 5;

/// The filter's noise model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilterNoise {
    /// q_j, the intensity of the white jerk of a = a_T/b, per axis, 1/s⁵.
    pub jerk_psd: f64,
    /// q_β, the intensity of the random walk of β = 1/b, 1/(ft² s).
    pub inverse_size_psd: f64,
    /// σ_g, the stationary σ of the target's gust velocity per axis, ft/s (0: no gust).
    pub gust_sigma_fps: f64,
    /// τ_g, its correlation time, s (> 0).
    pub gust_time_s: f64,
    /// The leader's swing at a known period, if it has one.
    pub swing: Option<SwingModel>,
}

/// The leader's swing across its track at a known period: a damped oscillator driven by white
/// noise (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwingModel {
    /// ω_L, rad/s.
    pub omega_rps: f64,
    /// σ_s, the stationary σ of the swing's velocity per axis, ft/s.
    pub sigma_fps: f64,
    /// τ_s, the time over which its amplitude and phase wander, s (> 1/ω_L).
    pub time_s: f64,
}

impl SwingModel {
    /// Φ over `dt` of one axis's (p, q): rows and columns in that order.
    fn transition(&self, dt: f64) -> Matrix2<f64> {
        let (omega, decay_rate) = (self.omega_rps, 1.0 / self.time_s);
        let damped = (omega * omega - decay_rate * decay_rate).sqrt();
        let (sin, cos) = (damped * dt).sin_cos();
        let envelope = (-decay_rate * dt).exp();
        Matrix2::new(
            cos + decay_rate / damped * sin,
            sin / damped,
            -omega * omega / damped * sin,
            cos - decay_rate / damped * sin,
        ) * envelope
    }

    /// The stationary covariance of one axis's (p, q) for a leader of inverse size
    /// `beta_per_ft`: diag(σ_q²/ω², σ_q²), σ_q = σ_s β.
    fn stationary(&self, beta_per_ft: f64) -> Matrix2<f64> {
        let rate = (self.sigma_fps * beta_per_ft).powi(2);
        Matrix2::new(rate / self.omega_rps.powi(2), 0.0, 0.0, rate)
    }
}

impl FilterNoise {
    /// The white-jerk model alone: no gust velocity.
    pub fn without_gust(jerk_psd: f64, inverse_size_psd: f64) -> Self {
        Self {
            jerk_psd,
            inverse_size_psd,
            gust_sigma_fps: 0.0,
            gust_time_s: 1.0,
            swing: None,
        }
    }

    /// The stationary variance of g for a target of inverse size `beta_per_ft`, 1/s².
    fn gust_variance(&self, beta_per_ft: f64) -> f64 {
        (self.gust_sigma_fps * beta_per_ft).powi(2)
    }
}

/// The filter's start: its belief about the target before the first measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilterPrior {
    /// b̂(0), ft.
    pub size_ft: f64,
    /// σ of β(0) = 1/b(0), 1/ft.
    pub inverse_size_sigma_per_ft: f64,
    /// σ of the target's velocity relative to the follower's at the start, per axis, ft/s
    /// (d(0) = β(0) V_F(0) ± this × β(0): the target is assumed to fly roughly like the
    /// follower).
    pub relative_velocity_sigma_fps: f64,
    /// σ of the target's acceleration at the start, per axis, ft/s².
    pub acceleration_sigma_fps2: f64,
    /// [b_min, b_max], ft, when the filter's estimate is kept within them: after every
    /// update x̂ is projected onto β ∈ [1/b_max, 1/b_min] (None: β is free, and only the
    /// law bounds b̂; docs/equations.md, The size's bounds in the filter).
    pub size_bounds_ft: Option<(f64, f64)>,
}

/// The filter's estimate at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilterEstimate {
    /// r̂.
    pub r: Vec3,
    /// d̂ = V̂_T/b, 1/s.
    pub d_per_s: Vec3,
    /// â = â_T/b, 1/s².
    pub a_per_s2: Vec3,
    /// β̂ = 1/b̂, 1/ft.
    pub beta_per_ft: f64,
    /// σ of β̂, 1/ft.
    pub beta_sigma_per_ft: f64,
    /// p̂, the leader's swing in r̂ (zero without the swing model): r̂ - p̂ is its path's.
    pub swing: Vec3,
}

impl FilterEstimate {
    /// b̂ = 1/β̂, ft (β̂ ≤ 0 gives infinity: the caller bounds it).
    pub fn size_ft(&self) -> f64 {
        1.0 / self.beta_per_ft
    }

    /// σ of b̂ to first order, σ_β / β̂², ft.
    pub fn size_sigma_ft(&self) -> f64 {
        self.beta_sigma_per_ft / (self.beta_per_ft * self.beta_per_ft)
    }
}

/// The outcome of fusing one measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Innovation {
    /// r* - r̂⁻.
    pub residual: Vec3,
    /// Its normalised square νᵀ S⁻¹ ν (χ² with 3 degrees of freedom when the model holds).
    pub normalised_sq: f64,
    /// The normalised square of its bearing alone, ν_⊥ᵀ S_⊥⁻¹ ν_⊥ (χ² with 2 degrees of
    /// freedom when the model holds; [`TargetFilter::bearing_normalised_sq`]).
    pub bearing_normalised_sq: f64,
    /// Whether the measurement was fused (false: outside the validation gate).
    pub fused: bool,
}

/// The validation gates a measurement must pass to be fused (docs/equations.md, The innovation
/// gate, and The bearing gate): on its whole innovation, and on its bearing alone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gates {
    /// The largest νᵀ S⁻¹ ν fused (∞: no gate).
    pub innovation: f64,
    /// The largest ν_⊥ᵀ S_⊥⁻¹ ν_⊥ fused (∞: no gate), of a measurement the bearing gate
    /// weighs ([`Self::weighs_bearing`]).
    pub bearing: f64,
    /// ρ_⊥ ≥ 1: the bearing gate weighs a measurement whose ‖r*‖ is off the prediction's
    /// ‖r̂⁻‖ by this factor or more, either way (1: every measurement).
    pub bearing_range_ratio: f64,
}

impl Gates {
    /// No gate: every finite measurement is fused.
    pub const OPEN: Self = Self {
        innovation: f64::INFINITY,
        bearing: f64::INFINITY,
        bearing_range_ratio: 1.0,
    };

    /// Whether the bearing gate weighs a measurement whose |ln(‖r*‖ / ‖r̂⁻‖)| is `range_off`
    /// ([`TargetFilter::range_off`]): ≥ ln ρ_⊥, a length off the predicted one by ρ_⊥ or more
    /// (not a number: yes).
    fn weighs_bearing(&self, range_off: f64) -> bool {
        self.bearing.is_finite()
            && (range_off.is_nan() || range_off >= self.bearing_range_ratio.ln())
    }
}

/// The Kalman filter of this module: posterior at the time of the last fused measurement.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetFilter {
    x: State,
    p: Covariance,
    noise: FilterNoise,
    /// Time of the posterior, s.
    t_s: f64,
    /// The follower's position then, NED, ft.
    follower_position_ned_ft: Vec3,
    /// [1/b_max, 1/b_min], 1/ft, when the estimate is kept within the size's bounds.
    beta_bounds_per_ft: Option<(f64, f64)>,
}

impl TargetFilter {
    /// A filter started on a first measurement r* (with covariance `r_covariance`) taken at
    /// `t_s` from `follower_position_ned_ft` while the follower flew at
    /// `follower_velocity_ned_fps`.
    pub fn new(
        noise: FilterNoise,
        prior: &FilterPrior,
        r_star: &Vec3,
        r_covariance: &Mat3,
        t_s: f64,
        follower_position_ned_ft: &Vec3,
        follower_velocity_ned_fps: &Vec3,
    ) -> Self {
        let beta = 1.0 / prior.size_ft;
        let sigma_beta = prior.inverse_size_sigma_per_ft;
        let v = follower_velocity_ned_fps;
        let mut x = State::zeros();
        x.fixed_rows_mut::<3>(R).copy_from(r_star);
        x.fixed_rows_mut::<3>(D).copy_from(&(v * beta));
        x[BETA] = beta;
        let mut p = Covariance::zeros();
        p.fixed_view_mut::<3, 3>(R, R).copy_from(r_covariance);
        let relative = (prior.relative_velocity_sigma_fps * beta).powi(2);
        let d_block = Mat3::identity() * relative + v * v.transpose() * sigma_beta.powi(2);
        p.fixed_view_mut::<3, 3>(D, D).copy_from(&d_block);
        let d_beta = v * sigma_beta.powi(2);
        p.fixed_view_mut::<3, 1>(D, BETA).copy_from(&d_beta);
        p.fixed_view_mut::<1, 3>(BETA, D)
            .copy_from(&d_beta.transpose());
        let accel = (prior.acceleration_sigma_fps2 * beta).powi(2);
        p.fixed_view_mut::<3, 3>(A, A)
            .copy_from(&(Mat3::identity() * accel));
        p[(BETA, BETA)] = sigma_beta.powi(2);
        let gust = noise.gust_variance(beta);
        p.fixed_view_mut::<3, 3>(G, G)
            .copy_from(&(Mat3::identity() * gust));
        if let Some(swing) = noise.swing {
            let stationary = swing.stationary(beta);
            for i in 0..3 {
                p[(SWING + i, SWING + i)] = stationary[(0, 0)];
                p[(SWING_RATE + i, SWING_RATE + i)] = stationary[(1, 1)];
            }
        }
        Self {
            x,
            p,
            noise,
            t_s,
            follower_position_ned_ft: *follower_position_ned_ft,
            beta_bounds_per_ft: prior
                .size_bounds_ft
                .map(|(min, max)| (1.0 / max, 1.0 / min)),
        }
    }

    /// With the size's bounds, projects x̂ onto β ∈ [1/b_max, 1/b_min], weighted by P⁻¹ (the
    /// estimate projection of a linearly constrained Kalman filter): x̂ ← x̂ - P e_β (β̂ - β_b)
    /// / P_ββ with β_b the nearer bound, which moves every state with β by its covariance
    /// with β, so that r̂, d̂ and â stay the ones the measurements give for that β. P is kept.
    fn keep_size_within_bounds(&mut self) {
        let Some((low, high)) = self.beta_bounds_per_ft else {
            return;
        };
        let beta = self.x[BETA];
        let bound = beta.clamp(low, high);
        if bound != beta {
            self.move_size_to(bound);
        }
    }

    /// Moves β̂ to `beta_per_ft`, every state with it by its covariance with β: x̂ ← x̂ - P e_β
    /// (β̂ - β) / P_ββ. P is kept.
    fn move_size_to(&mut self, beta_per_ft: f64) {
        let variance = self.p[(BETA, BETA)];
        if variance <= 0.0 {
            return;
        }
        let column: State = self.p.column(BETA).into_owned();
        self.x -= column * ((self.x[BETA] - beta_per_ft) / variance);
        self.x[BETA] = beta_per_ft;
    }

    /// Takes the size from another reading of it (docs/equations.md, The size from the
    /// excitation as an instrument): β̂ moved to `beta_per_ft` as [`Self::move_size_to`]
    /// moves it, and β's row and column of P scaled so that its σ is `sigma_per_ft`, its
    /// correlations with the other states kept.
    pub fn take_size(&mut self, beta_per_ft: f64, sigma_per_ft: f64) {
        self.move_size_to(beta_per_ft);
        let variance = self.p[(BETA, BETA)];
        if variance <= 0.0 {
            return;
        }
        let scale = sigma_per_ft / variance.sqrt();
        let mut column = self.p.column_mut(BETA);
        column *= scale;
        let mut row = self.p.row_mut(BETA);
        row *= scale;
    }

    /// The posterior's estimate.
    pub fn posterior(&self) -> FilterEstimate {
        self.estimate_of(&self.x, &self.p)
    }

    /// σ of the heading of the posterior's target velocity d̂ + ĝ (its horizontal
    /// direction), rad: the horizontal part of its covariance across it over its squared
    /// horizontal length (infinite for a velocity without a horizontal part).
    pub fn heading_sigma_rad(&self) -> f64 {
        let d = self.x.fixed_rows::<3>(D) + self.x.fixed_rows::<3>(G);
        let horizontal_sq = d[0] * d[0] + d[1] * d[1];
        if horizontal_sq <= 0.0 {
            return f64::INFINITY;
        }
        let across = Vec3::new(-d[1], d[0], 0.0) / horizontal_sq.sqrt();
        let block = |i: usize, j: usize| -> Mat3 { self.p.fixed_view::<3, 3>(i, j).into() };
        let p_vv = block(D, D) + block(D, G) + block(G, D) + block(G, G);
        ((across.transpose() * p_vv * across)[(0, 0)].max(0.0) / horizontal_sq).sqrt()
    }

    /// The estimate predicted to `t_s`, when the follower is at `follower_position_ned_ft`
    /// (the state's mean only; the filter is unchanged).
    pub fn estimate_at(&self, t_s: f64, follower_position_ned_ft: &Vec3) -> FilterEstimate {
        let phi = self.transition(t_s, follower_position_ned_ft);
        FilterEstimate {
            beta_sigma_per_ft: self.p[(BETA, BETA)].max(0.0).sqrt(),
            ..self.estimate_of(&(phi * self.x), &self.p)
        }
    }

    /// Propagates the posterior to `t_s`, when the follower is at `follower_position_ned_ft`.
    pub fn predict_to(&mut self, t_s: f64, follower_position_ned_ft: &Vec3) {
        let phi = self.transition(t_s, follower_position_ned_ft);
        let q = self.process_noise(t_s, follower_position_ned_ft);
        self.x = phi * self.x;
        self.p = phi * self.p * phi.transpose() + q;
        self.p = (self.p + self.p.transpose()) * 0.5;
        self.t_s = t_s;
        self.follower_position_ned_ft = *follower_position_ned_ft;
    }

    /// Fuses a measurement r* of covariance `r_covariance` taken at the posterior's time (call
    /// [`Self::predict_to`] first). Joseph form, so P stays symmetric positive.
    pub fn update(&mut self, r_star: &Vec3, r_covariance: &Mat3) -> Innovation {
        self.update_within(r_star, r_covariance, Gates::OPEN)
    }

    /// [`Self::update`], unless the measurement's normalised innovation νᵀ S⁻¹ ν exceeds
    /// `gates.innovation` (a validation gate, docs/equations.md, The innovation gate), that of
    /// its bearing exceeds `gates.bearing` where that gate weighs it (The bearing gate), or
    /// either is not finite: then
    /// the posterior is left as it is, and the innovation says so (`fused` false).
    pub fn update_within(
        &mut self,
        r_star: &Vec3,
        r_covariance: &Mat3,
        gates: Gates,
    ) -> Innovation {
        let predicted: Vec3 = self.x.fixed_rows::<3>(R).into_owned();
        let residual = r_star - predicted;
        let s: Mat3 = self.p.fixed_view::<3, 3>(R, R) + r_covariance;
        let bearing_normalised_sq = if gates.weighs_bearing(self.range_off(r_star)) {
            self.bearing_normalised_sq(r_star, r_covariance)
        } else {
            0.0
        };
        let rejected = |normalised_sq| Innovation {
            residual,
            normalised_sq,
            bearing_normalised_sq,
            fused: false,
        };
        let Some(s_inv) = s.try_inverse() else {
            return rejected(f64::INFINITY);
        };
        let normalised_sq = (residual.transpose() * s_inv * residual)[(0, 0)];
        // Not a number (from a measurement that is not finite), or outside a gate.
        let outside = |value: f64, gate: f64| value.is_nan() || value > gate;
        if outside(normalised_sq, gates.innovation) || outside(bearing_normalised_sq, gates.bearing)
        {
            return rejected(normalised_sq);
        }
        let gain: Gain = self.p.fixed_view::<FILTER_STATE_LEN, 3>(0, R) * s_inv;
        self.x += gain * residual;
        let mut kh = Covariance::zeros();
        kh.fixed_view_mut::<FILTER_STATE_LEN, 3>(0, R)
            .copy_from(&gain);
        let i_kh = Covariance::identity() - kh;
        self.p = i_kh * self.p * i_kh.transpose() + gain * r_covariance * gain.transpose();
        self.p = (self.p + self.p.transpose()) * 0.5;
        self.keep_size_within_bounds();
        Innovation {
            residual,
            normalised_sq,
            bearing_normalised_sq,
            fused: true,
        }
    }

    /// |ln(‖r*‖ / ‖r̂‖)|, r̂ the posterior's: how far a measurement's range, and so its length,
    /// is off the prediction's, either way (not a number where either is not finite or r̂ is
    /// zero). The bearing gate weighs the measurements far off it, the gate's re-opening takes
    /// only those near it.
    pub fn range_off(&self, r_star: &Vec3) -> f64 {
        (r_star.norm() / self.x.fixed_rows::<3>(R).norm())
            .ln()
            .abs()
    }

    /// The normalised square of a measurement's bearing innovation against the posterior
    /// (docs/equations.md, The bearing gate): where the ray through r* meets the plane across
    /// the predicted line of sight at the prediction's range |r̂⁻|, against the prediction's
    /// covariance across that line plus the measurement's across its own ray, scaled to that
    /// range. The measurement's length (its spread along its ray) does not enter, so a short
    /// fragment reads its bearing's error whatever the range its length implies. ∞ for a
    /// measurement behind the prediction's plane or a degenerate covariance.
    pub fn bearing_normalised_sq(&self, r_star: &Vec3, r_covariance: &Mat3) -> f64 {
        let predicted: Vec3 = self.x.fixed_rows::<3>(R).into_owned();
        let range = predicted.norm();
        let (Some(sight), Some(ray)) = (
            predicted.try_normalize(f64::MIN_POSITIVE),
            r_star.try_normalize(f64::MIN_POSITIVE),
        ) else {
            return f64::INFINITY;
        };
        let cos = sight.dot(&ray);
        if cos.is_nan() || cos <= 0.0 {
            return f64::INFINITY;
        }
        let across = plane_across(&sight);
        let residual = across * ray * (range / cos);
        let off_ray = Mat3::identity() - ray * ray.transpose();
        let measured = off_ray * r_covariance * off_ray * (range / r_star.norm()).powi(2);
        let predicted_covariance: Mat3 = self.p.fixed_view::<3, 3>(R, R).into_owned();
        let s: Matrix2<f64> = across * (predicted_covariance + measured) * across.transpose();
        s.try_inverse().map_or(f64::INFINITY, |s_inv| {
            (residual.transpose() * s_inv * residual)[(0, 0)]
        })
    }

    /// Scales the covariance of the kinematic states (r, d, a and g, and their
    /// cross-covariances with β by its square root) by `factor` ≥ 1, β's own kept: a
    /// congruence, so P stays positive. The filter's belief about where the target is and how
    /// it moves widens, its belief about the size (earned over tens of seconds of own motion)
    /// does not (docs/equations.md, The gate re-opened).
    pub fn widen_kinematics(&mut self, factor: f64) {
        let root = factor.max(1.0).sqrt();
        let mut scale = State::repeat(root);
        scale[BETA] = 1.0;
        let d = Covariance::from_diagonal(&scale);
        self.p = d * self.p * d;
    }

    /// Fuses a measured acceleration of the target across its velocity, `accel_fps2` ft/s²
    /// along the unit vector `across_ned` with variance `variance_fps4`, at the posterior's
    /// time (docs/equations.md, The target's bank from its wing line): h(x) = c · (a - g/τ_g +
    /// q̇) / β, the path's, the gust's and the swing's acceleration in feet, by an iterated
    /// extended Kalman update (relinearised at each iterate, so that the update does not claim
    /// from a linearisation about a lagging â an information about b that the measurement does
    /// not carry). Not fused, as [`Self::update_within`], outside `gate` or while β̂ ≤ 0;
    /// whether it was.
    pub fn update_lateral_acceleration(
        &mut self,
        across_ned: &Vec3,
        accel_fps2: f64,
        variance_fps4: f64,
        gate: f64,
    ) -> bool {
        let tau = self.noise.gust_time_s;
        // The swing's acceleration q̇ = -ω² p - (2/τ_s) q, as coefficients on p and q.
        let (on_swing, on_swing_rate) = self
            .noise
            .swing
            .map_or((0.0, 0.0), |s| (-s.omega_rps.powi(2), -2.0 / s.time_s));
        let model = |x: &State| -> (f64, State) {
            let beta = x[BETA];
            let scaled: Vec3 = x.fixed_rows::<3>(A) - x.fixed_rows::<3>(G) / tau
                + x.fixed_rows::<3>(SWING) * on_swing
                + x.fixed_rows::<3>(SWING_RATE) * on_swing_rate;
            let predicted = across_ned.dot(&scaled) / beta;
            let mut h = State::zeros();
            for i in 0..3 {
                h[A + i] = across_ned[i] / beta;
                h[G + i] = -across_ned[i] / (tau * beta);
                h[SWING + i] = across_ned[i] * on_swing / beta;
                h[SWING_RATE + i] = across_ned[i] * on_swing_rate / beta;
            }
            h[BETA] = -predicted / beta;
            (predicted, h)
        };
        // The first iterate is the prior: its innovation decides the gate.
        let (mut predicted, mut h) = model(&self.x);
        let p_h = self.p * h;
        let s = state_dot(&h, &p_h) + variance_fps4;
        let residual = accel_fps2 - predicted;
        let normalised_sq = residual * residual / s;
        // β̂ ≤ 0, not a number, or outside the gate.
        if self.x[BETA] <= 0.0 || normalised_sq.is_nan() || normalised_sq > gate {
            return false;
        }
        let mut iterate = self.x;
        let mut gain = p_h / s;
        for remaining in (0..LATERAL_ITERATIONS).rev() {
            let next =
                self.x + gain * (accel_fps2 - predicted - state_dot(&h, &(self.x - iterate)));
            if next[BETA] <= 0.0 {
                break;
            }
            iterate = next;
            if remaining == 0 {
                break;
            }
            (predicted, h) = model(&iterate);
            let p_h = self.p * h;
            gain = p_h / (state_dot(&h, &p_h) + variance_fps4);
        }
        self.x = iterate;
        let i_kh = Covariance::identity() - gain * h.transpose();
        self.p = i_kh * self.p * i_kh.transpose() + gain * gain.transpose() * variance_fps4;
        self.p = (self.p + self.p.transpose()) * 0.5;
        self.keep_size_within_bounds();
        true
    }

    /// Φ from the posterior's time to `t_s` (module docs).
    fn transition(&self, t_s: f64, follower_position_ned_ft: &Vec3) -> Covariance {
        let dt = t_s - self.t_s;
        let moved = follower_position_ned_ft - self.follower_position_ned_ft;
        let tau = self.noise.gust_time_s;
        let decay = (-dt / tau).exp();
        let mut phi = Covariance::identity();
        for i in 0..3 {
            phi[(R + i, D + i)] = dt;
            phi[(R + i, A + i)] = 0.5 * dt * dt;
            phi[(D + i, A + i)] = dt;
            phi[(R + i, BETA)] = -moved[i];
            phi[(R + i, G + i)] = tau * (1.0 - decay);
            phi[(G + i, G + i)] = decay;
        }
        if let Some(swing) = self.noise.swing {
            add_swing_transition(&mut phi, &swing.transition(dt));
        }
        phi
    }

    /// Q over the interval from the posterior's time to `t_s` (module docs).
    fn process_noise(&self, t_s: f64, follower_position_ned_ft: &Vec3) -> Covariance {
        let dt = t_s - self.t_s;
        let moved = follower_position_ned_ft - self.follower_position_ned_ft;
        let (qj, qb) = (self.noise.jerk_psd, self.noise.inverse_size_psd);
        let mut q = Covariance::zeros();
        let (dt2, dt3) = (dt * dt, dt * dt * dt);
        let jerk = [
            [dt3 * dt2 / 20.0, dt2 * dt2 / 8.0, dt3 / 6.0],
            [dt2 * dt2 / 8.0, dt3 / 3.0, dt2 / 2.0],
            [dt3 / 6.0, dt2 / 2.0, dt],
        ];
        for i in 0..3 {
            for (bi, row) in [R, D, A].iter().zip(jerk) {
                for (bj, value) in [R, D, A].iter().zip(row) {
                    q[(bi + i, bj + i)] = qj * value;
                }
            }
            for j in 0..3 {
                q[(R + i, R + j)] += qb * moved[i] * moved[j] * dt / 3.0;
            }
            q[(R + i, BETA)] = -qb * moved[i] * dt / 2.0;
            q[(BETA, R + i)] = q[(R + i, BETA)];
        }
        q[(BETA, BETA)] = qb * dt;
        self.add_gust_noise(&mut q, dt);
        self.add_swing_noise(&mut q, dt);
        q
    }

    /// Adds the swing's share of Q over `dt`: per axis, the oscillator's Q_d = P∞ - Φ P∞ Φᵀ
    /// (P∞ its stationary covariance at β̂), which r, moving by p's increment, shares with p.
    fn add_swing_noise(&self, q: &mut Covariance, dt: f64) {
        let Some(swing) = self.noise.swing else {
            return;
        };
        let stationary = swing.stationary(self.x[BETA].max(0.0));
        let phi = swing.transition(dt);
        let q_d = stationary - phi * stationary * phi.transpose();
        for i in 0..3 {
            let (p, v, r) = (SWING + i, SWING_RATE + i, R + i);
            let blocks = [
                (p, p, q_d[(0, 0)]),
                (p, v, q_d[(0, 1)]),
                (v, v, q_d[(1, 1)]),
                (r, r, q_d[(0, 0)]),
                (r, p, q_d[(0, 0)]),
                (r, v, q_d[(0, 1)]),
            ];
            for (a, b, value) in blocks {
                q[(a, b)] += value;
                if a != b {
                    q[(b, a)] += value;
                }
            }
        }
    }

    /// Adds the integrated Gauss-Markov gust's share of Q over `dt` (module docs): with
    /// φ = e^(-Δ/τ), Q_gg = q τ (1 - φ²)/2, Q_rg = q τ² (1 - φ)²/2 and
    /// Q_rr = q τ² (Δ - 2τ (1 - φ) + τ (1 - φ²)/2).
    fn add_gust_noise(&self, q: &mut Covariance, dt: f64) {
        let tau = self.noise.gust_time_s;
        let q_g = 2.0 * self.noise.gust_variance(self.x[BETA].max(0.0)) / tau;
        if q_g == 0.0 {
            return;
        }
        let decay = (-dt / tau).exp();
        let gg = q_g * tau * (1.0 - decay * decay) / 2.0;
        let rg = q_g * tau * tau * (1.0 - decay).powi(2) / 2.0;
        let rr =
            q_g * tau * tau * (dt - 2.0 * tau * (1.0 - decay) + tau * (1.0 - decay * decay) / 2.0);
        for i in 0..3 {
            q[(G + i, G + i)] += gg;
            q[(R + i, G + i)] += rg;
            q[(G + i, R + i)] += rg;
            q[(R + i, R + i)] += rr;
        }
    }

    fn estimate_of(&self, x: &State, p: &Covariance) -> FilterEstimate {
        FilterEstimate {
            r: x.fixed_rows::<3>(R).into(),
            d_per_s: x.fixed_rows::<3>(D) + x.fixed_rows::<3>(G),
            a_per_s2: x.fixed_rows::<3>(A) - x.fixed_rows::<3>(G) / self.noise.gust_time_s,
            beta_per_ft: x[BETA],
            beta_sigma_per_ft: p[(BETA, BETA)].max(0.0).sqrt(),
            swing: x.fixed_rows::<3>(SWING).into(),
        }
    }
}

/// a · b over the state, summed as the kinematic and size states first and the swing's
/// after: without the swing (its entries zero) the sum is, to the bit, the one over the
/// 13-state filter it had before the swing joined it (nalgebra sums in blocks of eight).
fn state_dot(a: &State, b: &State) -> f64 {
    a.fixed_rows::<SWING>(0).dot(&b.fixed_rows::<SWING>(0))
        + a.fixed_rows::<6>(SWING).dot(&b.fixed_rows::<6>(SWING))
}

/// Writes one axis's swing transition `swing` (rows and columns p, q) into Φ for every axis,
/// with r moving by p's increment: r⁺ = r + ... + (p⁺ - p).
fn add_swing_transition(phi: &mut Covariance, swing: &Matrix2<f64>) {
    for i in 0..3 {
        let (p, v, r) = (SWING + i, SWING_RATE + i, R + i);
        phi[(p, p)] = swing[(0, 0)];
        phi[(p, v)] = swing[(0, 1)];
        phi[(v, p)] = swing[(1, 0)];
        phi[(v, v)] = swing[(1, 1)];
        phi[(r, p)] = swing[(0, 0)] - 1.0;
        phi[(r, v)] = swing[(0, 1)];
    }
}

/// Two orthonormal rows across the unit vector `sight`: a basis of the plane normal to it.
fn plane_across(sight: &Vec3) -> SMatrix<f64, 2, 3> {
    let axis = sight.iamin();
    let first = sight.cross(&Vec3::ith(axis, 1.0)).normalize();
    let second = sight.cross(&first);
    SMatrix::<f64, 2, 3>::from_rows(&[first.transpose(), second.transpose()])
}

#[cfg(test)]
mod tests;
