//! The seed's Chapter 4 formation run (Figures 4.3-4.5) is reproduced in numbers: b̂ converges
//! to the true 8 ft, the relative position settles on R_c, and after the first 20 s the
//! follower's velocity follows the target's.

use crate::common;

#[test]
fn formation_reproduces_figures_4_3_to_4_5() {
    let report = common::run("seed_ch4_formation", &[]);
    let s = &report.summary;
    assert_eq!(s.steps, 140_000);
    // Fig 4.4: b̂ settles at the true size; the bound is 5%.
    assert!(
        (s.b_hat_final_ft - 8.0).abs() < 0.05 * 8.0,
        "b_hat = {}",
        s.b_hat_final_ft
    );
    // Fig 4.3: relative position on the command over the last 20 s, below 1 ft RMS per axis
    // (the x axis carries what is left of the excitation).
    for (axis, rms) in s.rms_error_last20s_ft.iter().enumerate() {
        assert!(*rms < 1.0, "axis {axis}: RMS {rms} ft");
    }
    // Fig 4.5: after 20 s V_F follows V_T. On y and z, which the excitation does not act on,
    // the RMS difference stays below 2% of the target's RMS speed (measured 1%: the
    // manoeuvres' accelerations leave a lag of about 0.5 ft/s). On x the excitation adds
    // about b ω a ≈ 8 ft/s of commanded oscillation; averaged over each excitation period
    // the difference stays below 5% of that speed (measured 2%).
    let after: Vec<_> = report.logged.iter().filter(|s| s.t_s >= 20.0).collect();
    let speed = common::rms(after.iter().map(|s| s.target.velocity_ned_fps.norm()));
    let difference =
        |s: &&wingman::sim::Snapshot| s.follower_velocity_ned_fps - s.target.velocity_ned_fps;
    for axis in [1, 2] {
        let rms = common::rms(after.iter().map(|s| difference(s)[axis]));
        assert!(
            rms < 0.02 * speed,
            "axis {axis}: RMS {rms} ft/s vs target {speed} ft/s"
        );
    }
    let rows_per_period = (3.0 / 0.01) as usize;
    let period_means = after
        .chunks_exact(rows_per_period)
        .map(|w| w.iter().map(|s| difference(s)[0]).sum::<f64>() / w.len() as f64);
    let rms_x = common::rms(period_means);
    assert!(
        rms_x < 0.05 * speed,
        "x: period-mean RMS {rms_x} ft/s vs {speed} ft/s"
    );
}

/// The b̂ estimate never leaves its projection bounds and starts at the seed's 4 ft.
#[test]
fn estimate_respects_projection_bounds() {
    let report = common::run("seed_ch4_formation", &["run.duration_s=30"]);
    assert_eq!(report.logged[0].b_hat_ft, 4.0);
    for s in &report.logged {
        assert!(
            (0.9..=30.1).contains(&s.b_hat_ft),
            "b_hat {} at {}",
            s.b_hat_ft,
            s.t_s
        );
        assert!(s.target_motion.vector().norm() <= (20f64.powi(2) + 1.0).sqrt() + 1e-9);
    }
}
