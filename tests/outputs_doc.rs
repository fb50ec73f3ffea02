//! docs/outputs.md's tables are the ones the code declares (regenerate them with
//! `cargo run --example gen_outputs_doc`), and the code's tables are what a run writes: every
//! telemetry column of a run is declared, and the summary's keys are `SUMMARY_KEYS`, in order.

use std::path::Path;
use wingman::output::columns::COLUMNS;
use wingman::output::outputs_doc::with_tables;
use wingman::output::run_to_directory;
use wingman::output::summary::SUMMARY_KEYS;
use wingman::scenario::Scenario;

#[test]
fn outputs_doc_tables_are_current() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/outputs.md");
    let doc = std::fs::read_to_string(&path).expect("docs/outputs.md");
    let generated = with_tables(&doc).expect("the generated block's marker lines");
    assert!(
        generated == doc,
        "docs/outputs.md is stale: run `cargo run --example gen_outputs_doc`"
    );
}

#[test]
fn a_run_writes_the_declared_columns_and_keys() {
    let dir = tempfile::tempdir().expect("temp dir");
    let toml = "[run]\nduration_s = 0.1\n[output]\nplots = false\n";
    let scenario = Scenario::from_toml_str(toml, Path::new("s.toml"), &[]).expect("valid");
    run_to_directory(&scenario, "s", dir.path(), |_| {}).expect("run");
    let telemetry = std::fs::read_to_string(dir.path().join("telemetry.csv")).expect("csv");
    let header = telemetry.lines().next().expect("header");
    let declared: Vec<&str> = COLUMNS.iter().flat_map(|c| c.names()).copied().collect();
    for name in header.split(',') {
        assert!(declared.contains(&name), "column {name} is not declared");
    }
    let summary = std::fs::read_to_string(dir.path().join("summary.json")).expect("summary");
    // The top-level keys: the lines indented by exactly two spaces.
    let written: Vec<&str> = summary
        .lines()
        .filter_map(|l| l.strip_prefix("  \""))
        .filter_map(|l| l.split_once('"').map(|(key, _)| key))
        .collect();
    let keys: Vec<&str> = SUMMARY_KEYS.iter().map(|(name, _)| *name).collect();
    assert_eq!(written, keys);
}
