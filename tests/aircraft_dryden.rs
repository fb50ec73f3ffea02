//! The Dryden gusts have MIL-F-8785C's low-altitude statistics: over a long run each
//! component's sample standard deviation is its σ, the u component's autocorrelation at lag
//! L_u/V is e^-1 and the w component's is ½e^-1 (the second-order form's (1 - τ/2T) e^{-τ/T});
//! `off` gives zero gusts; the same seed gives the same sequence and another seed another.
//!
//! Tolerances: for a correlated process of correlation time T observed for a time D, the
//! sample variance has relative standard deviation ≈ √(2T/D), so σ̂ has ≈ √(T/2D). With
//! h = 100 ft and V = 50 ft/s, T_u = L_u/V ≈ 10 s; D = 40 000 s gives ≈ 1.1 % for u (less for
//! w: T_w = 2 s), so the 10 % band is several standard errors wide and the seeds fixed. The
//! lag-T autocorrelation estimate has a standard error of about √(T/D) ≈ 1.6 %; its band is
//! ±0.05 (≈ 3 standard errors).

use wingman::frames::Vec3;
use wingman::world::atmosphere::{
    Atmosphere, AtmosphereConfig, DrydenTurbulence, TurbulenceLevel, dryden_intensities_fps,
    dryden_scale_lengths_ft,
};

const ALTITUDE_FT: f64 = 100.0;
const AIRSPEED_FPS: f64 = 50.0;
const DT_S: f64 = 0.05;

fn run(level: TurbulenceLevel, seed: u64, ticks: usize) -> Vec<Vec3> {
    let mut dryden = DrydenTurbulence::new(level, seed);
    (0..ticks)
        .map(|_| dryden.step(DT_S, AIRSPEED_FPS, ALTITUDE_FT))
        .collect()
}

fn std_dev(samples: &[f64]) -> f64 {
    let n = samples.len() as f64;
    let mean = samples.iter().sum::<f64>() / n;
    (samples.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / n).sqrt()
}

fn autocorrelation(samples: &[f64], lag: usize) -> f64 {
    let n = samples.len();
    let mean = samples.iter().sum::<f64>() / n as f64;
    let var = samples.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / n as f64;
    let cov = (0..n - lag)
        .map(|i| (samples[i] - mean) * (samples[i + lag] - mean))
        .sum::<f64>()
        / (n - lag) as f64;
    cov / var
}

#[test]
fn long_run_matches_dryden_intensities_and_correlation() {
    let ticks = (40_000.0 / DT_S) as usize;
    let gusts = run(TurbulenceLevel::Moderate, 7, ticks);
    let sigma = dryden_intensities_fps(TurbulenceLevel::Moderate, ALTITUDE_FT);
    let lengths = dryden_scale_lengths_ft(ALTITUDE_FT);
    for axis in 0..3 {
        let component: Vec<f64> = gusts.iter().map(|g| g[axis]).collect();
        let ratio = std_dev(&component) / sigma[axis];
        println!(
            "axis {axis}: sigma {:.3} ft/s, sample/sigma {ratio:.4}",
            sigma[axis]
        );
        assert!((ratio - 1.0).abs() < 0.10, "axis {axis}: ratio {ratio}");
    }
    let u: Vec<f64> = gusts.iter().map(|g| g.x).collect();
    let lag_u = (lengths.x / AIRSPEED_FPS / DT_S).round() as usize;
    let rho_u = autocorrelation(&u, lag_u);
    println!("u: lag {lag_u} ticks, autocorrelation {rho_u:.4} (e^-1 = 0.3679)");
    assert!((rho_u - (-1.0f64).exp()).abs() < 0.05, "rho_u {rho_u}");
    let w: Vec<f64> = gusts.iter().map(|g| g.z).collect();
    let lag_w = (lengths.z / AIRSPEED_FPS / DT_S).round() as usize;
    let rho_w = autocorrelation(&w, lag_w);
    println!("w: lag {lag_w} ticks, autocorrelation {rho_w:.4} (e^-1/2 = 0.1839)");
    assert!(
        (rho_w - 0.5 * (-1.0f64).exp()).abs() < 0.05,
        "rho_w {rho_w}"
    );
}

