//! Compares two folders of runs (`BASE/<scenario>/` and `NEW/<scenario>/`, as written by
//! `scripts/behaviour_check.sh`): telemetry column by column and the summary's numbers, to
//! check that a change which should not change behaviour did not.
//!
//! ```text
//! cargo run --release --example compare_runs -- BASE NEW [--rel-tol 1e-9]
//! ```
//!
//! A value matches when |a - b| ≤ tol · max(|a|, |b|, the column's largest |value| over the
//! run), both empty counting as equal. Summary keys and telemetry columns the new build adds
//! are not compared (the added columns are named); a column it no longer writes fails. Excepted: wall times (`wall_s`, `realtime_factor`,
//! `per_frame_ms`, `stage_wall_s` in the summary) and the columns and rows a known fix of
//! the telemetry changes: `r_meas_*` (now the brought-forward r the guidance was given, no
//! longer the held frame's), and the rows at which the sensor acted (now logged after it
//! acted, so they show the frame that just reached the guidance, or the noise sample just
//! drawn, and what guidance and flight control made of it; such a row is recognised by a
//! different `frame_t_s` in camera runs and a different `r_meas_*` in the others): on those
//! rows only the simulated states are compared. Exit code 0 when everything matches, 1
//! otherwise.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Summary keys that measure the machine, not the simulation.
const WALL_TIME_KEYS: [&str; 4] = ["wall_s", "realtime_factor", "per_frame_ms", "stage_wall_s"];

/// Columns of simulated state (and of the truth), which no fix of what is logged can change:
/// the only ones compared on a row where the logged frame differs.
const STATE_PREFIXES: [&str; 12] = [
    "t_s",
    "rel_",
    "tgt_",
    "fol_n",
    "fol_e",
    "fol_d",
    "phi_rad",
    "theta_rad",
    "psi_rad",
    "cmd_",
    "b_hat_ft",
    "d_hat_",
];

/// The telemetry columns whose meaning a fix changed on every row.
fn is_excepted_column(name: &str) -> bool {
    name.starts_with("r_meas_")
}

fn is_state_column(name: &str) -> bool {
    STATE_PREFIXES.iter().any(|p| name.starts_with(p))
}

struct Table {
    header: Vec<String>,
    rows: Vec<Vec<Option<f64>>>,
}

fn read_table(path: &Path) -> Result<Table, String> {
    let mut reader =
        csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let header = reader
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?
        .iter()
        .map(str::to_string)
        .collect();
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| format!("{}: {e}", path.display()))?;
        rows.push(record.iter().map(|v| v.parse::<f64>().ok()).collect());
    }
    Ok(Table { header, rows })
}

/// Largest |value| of each column.
fn column_scales(table: &Table) -> Vec<f64> {
    let mut scales = vec![0.0f64; table.header.len()];
    for row in &table.rows {
        for (scale, value) in scales.iter_mut().zip(row) {
            *scale = scale.max(value.map_or(0.0, f64::abs));
        }
    }
    scales
}

fn matches(a: Option<f64>, b: Option<f64>, scale: f64, tol: f64) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => (a - b).abs() <= tol * a.abs().max(b.abs()).max(scale),
        _ => false,
    }
}

/// Per column: the worst relative difference and how many rows broke the tolerance.
#[derive(Default)]
struct ColumnReport {
    worst: f64,
    failures: usize,
    first_failure_row: Option<usize>,
}

/// The new table's columns in the base's order, and the names of the columns only the new
/// build writes (a column added to the outputs, not compared); an error naming a base column
/// the new build no longer writes.
fn columns_of_base(base: &Table, new: &Table) -> Result<(Table, Vec<String>), String> {
    let position = |name: &String| new.header.iter().position(|h| h == name);
    let missing: Vec<&str> = base
        .header
        .iter()
        .filter(|h| position(h).is_none())
        .map(String::as_str)
        .collect();
    if !missing.is_empty() {
        return Err(format!("columns gone: {}", missing.join(",")));
    }
    let columns: Vec<usize> = base.header.iter().filter_map(position).collect();
    let rows = new
        .rows
        .iter()
        .map(|row| columns.iter().map(|c| row[*c]).collect())
        .collect();
    let added = new
        .header
        .iter()
        .filter(|h| !base.header.contains(h))
        .cloned()
        .collect();
    let projected = Table {
        header: base.header.clone(),
        rows,
    };
    Ok((projected, added))
}

