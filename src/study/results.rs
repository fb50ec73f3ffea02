//! A case's record (`cases/NNNNNN/case.json`, written last: its presence marks the case
//! complete) and the study's `results.csv`, one row per case built from the records.
//!
//! Columns of `results.csv`, in order: `case` (index), `point` (combination of axis values),
//! `replicate`; one column per axis key (and `run.seed` for replicates); `status` (one of
//! [`case_statuses`]: a run's status, or `failed` when the case could not run); the case's
//! numbers (for a sweep: `lost_target`, `rms_error_last20s_norm_ft` and
//! every number and true/false of `summary.json`, nested names joined by `.` and array
//! entries numbered from 0, e.g. `rms_error_last20s_ft.0`; for the apparent-size study its
//! lengths and sizes), in the order they first appear; and `message` (why a case stopped).
//! An empty cell is a number the case does not have. The columns of [`is_timing_column`]
//! hold wall-clock times, the only cells that differ between two runs of one study.

use crate::output::summary::RunStatus;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The status of a case that could not run: a set-up failure (no graphics adapter, a missing
/// asset), a crash, a run that wrote no summary. Not a result: a rerun of the sweep retries
/// the case.
pub const FAILED: &str = "failed";

/// Every status a case can have: a run's ([`RunStatus::name`]), then [`FAILED`]; the order in
/// which progress and summary lines count them.
pub fn case_statuses() -> Vec<&'static str> {
    RunStatus::ALL
        .iter()
        .map(|s| s.name())
        .chain([FAILED])
        .collect()
}

/// `records` counted by status, in the order of [`case_statuses`] (statuses no record has
/// left out; a status this build does not know, from another build's records, last):
/// `10 completed, 1 lost, 1 failed`.
pub fn count_statuses<'a>(statuses: impl IntoIterator<Item = &'a str>) -> String {
    let statuses: Vec<&str> = statuses.into_iter().collect();
    let mut names = case_statuses();
    for status in &statuses {
        if !names.contains(status) {
            names.push(status);
        }
    }
    let counts: Vec<String> = names
        .iter()
        .map(|name| (name, statuses.iter().filter(|s| *s == name).count()))
        .filter(|(_, count)| *count > 0)
        .map(|(name, count)| format!("{count} {name}"))
        .collect();
    if counts.is_empty() {
        "none yet".to_string()
    } else {
        counts.join(", ")
    }
}

/// One named number (or true/false, or text) of a case.
pub type Column = (String, Value);

/// What one case gave.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseRecord {
    /// The case's index.
    pub case: usize,
    /// Its combination of axis values.
    pub point: usize,
    /// Its replicate.
    pub replicate: u32,
    /// Its settings as `results.csv` cells: key, value.
    pub settings: Vec<(String, String)>,
    /// The run's status ([`RunStatus::name`]), or [`FAILED`] for a case that could not run.
    pub status: String,
    /// Why it stopped early or failed.
    pub message: Option<String>,
    /// Its numbers.
    pub columns: Vec<Column>,
}

impl CaseRecord {
    /// Whether the run flew to its end (completed or intercepted); anything else counts as
    /// stopped early or failed.
    pub fn ended_ok(&self) -> bool {
        [RunStatus::Completed, RunStatus::Intercepted]
            .iter()
            .any(|s| self.status == s.name())
    }

    /// Whether the case is a result: it ran, to its end or to a stop of its own (lost,
    /// diverged). A case that could not run ([`FAILED`]) or that a signal stopped
    /// (`interrupted`) is not, and a rerun of the sweep runs it again.
    pub fn is_final(&self) -> bool {
        self.status != FAILED && self.status != RunStatus::Interrupted.name()
    }

    /// Whether the run's summary says the target was lost (`lost_target`).
    pub fn lost_target(&self) -> bool {
        self.number("lost_target") == Some(1.0)
    }

    /// The value of column `name` as a number (true is 1, false 0), if it has one.
    pub fn number(&self, name: &str) -> Option<f64> {
        let value = self.columns.iter().find(|(n, _)| n == name)?;
        match &value.1 {
            Value::Bool(b) => Some(f64::from(u8::from(*b))),
            v => v.as_f64().filter(|x| x.is_finite()),
        }
    }

    /// The cell of setting `key`.
    pub fn setting(&self, key: &str) -> Option<&str> {
        self.settings
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
}

/// What a sweep's cases gave, as its last lines say it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tally {
    /// The cases counted by status ([`count_statuses`]).
    pub counts: String,
    /// The cases that are no result ([`CaseRecord::is_final`]): index and why.
    pub not_run: Vec<(usize, String)>,
}

