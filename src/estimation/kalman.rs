//! Range and size from the follower's own motion (docs/equations.md): a Kalman filter on
//! x = [r (3), d (3), a (3), β], with r = R/b the scaled relative position, d = V_T/b the scaled
//! target velocity (1/s), a = a_T/b its acceleration (1/s²) and β = 1/b (1/ft):
//! ```text
//! ṙ = d - β V_F(t)      ḋ = a      ȧ = w_j      β̇ = w_β      measurement r* = r + v
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
//! through -∫ w_β V_F, taken with V_F constant over the interval.
//!
//! Observability: with V_F constant, -β V_F t cannot be told from d t; β is learned only while
//! the follower's velocity changes differently from the target's (the excitation's job).

use crate::frames::{Mat3, Vec3};
use nalgebra::{SMatrix, SVector};

/// Length of the filter's state.
pub const FILTER_STATE_LEN: usize = 10;

type State = SVector<f64, FILTER_STATE_LEN>;
type Covariance = SMatrix<f64, FILTER_STATE_LEN, FILTER_STATE_LEN>;
type Gain = SMatrix<f64, FILTER_STATE_LEN, 3>;

/// Offsets of the blocks in the state.
const R: usize = 0;
const D: usize = 3;
const A: usize = 6;
const BETA: usize = 9;

/// The filter's noise model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilterNoise {
    /// q_j, the intensity of the white jerk of a = a_T/b, per axis, 1/s⁵.
    pub jerk_psd: f64,
    /// q_β, the intensity of the random walk of β = 1/b, 1/(ft² s).
    pub inverse_size_psd: f64,
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
        Self {
            x,
            p,
            noise,
            t_s,
            follower_position_ned_ft: *follower_position_ned_ft,
        }
    }

    /// Time of the posterior, s.
    pub fn time_s(&self) -> f64 {
        self.t_s
    }

    /// The posterior's estimate.
    pub fn posterior(&self) -> FilterEstimate {
        self.estimate_of(&self.x, &self.p)
    }

    /// σ of the heading of the posterior's d̂ (its horizontal direction), rad: the horizontal
    /// part of P_dd across d̂ over ‖d̂_h‖² (infinite for a d̂ without a horizontal part).
    pub fn heading_sigma_rad(&self) -> f64 {
        let d = self.x.fixed_rows::<3>(D);
        let horizontal_sq = d[0] * d[0] + d[1] * d[1];
        if horizontal_sq <= 0.0 {
            return f64::INFINITY;
        }
        let across = Vec3::new(-d[1], d[0], 0.0) / horizontal_sq.sqrt();
        let p_dd: Mat3 = self.p.fixed_view::<3, 3>(D, D).into();
        ((across.transpose() * p_dd * across)[(0, 0)].max(0.0) / horizontal_sq).sqrt()
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
        let residual = r_star - self.x.fixed_rows::<3>(R);
        let s: Mat3 = self.p.fixed_view::<3, 3>(R, R) + r_covariance;
        let Some(s_inv) = s.try_inverse() else {
            return Innovation {
                residual,
                normalised_sq: f64::INFINITY,
            };
        };
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
            normalised_sq: (residual.transpose() * s_inv * residual)[(0, 0)],
        }
    }

    /// Φ from the posterior's time to `t_s` (module docs).
    fn transition(&self, t_s: f64, follower_position_ned_ft: &Vec3) -> Covariance {
        let dt = t_s - self.t_s;
        let moved = follower_position_ned_ft - self.follower_position_ned_ft;
        let mut phi = Covariance::identity();
        for i in 0..3 {
            phi[(R + i, D + i)] = dt;
            phi[(R + i, A + i)] = 0.5 * dt * dt;
            phi[(D + i, A + i)] = dt;
            phi[(R + i, BETA)] = -moved[i];
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
        q
    }

    fn estimate_of(&self, x: &State, p: &Covariance) -> FilterEstimate {
        FilterEstimate {
            r: x.fixed_rows::<3>(R).into(),
            d_per_s: x.fixed_rows::<3>(D).into(),
            a_per_s2: x.fixed_rows::<3>(A).into(),
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
        let dt = 1e-3;
        let target_v = Vec3::new(50.0, 0.0, 0.0);
        let mut follower = Vec3::zeros();
        let target0 = Vec3::new(200.0, 50.0, 30.0);
        let noise = FilterNoise {
            jerk_psd: 1e-6,
            inverse_size_psd: 1e-10,
        };
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
                let r = (target0 + target_v * t - follower) / B_FT;
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
        let noise = FilterNoise {
            jerk_psd: 0.0,
            inverse_size_psd: 0.0,
        };
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
}