#[test]
fn off_is_zero_and_seeds_are_reproducible() {
    assert!(
        run(TurbulenceLevel::Off, 3, 1000)
            .iter()
            .all(|g| *g == Vec3::zeros())
    );
    let a = run(TurbulenceLevel::Light, 42, 1000);
    let b = run(TurbulenceLevel::Light, 42, 1000);
    let c = run(TurbulenceLevel::Light, 43, 1000);
    assert_eq!(a, b);
    assert_ne!(a, c);
    assert!(a.iter().any(|g| g.norm() > 0.0));
}

/// Through [`Atmosphere`]: altitude comes from the NED position and the origin's height, the
/// steady wind and perturbations are passed on, and severity scales the gusts (severe = 3 ×
/// light: W20 of 45 kt vs 15 kt drive the same normalised filter when the seed is the same).
#[test]
fn atmosphere_passes_wind_and_scales_gusts_with_severity() {
    let make = |turbulence| {
        let config = AtmosphereConfig {
            turbulence,
            wind_ned_fps: [5.0, -3.0, 0.0],
            origin_altitude_ft: 400.0,
            ..AtmosphereConfig::default()
        };
        Atmosphere::new(&config, 11).expect("valid config")
    };
    let (mut light, mut severe) = (make(TurbulenceLevel::Light), make(TurbulenceLevel::Severe));
    let position = Vec3::new(0.0, 0.0, -100.0);
    assert_eq!(light.altitude_ft(&position), 500.0);
    for _ in 0..100 {
        let a = light.sample(0.01, &position, 50.0);
        let b = severe.sample(0.01, &position, 50.0);
        assert_eq!(a.wind_ned_fps, Vec3::new(5.0, -3.0, 0.0));
        assert!((b.gust_body_fps - 3.0 * a.gust_body_fps).norm() < 1e-12);
    }
}

/// `target.gusts = "shared"`: one seed's white noise shaped at two aircraft's airspeeds (50 and
/// 40 ft/s, a slot's difference in a turn) gives gusts that agree as the air a few tens of
/// feet apart does (correlation over 0.9 per component: 0.99 measured), where two seeds' gusts are
/// unrelated (under 0.15 in magnitude). 10 000 s of moderate air at 500 ft: the estimates'
/// standard errors are about √(T/D) ≈ 0.044 for u (T_u ≈ 19 s) and less for v and w.
#[test]
fn one_stream_at_two_airspeeds_is_the_same_air() {
    let ticks = 200_000;
    let gusts = |seed: u64, airspeed_fps: f64| {
        let mut dryden = DrydenTurbulence::new(TurbulenceLevel::Moderate, seed);
        (0..ticks)
            .map(|_| dryden.step(DT_S, airspeed_fps, 500.0))
            .collect::<Vec<Vec3>>()
    };
    let correlation = |a: &[Vec3], b: &[Vec3], axis: usize| {
        let (x, y): (Vec<f64>, Vec<f64>) = a.iter().zip(b).map(|(p, q)| (p[axis], q[axis])).unzip();
        let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
        let (mx, my) = (mean(&x), mean(&y));
        let cov = x
            .iter()
            .zip(&y)
            .map(|(p, q)| (p - mx) * (q - my))
            .sum::<f64>();
        cov / (std_dev(&x) * std_dev(&y) * x.len() as f64)
    };
    let follower = gusts(7, 50.0);
    let shared = gusts(7, 40.0);
    let other = gusts(8, 40.0);
    for axis in 0..3 {
        let same = correlation(&follower, &shared, axis);
        let unrelated = correlation(&follower, &other, axis);
        assert!(same > 0.9, "axis {axis}: shared stream correlation {same}");
        assert!(
            unrelated.abs() < 0.15,
            "axis {axis}: other seed correlation {unrelated}"
        );
    }
}
