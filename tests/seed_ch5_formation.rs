//! The seed's Chapter 5 formation run (Section 5.7, Figures 5.1-5.4) through the simulation:
//! acceleration guidance (5.2)-(5.41) with a follower that realises a_F exactly. Shown: b̂
//! converges to the true 8 ft, a_F follows a_T on the axes the excitation does not act on
//! (Fig 5.2), the relative position settles on R_c (Fig 5.3), ‖d̂‖ grows and settles (Fig 5.4),
//! and the intelligent excitation (5.27) fades to k3 once the target stops manoeuvring.

use crate::common;

use wingman::frames::Vec3;
use wingman::guidance::FollowerCommand;

#[test]
fn formation_reproduces_figures_5_2_to_5_4() {
    let report = common::run("seed_ch5_formation", &[]);
    let s = &report.summary;
    assert_eq!(s.steps, 140_000);
    println!(
        "b̂ = {:.3} ft, ‖d̂‖ = {:.3} ft/s, RMS last 20 s {:.3?} ft, wall {:.3} s",
        s.b_hat_final_ft, s.d_hat_norm_final, s.rms_error_last20s_ft, s.wall_s
    );
    // Fig 5.4: b̂ ends within the 5% of 8 ft (measured 8.17 ft).
    assert!(
        (s.b_hat_final_ft - 8.0).abs() < 0.05 * 8.0,
        "b̂ = {}",
        s.b_hat_final_ft
    );
    // Fig 5.4: ‖d̂‖ settles near 5.8 ft/s (measured 5.81): between "barely adapted" and half
    // its 20 ft/s bound, and no longer moving once a_T = 0 (t > 120 s): under 1% change.
    let d_at = |t: f64| {
        report
            .logged
            .iter()
            .find(|s| s.t_s >= t - 1e-9)
            .map_or(f64::NAN, |s| s.target_motion.vector().norm())
    };
    assert!((3.0..=10.0).contains(&s.d_hat_norm_final));
    assert!(s.d_hat_norm_final - d_at(120.0) < 0.01 * s.d_hat_norm_final);
    // Fig 5.3: R on R_c over the last 20 s, below the 1.5 ft RMS per axis (measured
    // 0.57, 0.14, 0.01 ft).
    for (axis, rms) in s.rms_error_last20s_ft.iter().enumerate() {
        assert!(*rms < 1.5, "axis {axis}: RMS {rms} ft");
    }
    // Fig 5.2: on y and z, which the excitation (along x) does not act on, RMS(a_F - a_T) over
    // [60, 110] s stays below a quarter of RMS(a_T) (measured 0.014 and 0.049). On x the
    // commanded oscillation k ω² ≈ 2.2 ft/s² is a_F's job, not an error (measured 0.68).
    let ratios = common::accel_tracking_ratios(&report, 60.0, 110.0);
    println!("RMS(a_F - a_T)/RMS(a_T) over [60, 110] s: {ratios:.3?}");
    for axis in [1, 2] {
        assert!(ratios[axis] < 0.25, "axis {axis}: ratio {}", ratios[axis]);
    }
}

/// The follower starts at V_F(0) = [50, 0, 0] ft/s and integrates the commanded a_F: the
/// logged V_F moves by the logged a_F (trapezoid over the 10 ms rows, to 1% of the change
/// over the first 10 s, where a_F is smooth); the excitation amplitude starts at k1 = 0.5 ft
/// and ends at k3 = 0.0002 ft, since the target flies straight after 120 s and y_a → 0.
#[test]
fn follower_integrates_the_commanded_acceleration() {
    let report = common::run("seed_ch5_formation", &[]);
    let first = &report.logged[0];
    assert_eq!(first.follower_velocity_ned_fps, Vec3::new(50.0, 0.0, 0.0));
    assert!(matches!(
        first.guidance.command,
        FollowerCommand::Acceleration(_)
    ));
    let rows: Vec<_> = report.logged.iter().filter(|s| s.t_s <= 10.0).collect();
    let mut integrated = rows[0].follower_velocity_ned_fps;
    for w in rows.windows(2) {
        let (a0, a1) = (
            w[0].follower_accel_ned_fps2().unwrap_or(Vec3::zeros()),
            w[1].follower_accel_ned_fps2().unwrap_or(Vec3::zeros()),
        );
        integrated += (a0 + a1) * (0.5 * (w[1].t_s - w[0].t_s));
    }
    let last = rows[rows.len() - 1];
    let change = (last.follower_velocity_ned_fps - rows[0].follower_velocity_ned_fps).norm();
    let error = (integrated - last.follower_velocity_ned_fps).norm();
    assert!(error < 0.01 * change, "error {error} ft/s of {change} ft/s");
    assert_eq!(first.excitation_amplitude, 0.5);
    let end = report
        .logged
        .last()
        .map_or(f64::NAN, |s| s.excitation_amplitude);
    // k3 plus k2 ∫‖y_a‖² over the last period, which is below 1e-6 (measured 3e-8).
    assert!((0.0002..0.0002 + 1e-6).contains(&end), "amplitude {end}");
}
