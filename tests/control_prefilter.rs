//! The command prefilters of the flight controller (Remark 10, (7.32)-(7.33)) give the
//! derivative of their output exactly: integrated by the simulation's RK4 at dt = 5 ms under a
//! smooth command, the rate each filter reports matches a central finite difference of its own
//! output. The heading reference is continuous through χ = ±180°.
//!
//! Tolerance: the central difference of a C³ signal is off by dt² x‴/6; with dt = 5 ms and the
//! filters' ω ≤ 30 rad/s driven by signals of unit amplitude at ≤ 1 rad/s, x‴ stays below ≈ 10
//! (the rate filter's fast transient from rest is skipped), so the error is < 5e-5; the bound
//! 1e-4 also absorbs RK4's O(dt⁴) error in the samples.

use wingman::control::reference::unwrap_near_rad;
use wingman::control::{IntegralPrefilter, SecondOrderFilter, SmoothIntegralPrefilter};
use wingman::frames::wrap_angle_rad;
use wingman::integrate::Rk4;

const DT_S: f64 = 0.005;

/// A smooth command: a ramp plus two sines (the shapes the guidance produces).
fn command(t: f64) -> f64 {
    0.3 * t + (0.7 * t).sin() + 0.5 * (0.23 * t + 1.0).cos()
}

/// Runs the three filters side by side for 20 s and returns (t, value, rate) per filter.
fn run() -> [Vec<(f64, f64, f64)>; 3] {
    let seed = IntegralPrefilter {
        omega_rps: 1.0,
        zeta: 0.9,
    };
    let smooth = SmoothIntegralPrefilter {
        omega_rps: 1.5,
        zeta: 0.9,
        follows_ramps: true,
    };
    let rate = SecondOrderFilter {
        omega_rps: 30.0,
        zeta: 0.8,
    };
    let c0 = command(0.0);
    let mut x = [
        IntegralPrefilter::initial_state(c0).to_vec(),
        SmoothIntegralPrefilter::initial_state(c0).to_vec(),
        SecondOrderFilter::initial_state(c0).to_vec(),
    ]
    .concat();
    let mut rk = Rk4::new(x.len());
    let mut out: [Vec<(f64, f64, f64)>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    let mut scratch = vec![0.0; x.len()];
    for tick in 0..4000 {
        let t = tick as f64 * DT_S;
        let u = command(t);
        let a = seed.derivative(&x[0..2], u, &mut scratch[0..2]);
        let b = smooth.derivative(&x[2..5], u, &mut scratch[2..5]);
        let c = rate.derivative(&x[5..7], u, &mut scratch[5..7]);
        out[0].push((t, a.value, a.rate));
        out[1].push((t, b.value, b.rate));
        out[2].push((t, c.value, c.rate));
        rk.step(t, DT_S, &mut x, |t, x, dx| {
            let u = command(t);
            seed.derivative(&x[0..2], u, &mut dx[0..2]);
            smooth.derivative(&x[2..5], u, &mut dx[2..5]);
            rate.derivative(&x[5..7], u, &mut dx[5..7]);
        });
    }
    out
}

#[test]
fn reported_rate_matches_finite_difference_of_output() {
    let names = ["(7.33)", "smooth (7.33)", "rate command filter"];
    for (samples, name) in run().iter().zip(names) {
        let mut worst: f64 = 0.0;
        for w in samples.windows(3).skip(200) {
            let fd = (w[2].1 - w[0].1) / (2.0 * DT_S);
            worst = worst.max((fd - w[1].2).abs());
        }
        println!("{name}: max |rate - central difference| = {worst:.2e}");
        assert!(worst < 1e-4, "{name}: {worst}");
    }
}

/// Type-2 behaviour: on a ramp x_c = 0.3 t both (7.33) forms end with no lag (< 1e-4 after
/// 20 s: their error transfer s²/… vanishes for ramps), while the plain second-order filter
/// at the same ω and ζ lags by 2ζ/ω × 0.3 (its steady ramp error, checked to 1e-4).
#[test]
fn integral_prefilters_follow_ramps_without_lag() {
    let (omega, zeta, slope) = (1.5, 0.9, 0.3);
    let seed = IntegralPrefilter {
        omega_rps: omega,
        zeta,
    };
    let smooth = SmoothIntegralPrefilter {
        omega_rps: omega,
        zeta,
        follows_ramps: true,
    };
    let plain = SecondOrderFilter {
        omega_rps: omega,
        zeta,
    };
    let mut x = vec![0.0; 7];
    let mut rk = Rk4::new(7);
    let ticks = 8000;
    for tick in 0..ticks {
        rk.step(tick as f64 * DT_S, DT_S, &mut x, |t, x, dx| {
            seed.derivative(&x[0..2], slope * t, &mut dx[0..2]);
            smooth.derivative(&x[2..5], slope * t, &mut dx[2..5]);
            plain.derivative(&x[5..7], slope * t, &mut dx[5..7]);
        });
    }
    let command = slope * ticks as f64 * DT_S;
    assert!(
        (x[1] - command).abs() < 1e-4,
        "(7.33) lags by {}",
        command - x[1]
    );
    assert!(
        (x[3] - command).abs() < 1e-4,
        "smooth lags by {}",
        command - x[3]
    );
    let plain_lag = command - x[5];
    assert!(
        (plain_lag - 2.0 * zeta / omega * slope).abs() < 1e-4,
        "{plain_lag}"
    );
}

/// A course circling through south, fed to the heading prefilter unwrapped against its own
/// state (as the autopilot does), gives a continuous ψ_m whose rate stays at the course rate:
/// no 2π jump and no turn back.
#[test]
fn heading_reference_is_continuous_through_south() {
    let filter = SmoothIntegralPrefilter {
        omega_rps: 1.5,
        zeta: 0.9,
        follows_ramps: true,
    };
    let course_rate = 0.2;
    let mut x = SmoothIntegralPrefilter::initial_state(0.0).to_vec();
    let mut rk = Rk4::new(3);
    let mut scratch = [0.0; 3];
    let mut previous = x[1];
    for tick in 0..20_000 {
        let t = tick as f64 * DT_S;
        rk.step(t, DT_S, &mut x, |t, x, dx| {
            let course = wrap_angle_rad(course_rate * t);
            filter.derivative(x, unwrap_near_rad(course, x[1]), dx);
        });
        let out = filter.derivative(
            &x,
            unwrap_near_rad(wrap_angle_rad(course_rate * t), x[1]),
            &mut scratch,
        );
        assert!((x[1] - previous).abs() < 0.01, "jump at {t} s");
        assert!(
            out.rate > -0.01 && out.rate < 0.3,
            "rate {} at {t} s",
            out.rate
        );
        previous = x[1];
    }
    // 100 s at 0.2 rad/s: 20 rad, more than three turns, tracked without lag.
    assert!((x[1] - 20.0).abs() < 0.01, "ψ_m = {}", x[1]);
}
