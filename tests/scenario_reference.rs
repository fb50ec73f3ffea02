//! docs/scenario_reference.md is the schema's own reference: its tables are the ones made from
//! the scenario structs, their doc comments, defaults and the validator (regenerate them with
//! `cargo run --release --example gen_scenario_reference`), and every key of the default
//! scenario, and of every shipped scenario, has its row there.

use std::collections::BTreeSet;
use std::path::Path;
use wingman::scenario::Scenario;
use wingman::scenario::reference::{flatten, with_tables};

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn reference() -> String {
    std::fs::read_to_string(repo().join("docs/scenario_reference.md")).expect("the reference")
}

/// The dotted keys the document's tables list: `## \`[section]\`` headings, then rows whose
/// first cell is a key.
fn documented_keys(doc: &str) -> BTreeSet<String> {
    let mut section = String::new();
    let mut keys = BTreeSet::new();
    for line in doc.lines() {
        if let Some(title) = line.strip_prefix("## `[") {
            section = title
                .trim_end_matches("]`")
                .trim_matches(['[', ']'])
                .to_string();
        } else if let Some(row) = line.strip_prefix("| `") {
            let name = row.split('`').next().unwrap_or_default();
            keys.insert(format!("{section}.{name}"));
        }
    }
    keys
}

fn keys_of(scenario: &Scenario) -> Vec<String> {
    let toml::Value::Table(table) = toml::Value::try_from(scenario).expect("serialisable") else {
        panic!("a scenario is a table");
    };
    let mut values = Vec::new();
    flatten(&table, "", &mut values);
    values.into_iter().map(|(key, _)| key).collect()
}

#[test]
fn scenario_reference_is_current() {
    let doc = reference();
    let generated = with_tables(&doc, repo()).expect("the schema and the marker lines");
    assert!(
        generated == doc,
        "docs/scenario_reference.md is stale: run \
         `cargo run --release --example gen_scenario_reference`"
    );
}

#[test]
fn every_key_of_the_default_scenario_is_documented() {
    let documented = documented_keys(&reference());
    let keys = keys_of(&Scenario::default());
    assert!(keys.len() > 150, "too few keys found: {}", keys.len());
    let missing: Vec<&String> = keys.iter().filter(|k| !documented.contains(*k)).collect();
    assert!(missing.is_empty(), "keys without a row: {missing:?}");
}

#[test]
fn every_key_a_shipped_scenario_writes_is_documented() {
    let documented = documented_keys(&reference());
    let mut checked = 0;
    for entry in std::fs::read_dir(repo().join("scenarios")).expect("scenarios/") {
        let path = entry.expect("entry").path();
        let text = std::fs::read_to_string(&path).expect("readable");
        let table: toml::Table = text.parse().expect("TOML");
        let mut written = Vec::new();
        flatten(&table, "", &mut written);
        for (key, _) in written {
            assert!(
                documented.contains(&key),
                "{}: {key} has no row",
                path.display()
            );
            checked += 1;
        }
    }
    assert!(checked > 100, "too few keys checked: {checked}");
}

/// The reader above finds what it should: a heading's section and a row's key.
#[test]
fn documented_keys_reads_headings_and_rows() {
    let doc =
        "## `[a.b]`\n\n| key | type |\n|---|---|\n| `c` | float |\n## `[[a.w]]`\n| `p` | x |\n";
    let keys: Vec<String> = documented_keys(doc).into_iter().collect();
    assert_eq!(keys, ["a.b.c", "a.w.p"]);
}
