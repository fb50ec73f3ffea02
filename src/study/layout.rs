//! `plan.json`: what a study's results are made of: its axes and their values, every case's
//! settings, and the texts of the study and scenario files. Written into every sweep folder,
//! it tells a rerun whether the folder holds the same study (and so which cases are done),
//! and tells `wingman sweep merge` how to lay out and plot shards without the study file.

use super::results::CaseRecord;
use super::setting::SEED_KEY;
use super::spec::StudyKind;
use serde::{Deserialize, Serialize};

/// The columns a sweep plots by default (those its cases have).
pub const SWEEP_OUTCOMES: [&str; 6] = [
    "rms_error_last20s_norm_ft",
    "b_hat_final_ft",
    "min_range_ft",
    "lost_frames",
    "centroid_rms_px",
    "length_rms_px",
];

/// The columns an apparent-size study plots by default.
pub const APPARENT_SIZE_OUTCOMES: [&str; 4] = [
    "size_measured_ft",
    "size_mesh_ft",
    "size_four_point_ft",
    "ratio_measured_true",
];

/// One axis as `results.csv` shows it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxisLayout {
    /// Name.
    pub name: String,
    /// Keys set together.
    pub keys: Vec<String>,
    /// Each value as cells, one per key.
    pub values: Vec<Vec<String>>,
}

impl AxisLayout {
    /// Whether the first key's values are all numbers (plotted at their value; otherwise at
    /// 0, 1, 2... with their names).
    pub fn is_numeric(&self) -> bool {
        self.values
            .iter()
            .all(|v| v.first().is_some_and(|c| c.parse::<f64>().is_ok()))
    }

    /// Each value's name: its cells joined by `x` (`640x480`).
    pub fn value_labels(&self) -> Vec<String> {
        self.values.iter().map(|v| v.join("x")).collect()
    }

    /// Which of this axis' values a case had.
    pub fn index_of(&self, record: &CaseRecord) -> Option<usize> {
        self.values.iter().position(|value| {
            self.keys
                .iter()
                .zip(value)
                .all(|(key, cell)| record.setting(key) == Some(cell.as_str()))
        })
    }

    /// Where value `k` sits on a chart's x axis.
    pub fn x_of(&self, k: usize) -> f64 {
        let number = self.values[k].first().and_then(|c| c.parse::<f64>().ok());
        match number {
            Some(x) if self.is_numeric() => x,
            _ => k as f64,
        }
    }
}

/// A study's results layout (`plan.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudyLayout {
    /// The study's name.
    pub study: String,
    /// What its cases do.
    pub kind: StudyKind,
    /// Its axes.
    pub axes: Vec<AxisLayout>,
    /// Whether cases are replicated over `run.seed`.
    pub replicated: bool,
    /// Columns to plot (None: the kind's defaults).
    pub outcomes: Option<Vec<String>>,
    /// Each case's settings as cells (key, value), by index.
    pub cases: Vec<Vec<(String, String)>>,
    /// The study file's text.
    pub study_file: String,
    /// The base scenario's text.
    pub scenario_file: String,
}

impl StudyLayout {
    /// The settings' columns of `results.csv`: the axis keys, then `run.seed` when replicated.
    pub fn setting_keys(&self) -> Vec<String> {
        let mut keys: Vec<String> = self.axes.iter().flat_map(|a| a.keys.clone()).collect();
        if self.replicated {
            keys.push(SEED_KEY.to_string());
        }
        keys
    }

    /// Whether `record` is the complete record of case `index` of this study.
    pub fn is_record_of(&self, index: usize, record: &CaseRecord) -> bool {
        record.case == index && self.cases.get(index) == Some(&record.settings)
    }

    /// `plan.json`'s text.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// The outcomes to plot: those named in the study (a warning for each no case has) or
    /// the kind's defaults that some case has.
    pub fn outcomes_to_plot(
        &self,
        records: &[CaseRecord],
        warnings: &mut Vec<String>,
    ) -> Vec<String> {
        let present = |name: &str| records.iter().any(|r| r.number(name).is_some());
        match &self.outcomes {
            Some(named) => {
                for name in named.iter().filter(|n| !present(n)) {
                    warnings.push(format!(
                        "plots.outcomes: no case has a number in column `{name}`"
                    ));
                }
                named.iter().filter(|n| present(n)).cloned().collect()
            }
            None => {
                let defaults: &[&str] = match self.kind {
                    StudyKind::Sweep => &SWEEP_OUTCOMES,
                    StudyKind::ApparentSize => &APPARENT_SIZE_OUTCOMES,
                };
                defaults
                    .iter()
                    .filter(|n| present(n))
                    .map(|n| n.to_string())
                    .collect()
            }
        }
    }
}
