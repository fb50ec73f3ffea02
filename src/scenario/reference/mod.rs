//! `docs/scenario_reference.md`: every key a scenario may set, with its type, default, allowed
//! range and meaning, made from the schema itself: the keys and defaults from the default
//! [`Scenario`] serialised to TOML, the meaning from the doc comments of the scenario structs
//! (`src/scenario/*.rs`), the range from the validator ([`ranges`]).
//! `cargo run --example gen_scenario_reference` writes it; `tests/scenario_reference.rs` fails
//! when it is stale.

pub mod ranges;
pub mod schema_docs;

use crate::scenario::Scenario;
use schema_docs::{KeyDoc, Schema};
use std::fmt::Write;
use std::path::Path;

/// The line before the generated tables.
pub const BEGIN: &str = "<!-- Generated from src/scenario/*.rs by \
                         `cargo run --example gen_scenario_reference`; do not edit by hand. -->";
/// The line after them.
pub const END: &str = "<!-- End of the generated tables. -->";

/// A scenario's leaf values by dotted key (sections flattened; arrays are leaves).
pub fn flatten(table: &toml::Table, prefix: &str, out: &mut Vec<(String, toml::Value)>) {
    for (name, value) in table {
        let key = if prefix.is_empty() {
            name.clone()
        } else {
            format!("{prefix}.{name}")
        };
        match value {
            toml::Value::Table(inner) => flatten(inner, &key, out),
            _ => out.push((key, value.clone())),
        }
    }
}

/// A table cell: one line, pipes escaped.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

/// The type as a scenario writes it.
fn toml_type(key: &KeyDoc) -> String {
    let ty = key.rust_type.as_str();
    if !key.variants.is_empty() {
        return "string".to_string();
    }
    let array = |t: &str| {
        let (element, n) = t.strip_prefix('[')?.strip_suffix(']')?.split_once("; ")?;
        let noun = if element == "f64" {
            "floats"
        } else {
            "integers"
        };
        Some(format!("{n} {noun}"))
    };
    match ty {
        "f64" => "float".to_string(),
        "u8" | "u32" | "u64" => "integer".to_string(),
        "bool" => "boolean".to_string(),
        "String" => "string".to_string(),
        t if t.starts_with("Vec<") => "array of tables".to_string(),
        t => array(t).unwrap_or_else(|| t.to_string()),
    }
}

/// A value of the key's type, for a key without a default (in a table of an array).
fn example_value(key: &KeyDoc) -> toml::Value {
    match key
        .rust_type
        .strip_prefix('[')
        .and_then(|t| t.split_once("; "))
    {
        Some((_, n)) => {
            let n = n.trim_end_matches(']').parse().unwrap_or(0);
            toml::Value::Array(vec![toml::Value::Float(0.0); n])
        }
        None => toml::Value::Float(0.0),
    }
}

/// The meaning: the field's doc, then each variant's.
fn meaning(key: &KeyDoc) -> String {
    let mut text = key.doc.clone();
    for variant in &key.variants {
        let _ = write!(text, " `{}`: {}", variant.name, variant.doc);
    }
    cell(&text)
}

/// The sections' headings and tables. `contexts` are valid scenarios (the default first) the
/// validator is probed in; an error names a key of the default scenario the sources do not
/// document, or a documented key it lacks.
pub fn tables(schema: &Schema, contexts: &[Scenario]) -> Result<String, String> {
    let default_table = ranges::table_of(&Scenario::default())?;
    let mut defaults = Vec::new();
    flatten(&default_table, "", &mut defaults);
    let probed: Vec<toml::Table> = contexts
        .iter()
        .map(ranges::table_of)
        .collect::<Result<_, _>>()?;
    let keys = schema_docs::keys(schema, "Scenario", "")?;
    if let Some((key, _)) = defaults
        .iter()
        .find(|(key, _)| !keys.iter().any(|k| k.dotted() == *key))
    {
        return Err(format!(
            "the default scenario's key {key} is not documented"
        ));
    }
    let mut out = String::new();
    let mut section = None;
    for key in &keys {
        if section.as_ref() != Some(&key.section) {
            heading(&mut out, schema, key);
            section = Some(key.section.clone());
        }
        ranges::check_variants(key, &default_table)?;
        let default = defaults.iter().find(|(k, _)| *k == key.dotted());
        let in_array = key.section.contains("[]");
        let (default_text, probe_like) = match default {
            Some((_, value)) => (format!("`{value}`"), value.clone()),
            None if in_array => ("(none: required)".to_string(), example_value(key)),
            None => return Err(format!("documented key {} has no default", key.dotted())),
        };
        let range = ranges::validated_range(&key.dotted(), &probe_like, &probed);
        let range = range.unwrap_or_else(|| ranges::type_range(key));
        let _ = writeln!(
            out,
            "| `{}` | {} | {} | {} | {} |",
            key.name,
            toml_type(key),
            cell(&default_text),
            cell(&range),
            meaning(key)
        );
    }
    Ok(out)
}

