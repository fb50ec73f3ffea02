//! A loosely coupled INS/GPS's errors (`[navigation] mode = "ins_gps"`; docs/equations.md,
//! The follower's own navigation and sensors). Per axis, with every forcing held over a step
//! and each process stepped exactly ([`GaussMarkov`]):
//!
//! - GPS: at each fix (`gps_rate_hz`) its error is a slow Gauss-Markov part (σ_g, τ_g) plus a
//!   white part (σ_w), held until the next fix; the vertical axis is scaled by
//!   `gps_vertical_scale`.
//! - velocity: ė_v = (τ_v L_BEᵀ b_a - e_v) / τ_v + w: Gauss-Markov (σ_v, τ_v) about the
//!   accelerometer bias b_a integrated over the aiding's time constant.
//! - position: ė_p = e_v + (g - e_p) / τ_p: the INS carries the position between fixes with its
//!   velocity error and the filter pulls it toward the held fix error g with lag τ_p, so the
//!   solution moves smoothly. The INS's own displacement, without the fixes, errs by
//!   ∫ e_v dt from zero at the start.
//! - roll, pitch: ė = (m - e) / τ_a + w with m = b_g τ_a + tilt(b_a) (gravity aiding: the gyro
//!   bias b_g settles at b_g τ_a, the accelerometer bias reads as a tilt b_a / g) and
//!   stationary σ² = σ_a² + N² τ_a / 2 (the aiding's residual σ_a and the angle random walk
//!   N filtered by the loop).
//! - heading: the same with τ_h, σ_h and m = b_g,z τ_h (GPS-track aiding): for t ≪ τ_h it
//!   drifts at the gyro bias, b_g,z t.
//!
//! The biases are drawn once per run (σ of the keys), every process starts in its steady state.

use super::NavigationErrors;
use super::gauss_markov::GaussMarkov;
use crate::frames::{EulerAngles, Vec3};
use crate::scenario::NavigationSection;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

/// Standard gravity, ft/s².
const G_FPS2: f64 = 32.174;
/// Seconds in an hour.
const HOUR_S: f64 = 3600.0;

/// The INS/GPS error processes of one run.
#[derive(Debug, Clone)]
pub struct InsGps {
    rng: ChaCha8Rng,
    /// GPS slow error per axis.
    gps_slow: [GaussMarkov; 3],
    /// σ of the per-fix white error per axis, ft.
    gps_white_ft: Vec3,
    gps_period_s: f64,
    position_lag: GaussMarkov,
    velocity: GaussMarkov,
    /// Roll, pitch (gravity aiding), heading (GPS-track aiding).
    attitude: [GaussMarkov; 3],
    /// b_g (body p, q, r), rad/s.
    gyro_bias_rps: Vec3,
    /// b_a (body), ft/s².
    accel_bias_body_fps2: Vec3,
    gps_slow_ft: Vec3,
    /// The fix error held now (slow + white), ft.
    gps_fix_ft: Vec3,
    /// Time to the next fix, s.
    to_next_fix_s: f64,
    errors: NavigationErrors,
}

impl InsGps {
    /// The processes `[navigation]` states, drawn from `seed`, started in steady state for a
    /// follower at `attitude`.
    pub fn new(section: &NavigationSection, seed: u64, attitude: &EulerAngles) -> Self {
        let n = section;
        let scale = Vec3::new(1.0, 1.0, n.gps_vertical_scale);
        let gm = |tau: f64, sigma: f64| GaussMarkov {
            time_constant_s: tau,
            sigma,
        };
        let arw_rad_per_sqrt_s = n.angle_random_walk_deg_per_sqrt_h.to_radians() / HOUR_S.sqrt();
        let aided = |tau: f64, sigma_deg: f64| {
            let sigma = sigma_deg.to_radians();
            gm(
                tau,
                (sigma * sigma + arw_rad_per_sqrt_s.powi(2) * tau / 2.0).sqrt(),
            )
        };
        let level = aided(n.attitude_time_constant_s, n.attitude_sigma_deg);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut normals = || Vec3::from_fn(|_, _| rng.sample::<f64, _>(StandardNormal));
        let gyro_bias_rps = normals() * (n.gyro_bias_deg_per_h.to_radians() / HOUR_S);
        let accel_bias_body_fps2 = normals() * (n.accel_bias_milli_g * 1e-3 * G_FPS2);
        let mut ins = Self {
            gps_slow: [0, 1, 2]
                .map(|i| gm(n.gps_correlation_time_s, n.gps_position_sigma_ft * scale[i])),
            gps_white_ft: scale * n.gps_noise_sigma_ft,
            gps_period_s: 1.0 / n.gps_rate_hz,
            position_lag: gm(n.position_time_constant_s, 0.0),
            velocity: gm(n.velocity_time_constant_s, n.velocity_sigma_fps),
            attitude: [
                level,
                level,
                aided(n.heading_time_constant_s, n.heading_sigma_deg),
            ],
            gyro_bias_rps,
            accel_bias_body_fps2,
            gps_slow_ft: Vec3::zeros(),
            gps_fix_ft: Vec3::zeros(),
            to_next_fix_s: 0.0,
            errors: NavigationErrors::default(),
            rng,
        };
        ins.start(attitude);
        ins
    }

