//! The tables of `docs/outputs.md`, made from [`super::columns::COLUMNS`] and
//! [`super::summary::SUMMARY_KEYS`]: `cargo run --example gen_outputs_doc` writes them into
//! the file, and `tests/outputs_doc.rs` fails when the file's tables are stale.

use super::columns::COLUMNS;
use super::summary::SUMMARY_KEYS;
use std::fmt::Write;

/// The line before the generated tables.
pub const BEGIN: &str = "<!-- Generated from src/output/columns.rs and src/output/summary.rs \
                         by `cargo run --example gen_outputs_doc`; do not edit by hand. -->";
/// The line after them.
pub const END: &str = "<!-- End of the generated tables. -->";

/// A table cell: pipes escaped.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

/// The telemetry and summary tables, in Markdown.
pub fn tables() -> String {
    let mut out = String::from("## Telemetry columns\n\n");
    out.push_str("| columns | unit | runs | meaning |\n|---|---|---|---|\n");
    for column in COLUMNS {
        let names: Vec<String> = column.names().iter().map(|n| format!("`{n}`")).collect();
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} |",
            names.join(", "),
            cell(column.unit),
            column.runs.describe(),
            cell(column.meaning)
        );
    }
    out.push_str("\n## Summary keys\n\n| key | meaning |\n|---|---|\n");
    for (name, meaning) in SUMMARY_KEYS {
        let _ = writeln!(out, "| `{name}` | {} |", cell(meaning));
    }
    out
}

/// `doc` with the text between its [`BEGIN`] and [`END`] lines replaced by [`tables`];
/// an error when it lacks them.
pub fn with_tables(doc: &str) -> Result<String, String> {
    let missing = |line: &str| format!("the document lacks the line {line}");
    let begin = doc.find(BEGIN).ok_or_else(|| missing(BEGIN))? + BEGIN.len();
    let end = begin + doc[begin..].find(END).ok_or_else(|| missing(END))?;
    Ok(format!(
        "{}\n\n{}\n{}",
        &doc[..begin],
        tables(),
        &doc[end..]
    ))
}
