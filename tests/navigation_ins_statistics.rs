//! The INS/GPS error model (`navigation.mode = "ins_gps"`) has the statistics its keys state:
//! the position error's σ over a long run is within 20% of the σ the model states (and, with
//! the consumer-grade defaults, of `gps_position_sigma_ft`); the heading drifts at the gyro
//! bias, b_g,z τ_h (1 - e^(-t/τ_h)), and its spread over runs grows with the bias's σ; the same
//! seed gives the same errors, another seed others.

use wingman::frames::EulerAngles;
use wingman::navigation::InsGps;
use wingman::scenario::NavigationSection;

const LEVEL: EulerAngles = EulerAngles {
    phi_rad: 0.0,
    theta_rad: 0.0,
    psi_rad: 0.0,
};

/// The position error's σ per axis about its mean over `duration_s`, stepping `dt_s`.
fn position_sigma_ft(
    section: &NavigationSection,
    seed: u64,
    duration_s: f64,
    dt_s: f64,
) -> [f64; 3] {
    let mut ins = InsGps::new(section, seed, &LEVEL);
    let steps = (duration_s / dt_s) as usize;
    let (mut sum, mut sum_sq) = ([0.0; 3], [0.0; 3]);
    for _ in 0..steps {
        ins.advance(dt_s, &LEVEL);
        let e = ins.errors().position_ned_ft;
        for i in 0..3 {
            sum[i] += e[i];
            sum_sq[i] += e[i] * e[i];
        }
    }
    let n = steps as f64;
    [0, 1, 2].map(|i| (sum_sq[i] / n - (sum[i] / n).powi(2)).sqrt())
}

/// Consumer-grade defaults, no accelerometer bias (it moves the mean only), 1000 correlation
/// times of the GPS's slow error: each axis' σ within 20% of the model's, the horizontal
/// within 20% of `gps_position_sigma_ft`.
#[test]
fn the_position_error_has_the_stated_sigma() {
    let section = NavigationSection {
        accel_bias_milli_g: 0.0,
        ..NavigationSection::default()
    };
    let stated = InsGps::new(&section, 1, &LEVEL).position_sigma_ft();
    let measured = position_sigma_ft(&section, 1, 1000.0 * section.gps_correlation_time_s, 0.1);
    eprintln!("position σ: measured {measured:.2?} ft, stated {stated:.2?} ft");
    assert_within_a_fifth(&measured, &stated.into());
    for sigma in &measured[..2] {
        assert!(
            (sigma / section.gps_position_sigma_ft - 1.0).abs() < 0.2,
            "{sigma}"
        );
    }
}

/// With a fast GPS error and slow fixes the white part and the lag matter: still within 20%.
#[test]
fn the_stated_sigma_holds_for_slow_fixes_and_a_long_lag() {
    let section = NavigationSection {
        accel_bias_milli_g: 0.0,
        gps_position_sigma_ft: 3.0,
        gps_correlation_time_s: 5.0,
        gps_noise_sigma_ft: 4.0,
        gps_rate_hz: 1.0,
        position_time_constant_s: 2.0,
        velocity_sigma_fps: 1.0,
        ..NavigationSection::default()
    };
    let stated = InsGps::new(&section, 2, &LEVEL).position_sigma_ft();
    let measured = position_sigma_ft(&section, 2, 20_000.0, 0.05);
    eprintln!("position σ: measured {measured:.2?} ft, stated {stated:.2?} ft");
    assert_within_a_fifth(&measured, &stated.into());
}

/// Only the gyro biases acting (no random walk, no aiding residual, no accelerometer bias):
/// each attitude error sits where the bias's drift and the aiding balance, b_g τ (the heading
/// at b_g,z τ_h, roll and pitch at b_g τ_a), and stays there over 1000 s.
#[test]
fn the_attitude_error_is_the_gyro_bias_bounded_by_the_aiding() {
    let section = NavigationSection {
        gyro_bias_deg_per_h: 10.0,
        angle_random_walk_deg_per_sqrt_h: 0.0,
        attitude_sigma_deg: 0.0,
        heading_sigma_deg: 0.0,
        accel_bias_milli_g: 0.0,
        ..NavigationSection::default()
    };
    let mut ins = InsGps::new(&section, 5, &LEVEL);
    let bias = ins.gyro_bias_rps();
    assert!(bias.iter().all(|b| *b != 0.0));
    let tau = [
        section.attitude_time_constant_s,
        section.attitude_time_constant_s,
        section.heading_time_constant_s,
    ];
    for _ in 0..10_000 {
        ins.advance(0.1, &LEVEL);
    }
    let e = ins.errors().attitude_rad;
    for i in 0..3 {
        let stated = bias[i] * tau[i];
        assert!(
            (e[i] - stated).abs() < 1e-9 * stated.abs(),
            "axis {i}: {} vs {stated}",
            e[i]
        );
    }
}

/// Over 400 runs (each its own bias draw), the heading error's spread grows with the gyro
/// bias's σ as σ_b τ_h: within 20% at 1, 10 and 20 deg/h, and none without a bias.
#[test]
fn the_heading_error_grows_with_the_gyro_bias() {
    let spread_rad = |bias_deg_per_h: f64| {
        let section = NavigationSection {
            gyro_bias_deg_per_h: bias_deg_per_h,
            angle_random_walk_deg_per_sqrt_h: 0.0,
            heading_sigma_deg: 0.0,
            heading_time_constant_s: 1000.0,
            ..NavigationSection::default()
        };
        let sum_sq: f64 = (0..400u64)
            .map(|seed| {
                let mut ins = InsGps::new(&section, seed, &LEVEL);
                for _ in 0..100 {
                    ins.advance(1.0, &LEVEL);
                }
                ins.errors().attitude_rad.z.powi(2)
            })
            .sum();
        (sum_sq / 400.0).sqrt()
    };
    let stated = |bias_deg_per_h: f64| (bias_deg_per_h / 3600.0f64).to_radians() * 1000.0;
    for bias in [1.0, 10.0, 20.0] {
        let measured = spread_rad(bias);
        assert!(
            (measured / stated(bias) - 1.0).abs() < 0.2,
            "{bias} deg/h: {measured} rad against {}",
            stated(bias)
        );
    }
    assert_eq!(spread_rad(0.0), 0.0);
}

/// Same seed, same errors; another seed, other errors.
#[test]
fn the_errors_are_reproducible_per_seed() {
    let section = NavigationSection::default();
    let run = |seed: u64| {
        let mut ins = InsGps::new(&section, seed, &LEVEL);
        (0..1000)
            .map(|_| {
                ins.advance(0.01, &LEVEL);
                ins.errors()
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(run(3), run(3));
    assert_ne!(run(3), run(4));
}

/// Each axis's measured σ within 20% of the stated one.
fn assert_within_a_fifth(measured: &[f64; 3], stated: &[f64; 3]) {
    for i in 0..3 {
        assert!(
            (measured[i] / stated[i] - 1.0).abs() < 0.2,
            "axis {i}: measured {:.2} ft, stated {:.2} ft",
            measured[i],
            stated[i]
        );
    }
}
