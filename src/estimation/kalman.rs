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
//! Observability: with V_F constant, -β V_F t cannot be told from d t; β is learned only while
//! the follower's velocity changes differently from the target's (the excitation's job).

use crate::frames::{Mat3, Vec3};
use nalgebra::{SMatrix, SVector};

/// Length of the filter's state.
pub const FILTER_STATE_LEN: usize = 13;

type State = SVector<f64, FILTER_STATE_LEN>;
type Covariance = SMatrix<f64, FILTER_STATE_LEN, FILTER_STATE_LEN>;
type Gain = SMatrix<f64, FILTER_STATE_LEN, 3>;

/// Offsets of the blocks in the state.
const R: usize = 0;
const D: usize = 3;
const A: usize = 6;
const BETA: usize = 9;
const G: usize = 10;

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
}

impl FilterNoise {
    /// The white-jerk model alone: no gust velocity.
    pub fn without_gust(jerk_psd: f64, inverse_size_psd: f64) -> Self {
        Self {
            jerk_psd,
            inverse_size_psd,
            gust_sigma_fps: 0.0,
            gust_time_s: 1.0,
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
    /// Whether the measurement was fused (false: outside the validation gate).
    pub fused: bool,
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
        Self {
            x,
            p,
            noise,
            t_s,
            follower_position_ned_ft: *follower_position_ned_ft,
        }
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
        self.update_within(r_star, r_covariance, f64::INFINITY)
    }

    /// [`Self::update`], unless the measurement's normalised innovation νᵀ S⁻¹ ν exceeds
    /// `gate` (a validation gate, docs/equations.md, The innovation gate) or is not finite:
    /// then the posterior is left as it is, and the innovation says so (`fused` false).
    pub fn update_within(&mut self, r_star: &Vec3, r_covariance: &Mat3, gate: f64) -> Innovation {
        let residual = r_star - self.x.fixed_rows::<3>(R);
        let s: Mat3 = self.p.fixed_view::<3, 3>(R, R) + r_covariance;
        let rejected = |normalised_sq| Innovation {
            residual,
            normalised_sq,
            fused: false,
        };
        let Some(s_inv) = s.try_inverse() else {
            return rejected(f64::INFINITY);
        };
        let normalised_sq = (residual.transpose() * s_inv * residual)[(0, 0)];
        // Not a number (from a measurement that is not finite), or outside the gate.
        if normalised_sq.is_nan() || normalised_sq > gate {
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
        Innovation {
            residual,
            normalised_sq,
            fused: true,
        }
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
    /// time (docs/equations.md, The target's bank from its wing line): h(x) = c · (a - g/τ_g) / β,
    /// the path's and the gust's acceleration in feet, by an iterated extended Kalman update
    /// (relinearised at each iterate, so that the update does not claim from a linearisation
    /// about a lagging â an information about b that the measurement does not carry). Not
    /// fused, as [`Self::update_within`], outside `gate` or while β̂ ≤ 0; whether it was.
    pub fn update_lateral_acceleration(
        &mut self,
        across_ned: &Vec3,
        accel_fps2: f64,
        variance_fps4: f64,
        gate: f64,
    ) -> bool {
        let tau = self.noise.gust_time_s;
        let model = |x: &State| -> (f64, State) {
            let beta = x[BETA];
            let scaled: Vec3 = x.fixed_rows::<3>(A) - x.fixed_rows::<3>(G) / tau;
            let predicted = across_ned.dot(&scaled) / beta;
            let mut h = State::zeros();
            for i in 0..3 {
                h[A + i] = across_ned[i] / beta;
                h[G + i] = -across_ned[i] / (tau * beta);
            }
            h[BETA] = -predicted / beta;
            (predicted, h)
        };
        // The first iterate is the prior: its innovation decides the gate.
        let (mut predicted, mut h) = model(&self.x);
        let p_h = self.p * h;
        let s = h.dot(&p_h) + variance_fps4;
        let residual = accel_fps2 - predicted;
        let normalised_sq = residual * residual / s;
        // β̂ ≤ 0, not a number, or outside the gate.
        if self.x[BETA] <= 0.0 || normalised_sq.is_nan() || normalised_sq > gate {
            return false;
        }
        let mut iterate = self.x;
        let mut gain = p_h / s;
        for remaining in (0..LATERAL_ITERATIONS).rev() {
            let next = self.x + gain * (accel_fps2 - predicted - h.dot(&(self.x - iterate)));
            if next[BETA] <= 0.0 {
                break;
            }
            iterate = next;
            if remaining == 0 {
                break;
            }
            (predicted, h) = model(&iterate);
            let p_h = self.p * h;
            gain = p_h / (h.dot(&p_h) + variance_fps4);
        }
        self.x = iterate;
        let i_kh = Covariance::identity() - gain * h.transpose();
        self.p = i_kh * self.p * i_kh.transpose() + gain * gain.transpose() * variance_fps4;
        self.p = (self.p + self.p.transpose()) * 0.5;
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
        q
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
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};

    const B_FT: f64 = 8.0;

    fn prior() -> FilterPrior {
        FilterPrior {
            size_ft: 4.0,
            inverse_size_sigma_per_ft: 0.15,
            relative_velocity_sigma_fps: 15.0,
            acceleration_sigma_fps2: 3.0,
        }
    }

    /// A target flying straight at 50 ft/s north, a follower whose velocity is the target's
    /// plus `weave(t)`, measured every `period_s` with white noise σ (scaled units) and fused
    /// `latency_s` late from the follower's positions at capture. Returns the filter at 60 s.
    fn fly(
        weave: impl Fn(f64) -> Vec3,
        sigma: f64,
        period_s: f64,
        latency_s: f64,
    ) -> (TargetFilter, Vec<f64>) {
        let noise = FilterNoise::without_gust(1e-6, 1e-10);
        fly_target(weave, |_| Vec3::zeros(), noise, sigma, period_s, latency_s)
    }

    /// As [`fly`], the target's velocity `gust(t)` off its straight path, the filter's noise
    /// model `noise`.
    fn fly_target(
        weave: impl Fn(f64) -> Vec3,
        mut gust: impl FnMut(f64) -> Vec3,
        noise: FilterNoise,
        sigma: f64,
        period_s: f64,
        latency_s: f64,
    ) -> (TargetFilter, Vec<f64>) {
        let dt = 1e-3;
        let target_v = Vec3::new(50.0, 0.0, 0.0);
        let mut follower = Vec3::zeros();
        let mut target = Vec3::new(200.0, 50.0, 30.0);
        let covariance = Mat3::identity() * sigma * sigma;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let normal = Normal::new(0.0, sigma).expect("σ > 0");
        let mut filter: Option<TargetFilter> = None;
        let mut pending: Vec<(f64, Vec3, Vec3)> = Vec::new();
        let mut normalised = Vec::new();
        let steps = (60.0 / dt) as usize;
        let every = (period_s / dt).round() as usize;
        for k in 0..=steps {
            let t = k as f64 * dt;
            if k % every == 0 {
                let r = (target - follower) / B_FT;
                let n = Vec3::from_fn(|_, _| normal.sample(&mut rng));
                pending.push((t, r + n, follower));
            }
            while pending
                .first()
                .is_some_and(|(tk, _, _)| *tk + latency_s <= t + 1e-9)
            {
                let (tk, r_star, at) = pending.remove(0);
                match filter.as_mut() {
                    None => {
                        let v = target_v + weave(tk);
                        filter = Some(TargetFilter::new(
                            noise,
                            &prior(),
                            &r_star,
                            &covariance,
                            tk,
                            &at,
                            &v,
                        ));
                    }
                    Some(f) => {
                        f.predict_to(tk, &at);
                        normalised.push(f.update(&r_star, &covariance).normalised_sq);
                    }
                }
            }
            follower += (target_v + weave(t)) * dt;
            target += (target_v + gust(t)) * dt;
        }
        (filter.expect("measured"), normalised)
    }

    /// With a weaving follower the filter learns b within 1%, whatever the latency (frames
    /// fused at their capture time), and its residuals are consistent: the mean normalised
    /// square is the 3 of a χ² with 3 degrees of freedom (within 10%).
    #[test]
    fn weaving_follower_identifies_the_size() {
        let weave =
            |t: f64| Vec3::new(0.0, 0.0, 6.0 * (2.0 * std::f64::consts::PI * t / 6.0).cos());
        for latency_s in [0.0, 1.0 / 30.0, 2.0 / 30.0] {
            let (filter, normalised) = fly(weave, 0.02, 1.0 / 30.0, latency_s);
            let est = filter.posterior();
            assert!(
                (est.size_ft() - B_FT).abs() < 0.01 * B_FT,
                "{latency_s}: {est:?}"
            );
            assert!(est.size_sigma_ft() < 0.05, "{est:?}");
            let late = &normalised[normalised.len() / 2..];
            let mean = late.iter().sum::<f64>() / late.len() as f64;
            assert!(
                (mean - 3.0).abs() < 0.3,
                "mean normalised innovation {mean}"
            );
        }
    }

    /// A target whose velocity wanders about its straight path by a Gauss-Markov gust (σ 1.5
    /// ft/s per axis, τ 1.5 s, seeded): the filter with the gust states learns b within 10%
    /// and its ±3σ_b, with consistent residuals (mean normalised square within 25% of 3); the white-jerk
    /// filter alone (the same small q_j) cannot follow it: its residuals are many times
    /// larger than it expects.
    #[test]
    fn gust_states_follow_a_target_that_wanders_about_its_path() {
        let weave =
            |t: f64| Vec3::new(0.0, 0.0, 6.0 * (2.0 * std::f64::consts::PI * t / 6.0).cos());
        let (sigma_g, tau_g) = (1.5, 1.5);
        let mean_late = |noise: FilterNoise| {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
            let normal = Normal::new(0.0, 1.0).expect("σ > 0");
            let (mut u, mut last_t) = (Vec3::zeros(), 0.0);
            let gust = move |t: f64| {
                let dt: f64 = t - last_t;
                last_t = t;
                let decay = (-dt / tau_g).exp();
                let kick = sigma_g * (1.0 - decay * decay).sqrt();
                u = u * decay + Vec3::from_fn(|_, _| kick * normal.sample(&mut rng));
                u
            };
            let (filter, normalised) = fly_target(weave, gust, noise, 0.02, 1.0 / 30.0, 0.0);
            let late = &normalised[normalised.len() / 2..];
            (
                filter.posterior(),
                late.iter().sum::<f64>() / late.len() as f64,
            )
        };
        let with_gust = FilterNoise {
            gust_sigma_fps: sigma_g,
            gust_time_s: tau_g,
            ..FilterNoise::without_gust(1e-6, 1e-10)
        };
        let (est, mean) = mean_late(with_gust);
        let off_ft = (est.size_ft() - B_FT).abs();
        assert!(
            off_ft < 3.0 * est.size_sigma_ft() && off_ft < 0.1 * B_FT,
            "{est:?}"
        );
        assert!(
            (mean - 3.0).abs() < 0.75,
            "mean normalised innovation {mean}"
        );
        let (_, mean_jerk) = mean_late(FilterNoise::without_gust(1e-6, 1e-10));
        assert!(
            mean_jerk > 30.0,
            "white jerk: mean normalised innovation {mean_jerk}"
        );
    }

    /// A target flying straight for 10 s, then in S-turns (its acceleration across its path
    /// 6 cos(2π (t - 10) / 10) ft/s²), and a follower flying straight at its velocity, so that its own motion says
    /// nothing of b: with the turn's acceleration in feet fused beside each frame (as the
    /// wing line gives it, σ 0.3 ft/s²) the filter learns b within 1% (0.1% measured), with the truth inside
    /// its ±3σ_b; without it b̂ stays near its prior. A follower that turns as its target
    /// does learns nothing from the turn (the relative acceleration is what the image
    /// sees), and the filter must not claim it does.
    #[test]
    fn a_measured_turn_identifies_the_size_without_own_motion() {
        let (amplitude, omega) = (6.0, 2.0 * std::f64::consts::PI / 10.0);
        // A white jerk that follows the S-turns' 3.8 ft/s³ (with q_j = 0.05 â lags the turn
        // and β̂, fitted to the bank's prompt acceleration, ends 13% off).
        let noise = FilterNoise::without_gust(0.5, 1e-10);
        let offset = Vec3::new(40.0, 8.0, 0.0);
        let run = |with_turn: bool, mimic: bool| {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
            let (sigma_r, sigma_a) = (0.02, 0.3);
            let (normal_r, normal_a) = (
                Normal::new(0.0, sigma_r).expect("σ > 0"),
                Normal::new(0.0, sigma_a).expect("σ > 0"),
            );
            let covariance = Mat3::identity() * sigma_r * sigma_r;
            let target_at = |t: f64| {
                let turning = (t - 10.0).max(0.0);
                let (sin, cos) = (omega * turning).sin_cos();
                let lateral = amplitude / (omega * omega) * (1.0 - cos);
                let position = Vec3::new(50.0 * t, lateral, 0.0);
                let velocity = Vec3::new(50.0, amplitude / omega * sin, 0.0);
                let accel = Vec3::new(0.0, if t < 10.0 { 0.0 } else { amplitude * cos }, 0.0);
                (position, velocity, accel)
            };
            let (_, v0, _) = target_at(0.0);
            let measured = |rng: &mut rand_chacha::ChaCha8Rng, relative: Vec3| {
                relative / B_FT + Vec3::from_fn(|_, _| normal_r.sample(rng))
            };
            let r0 = measured(&mut rng, offset);
            let follower_at = |t: f64, position: Vec3| match mimic {
                true => position - offset,
                false => Vec3::new(50.0 * t, 0.0, 0.0) - offset,
            };
            let mut filter =
                TargetFilter::new(noise, &prior(), &r0, &covariance, 0.0, &-offset, &v0);
            for k in 1..=(60 * 30) {
                let t = k as f64 / 30.0;
                let (position, velocity, accel) = target_at(t);
                let follower = follower_at(t, position);
                filter.predict_to(t, &follower);
                filter.update(&measured(&mut rng, position - follower), &covariance);
                if with_turn {
                    let across = Vec3::new(-velocity.y, velocity.x, 0.0).normalize();
                    let read = across.dot(&accel) + normal_a.sample(&mut rng);
                    filter.update_lateral_acceleration(
                        &across,
                        read,
                        sigma_a * sigma_a,
                        f64::INFINITY,
                    );
                }
            }
            filter.posterior()
        };
        let est = run(true, false);
        let off_ft = (est.size_ft() - B_FT).abs();
        assert!(
            off_ft < 0.01 * B_FT && off_ft < 3.0 * est.size_sigma_ft(),
            "{est:?}"
        );
        for (with_turn, mimic) in [(false, false), (true, true)] {
            let blind = run(with_turn, mimic);
            let claimed = blind.size_sigma_ft();
            assert!(claimed > 1.0, "turn {with_turn}, mimic {mimic}: {blind:?}");
        }
    }

    /// With a follower flying the target's velocity the range is unobservable: b̂ stays near
    /// its prior and σ_b stays large.
    #[test]
    fn steady_follower_cannot_identify_the_size() {
        let (filter, _) = fly(|_| Vec3::zeros(), 0.02, 1.0 / 30.0, 0.0);
        let est = filter.posterior();
        assert!(est.size_sigma_ft() > 1.0, "{est:?}");
        assert!((est.size_ft() - 4.0).abs() < 1.0, "{est:?}");
    }

    /// The prediction between frames is exact for the model: a target at constant velocity,
    /// the follower anywhere, the predicted r equals the truth to round-off.
    #[test]
    fn prediction_follows_the_followers_motion() {
        let noise = FilterNoise::without_gust(0.0, 0.0);
        let p = FilterPrior {
            size_ft: B_FT,
            ..prior()
        };
        let target_v = Vec3::new(40.0, 10.0, 0.0);
        let mut filter = TargetFilter::new(
            noise,
            &p,
            &Vec3::new(25.0, 6.0, 4.0),
            &(Mat3::identity() * 1e-6),
            0.0,
            &Vec3::zeros(),
            &target_v,
        );
        // Exact d = V_T / b: the filter's prior d = β V_F(0) with V_F(0) = V_T.
        let follower_then = Vec3::new(12.0, -30.0, 7.0);
        let est = filter.estimate_at(0.5, &follower_then);
        let truth = Vec3::new(25.0, 6.0, 4.0) + (target_v * 0.5 - follower_then) / B_FT;
        assert!((est.r - truth).norm() < 1e-12, "{:?} vs {truth:?}", est.r);
        filter.predict_to(0.5, &follower_then);
        assert!((filter.posterior().r - truth).norm() < 1e-12);
    }

    /// A filter started at t = 0 on r* = (25, 6, 4) of covariance `covariance`, the follower
    /// at the origin flying north at 50 ft/s.
    fn started_at_25_ft(covariance: &Mat3) -> TargetFilter {
        TargetFilter::new(
            FilterNoise::without_gust(1e-4, 0.0),
            &prior(),
            &Vec3::new(25.0, 6.0, 4.0),
            covariance,
            0.0,
            &Vec3::zeros(),
            &Vec3::new(50.0, 0.0, 0.0),
        )
    }

    /// Invariant: the validation gate keeps out a measurement whose normalised innovation
    /// exceeds it, leaving the posterior as it was, and fuses one inside it as the ungated
    /// update does.
    #[test]
    fn gate_keeps_out_a_measurement_off_the_prediction() {
        let covariance = Mat3::identity() * 1e-4;
        let mut gated = started_at_25_ft(&covariance);
        gated.predict_to(0.1, &Vec3::new(5.0, 0.0, 0.0));
        let before = gated.posterior();
        let predicted = before.r;
        let far = predicted + Vec3::new(0.0, 5.0, 0.0);
        let rejected = gated.update_within(&far, &covariance, 16.3);
        assert!(
            !rejected.fused && rejected.normalised_sq > 16.3,
            "{rejected:?}"
        );
        assert_eq!(gated.posterior(), before);
        let near = predicted + Vec3::new(0.0, 0.01, 0.0);
        let mut ungated = gated.clone();
        let fused = gated.update_within(&near, &covariance, 16.3);
        assert!(fused.fused && fused.normalised_sq < 16.3, "{fused:?}");
        ungated.update(&near, &covariance);
        assert_eq!(gated.posterior(), ungated.posterior());
    }

    /// Invariant: widening the kinematics scales the r, d, a and g blocks of P by the factor
    /// and their covariances with β by its square root, leaves β's variance as it was, keeps
    /// P symmetric and positive, and lets a frame the gate kept out be taken with a
    /// normalised innovation of about its 3 degrees of freedom.
    #[test]
    fn widened_kinematics_keep_the_size_and_take_the_frame() {
        let covariance = Mat3::identity() * 1e-4;
        let mut filter = started_at_25_ft(&covariance);
        filter.predict_to(0.1, &Vec3::new(5.0, 0.0, 0.0));
        let far = filter.posterior().r + Vec3::new(0.0, 5.0, 0.0);
        let kept_out = filter.clone().update_within(&far, &covariance, 16.3);
        assert!(!kept_out.fused, "{kept_out:?}");
        let before = filter.p;
        let factor = kept_out.normalised_sq / 3.0;
        filter.widen_kinematics(factor);
        assert_eq!(filter.p[(BETA, BETA)], before[(BETA, BETA)]);
        assert!((filter.p[(R, R)] / before[(R, R)] - factor).abs() < 1e-9 * factor);
        assert!((filter.p[(D, BETA)] / before[(D, BETA)] - factor.sqrt()).abs() < 1e-9);
        assert!((filter.p - filter.p.transpose()).abs().max() < 1e-12);
        // Positive semi-definite (the gust block is zero without a gust model).
        let eigen = filter.p.symmetric_eigen().eigenvalues;
        assert!(eigen.min() >= -1e-12 * eigen.max(), "{eigen:?}");
        let taken = filter.update_within(&far, &covariance, 16.3);
        assert!(taken.fused && taken.normalised_sq < 3.5, "{taken:?}");
    }
}
