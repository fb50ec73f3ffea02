//! Helpers shared by the behaviour tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use wingman::output::{RunReport, run_to_directory};
use wingman::scenario::Scenario;

/// The repository root (where `scenarios/` lives).
pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Loads `scenarios/<name>.toml` with overrides (plots off unless asked for).
pub fn load(name: &str, overrides: &[&str]) -> Scenario {
    let mut all: Vec<String> = vec!["output.plots=false".to_string()];
    all.extend(overrides.iter().map(|s| s.to_string()));
    let path = repo_root().join("scenarios").join(format!("{name}.toml"));
    Scenario::load(&path, &all).unwrap_or_else(|e| panic!("{e}"))
}

/// Runs a scenario into `dir` and returns the report.
pub fn run_in(scenario: &Scenario, name: &str, dir: &Path) -> RunReport {
    run_to_directory(scenario, name, dir, |_| {}).unwrap_or_else(|e| panic!("{e}"))
}

/// Runs `scenarios/<name>.toml` into a temporary directory.
pub fn run(name: &str, overrides: &[&str]) -> RunReport {
    let dir = tempfile::tempdir().expect("temp dir");
    run_in(&load(name, overrides), name, dir.path())
}

/// RMS of a sequence.
pub fn rms(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v * v, n + 1));
    (sum / n.max(1) as f64).sqrt()
}

/// RMS of R - R_c per axis over the logged rows with t ≥ `from_s`, ft.
pub fn position_rms_since(report: &RunReport, from_s: f64) -> [f64; 3] {
    let rows: Vec<_> = report.logged.iter().filter(|s| s.t_s >= from_s).collect();
    [0, 1, 2].map(|i| {
        rms(rows
            .iter()
            .map(|s| s.relative_ned_ft[i] - s.command_ned_ft[i]))
    })
}

/// RMS(a_F - a_T) / RMS(a_T) on each axis over t in [from_s, to_s] (acceleration law runs).
pub fn accel_tracking_ratios(report: &RunReport, from_s: f64, to_s: f64) -> [f64; 3] {
    let rows: Vec<_> = report
        .logged
        .iter()
        .filter(|s| (from_s..=to_s).contains(&s.t_s))
        .collect();
    [0, 1, 2].map(|i| {
        let difference = rms(rows.iter().map(|s| {
            s.follower_accel_ned_fps2().map_or(f64::NAN, |a| a[i]) - s.target.accel_ned_fps2[i]
        }));
        difference / rms(rows.iter().map(|s| s.target.accel_ned_fps2[i]))
    })
}

/// The largest difference between two runs' logged values of `f`, relative to the span of
/// `f` over both runs, per axis (rows matched by index; both runs log at the same times).
pub fn largest_difference_of_span(
    a: &RunReport,
    b: &RunReport,
    f: impl Fn(&wingman::sim::Snapshot) -> wingman::frames::Vec3,
) -> [f64; 3] {
    [0, 1, 2].map(|i| {
        let values = a.logged.iter().chain(&b.logged).map(|s| f(s)[i]);
        let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        let largest = a
            .logged
            .iter()
            .zip(&b.logged)
            .map(|(x, y)| (f(x)[i] - f(y)[i]).abs())
            .fold(0.0, f64::max);
        largest / (hi - lo).max(1e-9)
    })
}