    /// Every process drawn from its steady state (position at its mean).
    fn start(&mut self, attitude: &EulerAngles) {
        let velocity_mean = self.velocity_mean_fps(attitude);
        let attitude_mean = self.attitude_mean_rad();
        for i in 0..3 {
            let [ng, nv, na] = [self.normal(), self.normal(), self.normal()];
            self.gps_slow_ft[i] = self.gps_slow[i].stationary(0.0, ng);
            self.errors.velocity_ned_fps[i] = self.velocity.stationary(velocity_mean[i], nv);
            self.errors.attitude_rad[i] = self.attitude[i].stationary(attitude_mean[i], na);
        }
        self.draw_fix();
        self.errors.position_ned_ft = self.position_mean_ft();
    }

    fn normal(&mut self) -> f64 {
        self.rng.sample(StandardNormal)
    }

    /// A GPS fix: the slow error stepped over the fix period, a new white draw, held.
    fn draw_fix(&mut self) {
        for i in 0..3 {
            let n = self.normal();
            let white = self.gps_white_ft[i] * self.normal();
            self.gps_slow_ft[i] =
                self.gps_slow[i].step(self.gps_slow_ft[i], 0.0, self.gps_period_s, n);
            self.gps_fix_ft[i] = self.gps_slow_ft[i] + white;
        }
        self.to_next_fix_s += self.gps_period_s;
    }

    /// τ_v L_BEᵀ b_a: where the velocity error settles for the accelerometer bias.
    fn velocity_mean_fps(&self, attitude: &EulerAngles) -> Vec3 {
        attitude.body_from_ned().transpose()
            * self.accel_bias_body_fps2
            * self.velocity.time_constant_s
    }

    /// Where roll, pitch and heading errors settle: b_g τ, plus the tilt the accelerometer
    /// bias reads as (δφ = -b_y / g, δθ = b_x / g).
    fn attitude_mean_rad(&self) -> Vec3 {
        let b = &self.accel_bias_body_fps2;
        let tilt = Vec3::new(-b.y / G_FPS2, b.x / G_FPS2, 0.0);
        Vec3::from_fn(|i, _| self.gyro_bias_rps[i] * self.attitude[i].time_constant_s) + tilt
    }

    /// g + τ_p e_v: where the position error settles for the held fix and velocity error.
    fn position_mean_ft(&self) -> Vec3 {
        self.gps_fix_ft + self.errors.velocity_ned_fps * self.position_lag.time_constant_s
    }

    /// Advances every process by `dt_s` for a follower at `attitude` (a fix when one is due).
    pub fn advance(&mut self, dt_s: f64, attitude: &EulerAngles) {
        self.to_next_fix_s -= dt_s;
        if self.to_next_fix_s <= 1e-9 {
            self.draw_fix();
        }
        let position_mean = self.position_mean_ft();
        let velocity_mean = self.velocity_mean_fps(attitude);
        let attitude_mean = self.attitude_mean_rad();
        for i in 0..3 {
            let e = &mut self.errors;
            e.position_ned_ft[i] =
                self.position_lag
                    .step(e.position_ned_ft[i], position_mean[i], dt_s, 0.0);
            let (nv, na) = (self.normal(), self.normal());
            let e = &mut self.errors;
            let velocity_before = e.velocity_ned_fps[i];
            e.velocity_ned_fps[i] = self
                .velocity
                .step(velocity_before, velocity_mean[i], dt_s, nv);
            e.inertial_position_ned_ft[i] += 0.5 * (velocity_before + e.velocity_ned_fps[i]) * dt_s;
            e.attitude_rad[i] =
                self.attitude[i].step(e.attitude_rad[i], attitude_mean[i], dt_s, na);
        }
    }

    /// The errors now.
    pub fn errors(&self) -> NavigationErrors {
        self.errors
    }