impl Tally {
    /// The tally of `records`.
    pub fn of(records: &[CaseRecord]) -> Self {
        Self {
            counts: count_statuses(records.iter().map(|r| r.status.as_str())),
            not_run: records
                .iter()
                .filter(|r| !r.is_final())
                .map(|r| {
                    let why = r.message.as_deref().unwrap_or(r.status.as_str());
                    (r.case, why.to_string())
                })
                .collect(),
        }
    }
}

/// Summary fields that are not numbers of the case (text, or lists summarised elsewhere).
const NOT_COLUMNS: [&str; 6] = [
    "scenario",
    "status",
    "message",
    "notes",
    "adapter",
    "loss_episodes",
];

/// The columns of a run's `summary.json`: `lost_target` (a loss episode that never ended),
/// the norm of the last 20 s RMS error, then every number and true/false, flattened.
pub fn summary_columns(summary: &Value) -> Vec<Column> {
    let lost_target = summary["loss_episodes"]
        .as_array()
        .is_some_and(|episodes| episodes.iter().any(|e| e["found"] == Value::Bool(false)));
    let rms_norm = summary["rms_error_last20s_ft"].as_array().and_then(|axes| {
        let squares: Option<f64> = axes.iter().map(|v| v.as_f64().map(|x| x * x)).sum();
        squares.map(f64::sqrt)
    });
    let mut columns = vec![
        ("lost_target".to_string(), Value::Bool(lost_target)),
        (
            "rms_error_last20s_norm_ft".to_string(),
            rms_norm.map_or(Value::Null, Value::from),
        ),
    ];
    if let Value::Object(fields) = summary {
        for (name, value) in fields
            .iter()
            .filter(|(n, _)| !NOT_COLUMNS.contains(&n.as_str()))
        {
            flatten(name, value, &mut columns);
        }
    }
    columns
}

/// Appends the numbers and true/falses under `value`, named from `name` (a null is a
/// number the case does not have: no column).
fn flatten(name: &str, value: &Value, out: &mut Vec<Column>) {
    match value {
        Value::Number(_) | Value::Bool(_) => out.push((name.into(), value.clone())),
        Value::Array(items) => {
            for (k, item) in items.iter().enumerate() {
                flatten(&format!("{name}.{k}"), item, out);
            }
        }
        Value::Object(fields) => {
            for (key, item) in fields {
                flatten(&format!("{name}.{key}"), item, out);
            }
        }
        Value::String(_) | Value::Null => {}
    }
}

/// Whether a column holds wall-clock time (differs from run to run), a group's follower's
/// (`f1.wall_s`) included.
pub fn is_timing_column(name: &str) -> bool {
    let timing = |name: &str| {
        name == "wall_s"
            || name == "realtime_factor"
            || name.starts_with("per_frame_ms.")
            || name.starts_with("stage_wall_s.")
    };
    timing(name)
        || name
            .match_indices('.')
            .any(|(at, _)| timing(&name[at + 1..]))
}

/// Why results could not be read or written.
#[derive(Debug, thiserror::Error)]
#[error("{}: {reason}", path.display())]
pub struct ResultsError {
    /// The file.
    pub path: PathBuf,
    /// What went wrong.
    pub reason: String,
}

/// The record in `dir/case.json`, if there is a readable one.
pub fn read_record(dir: &Path) -> Option<CaseRecord> {
    let text = std::fs::read_to_string(dir.join(RECORD_FILE)).ok()?;
    serde_json::from_str(&text).ok()
}

/// The file that marks a case complete.
pub const RECORD_FILE: &str = "case.json";

/// Writes `dir/case.json` through a temporary file, so that a killed sweep never leaves a
/// half-written record.
pub fn write_record(dir: &Path, record: &CaseRecord) -> Result<(), ResultsError> {
    let path = dir.join(RECORD_FILE);
    let temporary = dir.join("case.json.partial");
    let error = |e: std::io::Error| ResultsError {
        path: path.clone(),
        reason: e.to_string(),
    };
    let text = serde_json::to_string_pretty(record).map_err(|e| ResultsError {
        path: path.clone(),
        reason: e.to_string(),
    })?;
    std::fs::write(&temporary, text).map_err(error)?;
    std::fs::rename(&temporary, &path).map_err(error)
}

