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
