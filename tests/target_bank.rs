//! The target's bank read from its wing line (`estimator.target_bank = "measured"`;
//! docs/equations.md, The target's bank from its wing line). formation_realistic.toml's
//! stream 5 (an aircraft target on seeded random manoeuvres, consumer navigation): with the
//! filter inferring the target's acceleration from the frames alone (`inferred`, q_j = 1e-3,
//! the scenario before the bank) b̂ reads 9.03 ft for the 8 ft target, 6.5 σ_b off; with the
//! bank fused (the scenario as shipped) 8.15 ft, the truth inside ±3σ_b (measured on the
//! energy loop the scenario flies now; 9.02 and 8.17 ft on the Chapter 7 loop it flew before.
//! Over run.seed 1-20: within 5% and inside ±3σ_b on 20 against 15 on that loop, and on 20
//! with the bank on the energy loop; docs/findings.md).

use crate::common::run;
use wingman::output::summary::{RunStatus, Summary};

const TRUE_SIZE_FT: f64 = 8.0;

fn realistic(overrides: &[&str]) -> Summary {
    let mut all = vec!["output.frames_every=0", "run.seed=5"];
    all.extend_from_slice(overrides);
    let summary = run("formation_realistic", &all).summary;
    assert_eq!(summary.status, RunStatus::Completed);
    assert_eq!(summary.lost_frames, 0);
    summary
}

/// b̂ and σ_b at the end, ft.
fn size(summary: &Summary) -> (f64, f64) {
    let sigma_ft = summary.b_sigma_final_ft.expect("the Kalman filter's σ_b");
    (summary.b_hat_final_ft, sigma_ft)
}

#[test]
fn the_bank_brings_the_size_within_its_uncertainty() {
    let measured = realistic(&[]);
    let fused = measured.track_check.bank_fused_frames;
    assert!(
        fused * 10 > measured.frames * 9,
        "{fused} of {} frames' banks fused",
        measured.frames
    );
    let (b_ft, sigma_ft) = size(&measured);
    let off_ft = (b_ft - TRUE_SIZE_FT).abs();
    assert!(
        off_ft < 0.05 * TRUE_SIZE_FT && off_ft < 3.0 * sigma_ft,
        "b̂ {b_ft} ± {sigma_ft}"
    );
    let inferred = realistic(&[
        "estimator.target_bank=\"inferred\"",
        "estimator.jerk_psd=0.001",
    ]);
    assert_eq!(inferred.track_check.bank_fused_frames, 0);
    let (b_ft, sigma_ft) = size(&inferred);
    let off_ft = (b_ft - TRUE_SIZE_FT).abs();
    assert!(
        off_ft > 0.08 * TRUE_SIZE_FT && off_ft > 3.0 * sigma_ft,
        "without the bank b̂ {b_ft} ± {sigma_ft}"
    );
}