/// Writes `results.csv`: one row per record, in the order given.
pub fn write_results_csv(
    path: &Path,
    setting_keys: &[String],
    records: &[CaseRecord],
) -> Result<(), ResultsError> {
    let error = |e: &dyn std::fmt::Display| ResultsError {
        path: path.to_path_buf(),
        reason: e.to_string(),
    };
    let mut number_names: Vec<&str> = Vec::new();
    for record in records {
        for (name, _) in &record.columns {
            if !number_names.contains(&name.as_str()) {
                number_names.push(name);
            }
        }
    }
    let mut writer = csv::Writer::from_path(path).map_err(|e| error(&e))?;
    let header = ["case", "point", "replicate"]
        .into_iter()
        .chain(setting_keys.iter().map(String::as_str))
        .chain(["status"])
        .chain(number_names.iter().copied())
        .chain(["message"]);
    writer.write_record(header).map_err(|e| error(&e))?;
    for r in records {
        let mut row = vec![
            r.case.to_string(),
            r.point.to_string(),
            r.replicate.to_string(),
        ];
        row.extend(
            setting_keys
                .iter()
                .map(|k| r.setting(k).unwrap_or("").to_string()),
        );
        row.push(r.status.clone());
        row.extend(number_names.iter().map(|name| {
            r.columns
                .iter()
                .find(|(n, _)| n == name)
                .map_or(String::new(), |(_, v)| cell(v))
        }));
        row.push(r.message.clone().unwrap_or_default());
        writer.write_record(&row).map_err(|e| error(&e))?;
    }
    writer.flush().map_err(|e| error(&e))
}

/// A value as a cell: numbers as Rust prints them (shortest exact form), null empty.
fn cell(value: &Value) -> String {
    match value {
        Value::Null => String::new(),
        Value::String(s) => s.clone(),
        Value::Number(n) => n
            .as_i64()
            .map(|i| i.to_string())
            .or_else(|| n.as_f64().map(|f| f.to_string()))
            .unwrap_or_else(|| n.to_string()),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_is_flattened_with_derived_columns() {
        let summary = serde_json::json!({
            "scenario": "x", "status": "completed", "wall_s": 1.5,
            "rms_error_last20s_ft": [3.0, 4.0, 0.0],
            "aircraft": {"throttle_range": [0.1, 0.9]},
            "loss_episodes": [{"found": true}, {"found": false}],
            "intercept_time_s": null,
        });
        let columns = summary_columns(&summary);
        let get = |n: &str| columns.iter().find(|(k, _)| k == n).map(|(_, v)| v.clone());
        assert_eq!(get("lost_target"), Some(Value::Bool(true)));
        assert_eq!(get("rms_error_last20s_norm_ft"), Some(Value::from(5.0)));
        assert_eq!(get("rms_error_last20s_ft.1"), Some(Value::from(4.0)));
        assert_eq!(get("aircraft.throttle_range.1"), Some(Value::from(0.9)));
        assert_eq!(get("intercept_time_s"), None);
        assert_eq!(get("scenario"), None);
        assert!(is_timing_column("wall_s") && is_timing_column("per_frame_ms.render"));
        assert!(is_timing_column("f1.wall_s") && is_timing_column("f2.per_frame_ms.render"));
        assert!(!is_timing_column("min_range_ft") && !is_timing_column("f1.min_range_ft"));
    }

    #[test]
    fn csv_has_the_union_of_columns_and_quotes_messages() {
        let dir = tempfile::tempdir().unwrap();
        let record = |case: usize, columns: Vec<Column>, message: Option<&str>| CaseRecord {
            case,
            point: case,
            replicate: 0,
            settings: vec![("camera.hfov_deg".into(), format!("{}", 30 * (case + 1)))],
            status: "completed".into(),
            message: message.map(str::to_string),
            columns,
        };
        let records = [
            record(0, vec![("a".into(), Value::from(1.5))], None),
            record(
                1,
                vec![("b".into(), Value::Bool(true))],
                Some("stopped, at 3 s"),
            ),
        ];
        let path = dir.path().join("results.csv");
        write_results_csv(&path, &["camera.hfov_deg".into()], &records).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines[0],
            "case,point,replicate,camera.hfov_deg,status,a,b,message"
        );
        assert_eq!(lines[1], "0,0,0,30,completed,1.5,,");
        assert_eq!(lines[2], "1,1,0,60,completed,,true,\"stopped, at 3 s\"");
        assert_eq!(records[1].number("b"), Some(1.0));
    }
}
