//! A run writes the outputs of docs/outputs.md: the resolved scenario (re-runnable, giving identical
//! telemetry), telemetry.csv, summary.json with its keys, and plots; a diverging run stops
//! with exit code 1 and keeps the telemetry written so far.

use crate::common::wingman_cli as wingman;

/// Runs the resolved `scenario.toml` of the run in `first` into `second` and checks that it
/// writes `telemetry` again, byte for byte.
fn assert_rerun_is_identical(first: &std::path::Path, second: &std::path::Path, telemetry: &str) {
    let (code, stderr) = wingman(&[
        "run",
        first.join("scenario.toml").to_str().expect("utf-8"),
        "--out",
        second.to_str().expect("utf-8"),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let again = std::fs::read_to_string(second.join("telemetry.csv")).expect("telemetry");
    assert!(
        again == telemetry,
        "telemetry differs between identical runs"
    );
}

#[test]
fn outputs_are_complete_and_rerunnable() {
    let dir = tempfile::tempdir().expect("temp dir");
    let first = dir.path().join("first");
    let first_s = first.to_str().expect("utf-8 path");
    let (code, stderr) = wingman(&[
        "run",
        "scenarios/seed_ch4_formation.toml",
        "--out",
        first_s,
        "--set",
        "run.duration_s=25",
        "--quiet",
    ]);
    assert_eq!(code, 0, "{stderr}");
    for file in [
        "scenario.toml",
        "telemetry.csv",
        "summary.json",
        "plots/relative_position.png",
        "plots/parameter_estimates.png",
        "plots/velocity.png",
    ] {
        let path = first.join(file);
        assert!(path.is_file(), "{file} missing");
        assert!(
            std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0) > 0,
            "{file} empty"
        );
    }
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(first.join("summary.json")).expect("summary"),
    )
    .expect("summary is JSON");
    for key in [
        "scenario",
        "duration_s",
        "steps",
        "frames",
        "wall_s",
        "b_true_ft",
        "b_hat_final_ft",
        "intercept_time_s",
        "min_range_ft",
        "rms_error_last20s_ft",
        "lost_frames",
    ] {
        assert!(summary.get(key).is_some(), "summary lacks {key}");
    }
    assert_eq!(summary["steps"], 25_000);
    assert_eq!(
        summary["rms_error_last20s_ft"].as_array().map(Vec::len),
        Some(3)
    );

    let telemetry = std::fs::read_to_string(first.join("telemetry.csv")).expect("telemetry");
    let header = telemetry.lines().next().expect("header");
    for column in [
        "t_s",
        "rel_n_ft",
        "b_hat_ft",
        "cmd_n_ft",
        "phi_rad",
        "tgt_psi_rad",
    ] {
        assert!(header.split(',').any(|c| c == column), "no column {column}");
    }
    // 25 s logged every 10 ms, plus the initial row.
    assert_eq!(telemetry.lines().count(), 1 + 2501);

    // The resolved scenario runs as is and gives identical telemetry (determinism).
    assert_rerun_is_identical(&first, &dir.path().join("second"), &telemetry);
}

#[test]
fn diverging_run_keeps_telemetry() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("run");
    // k = 1000 with dt = 10 ms puts -k dt far outside RK4's stability region.
    let (code, stderr) = wingman(&[
        "run",
        "scenarios/seed_ch4_formation.toml",
        "--out",
        out.to_str().expect("utf-8"),
        "--set",
        "guidance.k=1000",
        "--set",
        "run.dt_s=0.01",
        "--set",
        "run.log_every=1",
        "--quiet",
    ]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("diverged"), "{stderr}");
    let telemetry = std::fs::read_to_string(out.join("telemetry.csv")).expect("telemetry kept");
    assert!(telemetry.lines().count() > 2, "no rows kept");
    let summary = std::fs::read_to_string(out.join("summary.json")).expect("summary kept");
    assert!(summary.contains("\"diverged\""), "{summary}");
}

/// An acceleration-law run on the noisy sensor writes its extra figures (Figs 5.1, 6.7, the
/// measurement), its law's telemetry columns and the summary's noise and notes keys; its
/// resolved scenario re-runs to identical telemetry (the noise comes from `[run] seed`).
#[test]
fn noisy_acceleration_run_outputs_are_complete_and_deterministic() {
    let dir = tempfile::tempdir().expect("temp dir");
    let first = dir.path().join("first");
    let (code, stderr) = wingman(&[
        "run",
        "scenarios/seed_ch6_acceleration_noise.toml",
        "--out",
        first.to_str().expect("utf-8"),
        "--set",
        "run.duration_s=5",
        "--quiet",
    ]);
    assert_eq!(code, 0, "{stderr}");
    for file in [
        "plots/relative_position.png",
        "plots/parameter_estimates.png",
        "plots/velocity.png",
        "plots/acceleration.png",
        "plots/target_acceleration.png",
        "plots/measurement.png",
    ] {
        assert!(first.join(file).is_file(), "{file} missing");
    }
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(first.join("summary.json")).expect("summary"),
    )
    .expect("summary is JSON");
    assert_eq!(summary["law"], "acceleration");
    assert!(summary["noise_snr_db"].as_f64().is_some());
    assert!(summary["notes"].as_array().is_some());
    let telemetry = std::fs::read_to_string(first.join("telemetry.csv")).expect("telemetry");
    let header = telemetry.lines().next().expect("header");
    for column in ["fol_an_fps2", "d_hat_x_fps", "y_a_x", "b_hat_rate_fps"] {
        assert!(header.split(',').any(|c| c == column), "no column {column}");
    }
    assert_rerun_is_identical(&first, &dir.path().join("second"), &telemetry);
}
