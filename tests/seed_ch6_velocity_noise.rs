//! The seed's Chapter 6 velocity-guidance run with the state estimator (6.10)-(6.17) on
//! measurements with white noise at SNR 25 dB (Figures 6.4-6.6), and without noise (Figures
//! 6.1-6.3). Shown: the loop stays bounded over 140 s, b̂ ends within 10% of 8 ft, R stays
//! within 3 ft RMS of R_c over the last 20 s; the sensor realises the stated SNR; the same run
//! without noise reproduces the Chapter 4 run up to the estimator's documented effect; pixel
//! noise propagated through (6.1)-(6.3) is a small perturbation of the noise-free run.

use crate::common;

use wingman::output::summary::RunStatus;

/// Bounded, b̂ within 10%, position within 3 ft RMS per axis over the last 20 s, and the SNR
/// realised over the run's 140 001 samples within 0.1 dB of 25 (its standard error is
/// 0.01 dB).
#[test]
fn noisy_run_stays_bounded_and_on_the_command() {
    let report = common::run("seed_ch6_velocity_noise", &[]);
    let s = &report.summary;
    println!(
        "b̂ = {:.3} ft, RMS last 20 s {:.3?} ft, SNR {:?} dB, wall {:.3} s, notes {:?}",
        s.b_hat_final_ft, s.rms_error_last20s_ft, s.noise_snr_db, s.wall_s, s.notes
    );
    // Measured: b̂ = 8.34 ft; RMS 0.83, 0.24, 0.05 ft.
    common::assert_noisy_run_bounded(&report);
    let snr = s.noise_snr_db.expect("noisy run");
    assert!((snr - 25.0).abs() < 0.1, "SNR {snr} dB");
    assert!(
        s.notes.iter().any(|n| n.contains("L_v = 23.57")),
        "{:?}",
        s.notes
    );
}

/// The same run without noise against the Chapter 4 run (Figures 6.1-6.3 against 4.3-4.5).
/// With the scenario's Q_v = I the adaptive laws (6.16) weigh the error 2k = 7 times less
/// than (4.5) do (that keeps the noise out of b̂): the runs differ by the "slight
/// deterioration" the seed reports: the largest R differences are 6.8%, 10.0% and 3.1% of the
/// panels' spans (bounded at 12% here), b̂ differs by up to 1.3 ft mid-run and still ends
/// within 5% of 8 ft (measured 8.00). With Q_v = 2k I and the
/// Chapter 4 excitation, the estimator run reproduces the Chapter 4 run within the figures'
/// resolution: every R panel within 2% of its span (measured 1.4%).
#[test]
fn noise_free_run_matches_chapter_4() {
    let chapter4 = common::run("seed_ch4_formation", &[]);
    let noise_free = common::run("seed_ch6_velocity_noise", &["sensor.mode=perfect"]);
    let b = noise_free.summary.b_hat_final_ft;
    let r_span = common::largest_difference_of_span(&chapter4, &noise_free, |s| s.relative_ned_ft);
    println!("noise-free: b̂ = {b:.3} ft; largest R difference / span {r_span:.3?}");
    assert!((b - 8.0).abs() < 0.05 * 8.0, "b̂ = {b}");
    assert!(r_span.iter().all(|d| *d < 0.12), "{r_span:?}");

    let matched = common::run(
        "seed_ch4_formation",
        &[
            "guidance.estimator=true",
            "guidance.estimator_gain_mode=covariance",
            "guidance.estimator_process_psd=0.01",
            "guidance.estimator_lyapunov_weight=7.0",
        ],
    );
    let r_span = common::largest_difference_of_span(&chapter4, &matched, |s| s.relative_ned_ft);
    println!("Q_v = 2k I: largest R difference / span {r_span:.4?}");
    assert!(r_span.iter().all(|d| *d < 0.02), "{r_span:?}");
}

/// Noise on the pixels (6.1) instead of r: 0.5 px on (yI, zI, bI) at the default 60° camera
/// (l = 554 px) gives r about 38 dB SNR. The heading-frame command keeps the target in front
/// of the camera (with the inertial [32, 8, 0] ft it passes behind the image plane when both
/// fly west and the measurement is lost). The run stays bounded and within 0.25 ft of b̂ and
/// 0.5 ft RMS position of its noise-free twin (measured 0.03 ft and 0.02 ft).
#[test]
fn pixel_noise_propagates_through_the_sensing_transform() {
    let heading = ["guidance.command_frame=heading"];
    let clean = common::run(
        "seed_ch6_velocity_noise",
        &[heading[0], "sensor.mode=perfect"],
    );
    let noisy = common::run(
        "seed_ch6_velocity_noise",
        &[
            heading[0],
            "sensor.noise_on=pixels",
            "sensor.pixel_noise_px=[0.5, 0.5, 0.5]",
        ],
    );
    let snr = noisy.summary.noise_snr_db.expect("noisy run");
    let (b_clean, b_noisy) = (clean.summary.b_hat_final_ft, noisy.summary.b_hat_final_ft);
    let (p_clean, p_noisy) = (
        clean.summary.rms_error_last20s_ft,
        noisy.summary.rms_error_last20s_ft,
    );
    println!(
        "pixels: SNR {snr:.1} dB; b̂ {b_noisy:.3} vs {b_clean:.3}; RMS {p_noisy:.3?} vs {p_clean:.3?}"
    );
    assert_eq!(noisy.summary.status, RunStatus::Completed);
    assert!(
        noisy.logged.iter().all(|s| s.r_measured.is_some()),
        "lost measurements"
    );
    assert!((30.0..45.0).contains(&snr), "SNR {snr} dB");
    assert!((b_noisy - b_clean).abs() < 0.25);
    for axis in 0..3 {
        assert!((p_noisy[axis] - p_clean[axis]).abs() < 0.5, "axis {axis}");
    }
}