fn compare_telemetry(base: &Table, new: &Table, tol: f64) -> Result<Vec<String>, String> {
    let (new, added) = columns_of_base(base, new)?;
    let new = &new;
    if base.rows.len() != new.rows.len() {
        return Err(format!(
            "row counts differ: base {} new {}",
            base.rows.len(),
            new.rows.len()
        ));
    }
    let frame_column = base.header.iter().position(|h| h == "frame_t_s");
    let measurement_columns: Vec<usize> = (0..base.header.len())
        .filter(|c| base.header[*c].starts_with("r_meas_"))
        .collect();
    // The row shows a frame (camera run) or not: then the sensor is a continuous one.
    let sensor_acted = |a: &[Option<f64>], b: &[Option<f64>]| match frame_column {
        Some(c) if a[c].is_some() || b[c].is_some() => a[c] != b[c],
        _ => measurement_columns.iter().any(|c| a[*c] != b[*c]),
    };
    let scales = column_scales(base);
    let mut reports: BTreeMap<&str, ColumnReport> = BTreeMap::new();
    let mut delivery_rows = 0;
    for (i, (a, b)) in base.rows.iter().zip(&new.rows).enumerate() {
        let delivery = sensor_acted(a, b);
        delivery_rows += usize::from(delivery);
        for (c, name) in base.header.iter().enumerate() {
            if is_excepted_column(name) || (delivery && !is_state_column(name)) {
                continue;
            }
            let report = reports.entry(name).or_default();
            if let (Some(x), Some(y)) = (a[c], b[c]) {
                let denominator = x.abs().max(y.abs()).max(scales[c]);
                if denominator > 0.0 {
                    report.worst = report.worst.max((x - y).abs() / denominator);
                }
            }
            if !matches(a[c], b[c], scales[c], tol) {
                report.failures += 1;
                report.first_failure_row.get_or_insert(i);
            }
        }
    }
    let mut lines = vec![format!(
        "{} rows, {} columns compared, {} rows where the sensor acted compared on states only",
        base.rows.len(),
        reports.len(),
        delivery_rows
    )];
    if !added.is_empty() {
        lines.push(format!(
            "columns the new build adds (not compared): {}",
            added.join(",")
        ));
    }
    let worst = reports
        .iter()
        .filter(|(_, r)| r.worst > 0.0)
        .max_by(|a, b| a.1.worst.total_cmp(&b.1.worst))
        .map_or("every value identical".to_string(), |(name, r)| {
            format!("largest relative difference {:.2e} ({name})", r.worst)
        });
    lines.push(worst);

    let failing: Vec<String> = reports
        .iter()
        .filter(|(_, r)| r.failures > 0)
        .map(|(name, r)| {
            format!(
                "  {name}: {} rows over tolerance, worst {:.2e}, first at row {}",
                r.failures,
                r.worst,
                r.first_failure_row.unwrap_or(0)
            )
        })
        .collect();
    if failing.is_empty() {
        Ok(lines)
    } else {
        Err([lines, failing].concat().join("\n"))
    }
}

/// Every number of a JSON value, by path.
fn flatten(value: &serde_json::Value, path: String, out: &mut BTreeMap<String, Option<f64>>) {
    match value {
        serde_json::Value::Object(map) => {
            for (key, v) in map {
                if !WALL_TIME_KEYS.contains(&key.as_str()) {
                    flatten(v, format!("{path}.{key}"), out);
                }
            }
        }
        serde_json::Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                flatten(v, format!("{path}[{i}]"), out);
            }
        }
        serde_json::Value::Number(n) => {
            out.insert(path, n.as_f64());
        }
        serde_json::Value::Null => {
            out.insert(path, None);
        }
        other => {
            out.insert(format!("{path}={other}"), None);
        }
    }
}

fn read_summary(path: &Path) -> Result<BTreeMap<String, Option<f64>>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let json: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut out = BTreeMap::new();
    flatten(&json, String::new(), &mut out);
    Ok(out)
}

/// Summary values must match; keys only the new summary has are new information, not a
/// change of behaviour, and are not compared.
fn compare_summary(base: &Path, new: &Path, tol: f64) -> Result<(), String> {
    let (a, b) = (read_summary(base)?, read_summary(new)?);
    let mut problems = Vec::new();
    for key in a.keys() {
        match (a.get(key), b.get(key)) {
            (Some(x), Some(y)) if matches(*x, *y, 0.0, tol) => {}
            (x, y) => problems.push(format!("  summary {key}: base {x:?} new {y:?}")),
        }
    }
    problems.dedup();
    if problems.is_empty() {
        Ok(())
    } else {
        Err(problems.join("\n"))
    }
}

fn compare_run(base: &Path, new: &Path, tol: f64) -> Result<Vec<String>, String> {
    let lines = compare_telemetry(
        &read_table(&base.join("telemetry.csv"))?,
        &read_table(&new.join("telemetry.csv"))?,
        tol,
    )?;
    compare_summary(&base.join("summary.json"), &new.join("summary.json"), tol)?;
    Ok(lines)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let tol = args
        .iter()
        .position(|a| a == "--rel-tol")
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(1e-9);
    let dirs: Vec<PathBuf> = args
        .iter()
        .take_while(|a| *a != "--rel-tol")
        .map(PathBuf::from)
        .collect();
    let [base, new] = dirs.as_slice() else {
        eprintln!("usage: compare_runs BASE_DIR NEW_DIR [--rel-tol 1e-9]");
        std::process::exit(2);
    };
    let mut names: Vec<String> = std::fs::read_dir(base)
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .filter(|e| e.path().join("telemetry.csv").exists())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    let mut failed = names.is_empty();
    for name in &names {
        match compare_run(&base.join(name), &new.join(name), tol) {
            Ok(lines) => println!("{name}: same within {tol:e}; {}", lines.join("; ")),
            Err(why) => {
                failed = true;
                println!("{name}: DIFFERS\n{why}");
            }
        }
    }
    std::process::exit(i32::from(failed));
}