/// A section's heading, its doc and the table's header.
fn heading(out: &mut String, schema: &Schema, key: &KeyDoc) {
    let title = match key.section.strip_suffix("[]") {
        Some(array) => format!("[[{array}]]"),
        None => format!("[{}]", key.section),
    };
    let _ = write!(out, "\n## `{title}`\n\n");
    if let Some(doc) = section_doc(schema, &key.section).filter(|d| !d.is_empty()) {
        let _ = write!(out, "{}\n\n", doc.replace('\n', " "));
    }
    out.push_str("| key | type | default | allowed | meaning |\n|---|---|---|---|---|\n");
}

/// The doc comment of the struct that the dotted path `section` holds (of the field that
/// holds it, when the struct has none).
fn section_doc(schema: &Schema, section: &str) -> Option<String> {
    let mut type_name = "Scenario".to_string();
    let mut field_doc = String::new();
    for part in section.split('.') {
        let part = part.trim_end_matches("[]");
        let field = schema
            .get(&type_name)?
            .members
            .iter()
            .find(|m| m.name == part)?;
        let ty = field.rust_type.rsplit("::").next().unwrap_or_default();
        type_name = ty
            .strip_prefix("Vec<")
            .and_then(|t| t.strip_suffix('>'))
            .unwrap_or(ty)
            .to_string();
        field_doc = field.doc.clone();
    }
    // A struct doc that only names its section, or names another one (a struct used in two
    // places), gives way to the field's.
    let struct_doc = &schema.get(&type_name)?.doc;
    let own = format!("`[{section}]`");
    let rest = struct_doc.strip_prefix(&own).unwrap_or(struct_doc);
    let bare = matches!(
        rest.trim_matches(|c: char| ":. ".contains(c)),
        "" | "section"
    );
    let foreign = struct_doc.starts_with("`[") && !struct_doc.starts_with(&own);
    Some(if bare || foreign {
        field_doc
    } else {
        struct_doc.clone()
    })
}

/// The schema of the scenario sources in `dir` (`src/scenario/`).
pub fn schema_of(dir: &Path) -> Result<Schema, String> {
    let mut schema = Schema::new();
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        .collect();
    files.sort();
    for file in files {
        let text =
            std::fs::read_to_string(&file).map_err(|e| format!("{}: {e}", file.display()))?;
        schema_docs::parse_source(&text, &mut schema);
    }
    Ok(schema)
}

/// The default scenario with the target flying to one waypoint: the one scenario that holds a
/// table of every array of tables, for the checks of their keys.
fn one_waypoint() -> Scenario {
    let mut scenario = Scenario::default();
    scenario.target.motion = crate::scenario::TargetMotion::Waypoints;
    scenario.target.waypoints = vec![crate::scenario::Waypoint {
        position_ft: [1000.0, 0.0, 0.0],
        speed_fps: 50.0,
    }];
    scenario
}

/// The default scenario, then each of the scenario files in `dir` (`scenarios/`), by name, then
/// the default with one waypoint.
pub fn contexts_of(dir: &Path) -> Result<Vec<Scenario>, String> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    let mut contexts = vec![Scenario::default()];
    for file in files {
        let text =
            std::fs::read_to_string(&file).map_err(|e| format!("{}: {e}", file.display()))?;
        contexts.push(Scenario::from_toml_str(&text, &file, &[]).map_err(|e| e.to_string())?);
    }
    contexts.push(one_waypoint());
    Ok(contexts)
}

/// `doc` with the text between its [`BEGIN`] and [`END`] lines replaced by the tables made
/// from the repository at `repo` (its `src/scenario/` and `scenarios/`).
pub fn with_tables(doc: &str, repo: &Path) -> Result<String, String> {
    let missing = |line: &str| format!("the document lacks the line {line}");
    let begin = doc.find(BEGIN).ok_or_else(|| missing(BEGIN))? + BEGIN.len();
    let end = begin + doc[begin..].find(END).ok_or_else(|| missing(END))?;
    let schema = schema_of(&repo.join("src").join("scenario"))?;
    let contexts = contexts_of(&repo.join("scenarios"))?;
    let generated = tables(&schema, &contexts)?;
    Ok(format!("{}\n{}\n{}", &doc[..begin], generated, &doc[end..]))
}