    /// This run's gyro biases b_g (body p, q, r), rad/s.
    pub fn gyro_bias_rps(&self) -> Vec3 {
        self.gyro_bias_rps
    }

    /// This run's accelerometer biases b_a (body), ft/s².
    pub fn accel_bias_body_fps2(&self) -> Vec3 {
        self.accel_bias_body_fps2
    }

    /// The stationary σ of the position error per axis about its mean, ft: the slow GPS error
    /// through the lag, σ_g² τ_g / (τ_g + τ_p); the held white fixes through the lag, averaged
    /// over a fix period; the velocity error's τ_p e_v through the lag,
    /// (τ_p σ_v)² τ_v / (τ_v + τ_p). (The accelerometer bias only moves the mean.)
    pub fn position_sigma_ft(&self) -> Vec3 {
        let tau_p = self.position_lag.time_constant_s;
        let tau_v = self.velocity.time_constant_s;
        let white = held_white_through_lag(self.gps_period_s, tau_p);
        let from_velocity = (tau_p * self.velocity.sigma).powi(2) * tau_v / (tau_v + tau_p);
        Vec3::from_fn(|i, _| {
            let slow = &self.gps_slow[i];
            let from_slow =
                slow.sigma.powi(2) * slow.time_constant_s / (slow.time_constant_s + tau_p);
            (from_slow + self.gps_white_ft[i].powi(2) * white + from_velocity).sqrt()
        })
    }
}

/// The variance, averaged over a fix period T, of a unit-variance white sequence held for T
/// and passed through the lag 1/(τ s + 1): at the fixes the lag's output has variance
/// V₀ = (1 - a)/(1 + a), a = e^(-T/τ); a time s after a fix it is (1 - e^(-s/τ))² +
/// V₀ e^(-2s/τ) (the new fix and the old output are independent); averaged numerically.
fn held_white_through_lag(period_s: f64, lag_s: f64) -> f64 {
    let a = (-period_s / lag_s).exp();
    let v0 = (1.0 - a) / (1.0 + a);
    const POINTS: u32 = 1000;
    (0..POINTS)
        .map(|k| {
            let e = (-(f64::from(k) + 0.5) / f64::from(POINTS) * period_s / lag_s).exp();
            (1.0 - e).powi(2) + v0 * e * e
        })
        .sum::<f64>()
        / f64::from(POINTS)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fix held for a period much longer than the lag passes nearly whole; one much
    /// shorter is averaged away to about T / (2τ).
    #[test]
    fn held_white_noise_is_smoothed_by_the_lag() {
        assert!((held_white_through_lag(100.0, 1.0) - 1.0).abs() < 0.02);
        let short = held_white_through_lag(0.01, 10.0);
        assert!((short - 0.01 / 20.0).abs() < 0.1 * 0.01 / 20.0, "{short}");
    }

    /// Each fix is held: the position error's mean moves only at fixes.
    #[test]
    fn fixes_arrive_at_the_gps_rate() {
        let section = NavigationSection {
            gps_rate_hz: 2.0,
            ..NavigationSection::default()
        };
        let level = EulerAngles::new(0.0, 0.0, 0.0);
        let mut ins = InsGps::new(&section, 7, &level);
        let mut changes = 0;
        let mut last = ins.gps_fix_ft;
        for _ in 0..1000 {
            ins.advance(0.01, &level);
            if ins.gps_fix_ft != last {
                changes += 1;
                last = ins.gps_fix_ft;
            }
        }
        assert_eq!(changes, 20, "10 s at 2 Hz");
    }

    /// The INS's own position error is the trapezoidal integral of its velocity error from
    /// zero at the start, whatever the fixes do.
    #[test]
    fn the_inertial_position_integrates_the_velocity_error() {
        let level = EulerAngles::new(0.0, 0.0, 0.0);
        let mut ins = InsGps::new(&NavigationSection::default(), 3, &level);
        assert_eq!(ins.errors().inertial_position_ned_ft, Vec3::zeros());
        let dt_s = 0.01;
        let mut integral = Vec3::zeros();
        for _ in 0..500 {
            let before = ins.errors().velocity_ned_fps;
            ins.advance(dt_s, &level);
            integral += (before + ins.errors().velocity_ned_fps) * (0.5 * dt_s);
        }
        let e = ins.errors();
        assert!((e.inertial_position_ned_ft - integral).norm() < 1e-12);
        assert!(e.inertial_position_ned_ft != e.position_ned_ft);
    }
}
