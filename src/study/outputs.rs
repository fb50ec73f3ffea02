//! What a sweep folder holds besides its cases: `plan.json` (which study it belongs to),
//! `results.csv` and `plots/`. One function writes them for a whole sweep, a shard and a
//! merge alike, so that merged shards give what one machine would write.

use super::StudyError;
use super::layout::StudyLayout;
use super::plots::draw_study_plots;
use super::results::{CaseRecord, read_record, write_results_csv};
use crate::output::folder::{self, FolderError};
use std::path::Path;

/// The file naming a sweep folder's study.
pub const PLAN_FILE: &str = "plan.json";

/// Makes `out_dir` this study's folder: checks it as `wingman run` checks its folder
/// ([`folder::check_for`]: new, empty, or a sweep's, known by its `plan.json`; a folder of
/// other files is refused rather than mixed), creates it and writes `plan.json`, or checks
/// that the `plan.json` there is this study's (a folder of another study, or of this study
/// with other scenario or study texts, is refused too).
pub fn claim_folder(layout: &StudyLayout, out_dir: &Path) -> Result<(), StudyError> {
    let path = out_dir.join(PLAN_FILE);
    folder::check_for(out_dir, |dir| dir.join(PLAN_FILE).is_file()).map_err(|e| match e {
        FolderError::NotARun(dir) => StudyError::NotThisStudy { out_dir: dir },
        other => StudyError::OutFolder(other),
    })?;
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| StudyError::Io { path, source }
    };
    // plan.json goes first: a sweep stopped at once leaves a folder a rerun recognises.
    std::fs::create_dir_all(out_dir).map_err(io(out_dir))?;
    match std::fs::read_to_string(&path) {
        Ok(existing) if existing == layout.to_json() => Ok(()),
        Ok(_) => Err(StudyError::OtherStudy {
            out_dir: out_dir.to_path_buf(),
        }),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            std::fs::write(&path, layout.to_json()).map_err(io(&path))
        }
        Err(source) => Err(StudyError::Io { path, source }),
    }?;
    let cases = out_dir.join("cases");
    std::fs::create_dir_all(&cases).map_err(io(&cases))
}

/// The layout in a sweep folder's `plan.json`.
pub fn read_layout(dir: &Path) -> Result<StudyLayout, StudyError> {
    let path = dir.join(PLAN_FILE);
    let text = std::fs::read_to_string(&path).map_err(|e| StudyError::NotASweep {
        dir: dir.to_path_buf(),
        reason: format!("cannot read {PLAN_FILE}: {e}"),
    })?;
    serde_json::from_str(&text).map_err(|e| StudyError::NotASweep {
        dir: dir.to_path_buf(),
        reason: format!("{PLAN_FILE} is not a study layout: {e}"),
    })
}

/// The complete records of cases `indices` in `out_dir`, in that order.
pub fn read_records(
    layout: &StudyLayout,
    out_dir: &Path,
    indices: &[usize],
) -> Result<Vec<CaseRecord>, StudyError> {
    let mut missing = Vec::new();
    let mut records = Vec::with_capacity(indices.len());
    for &index in indices {
        match read_record(&case_folder(out_dir, index)).filter(|r| layout.is_record_of(index, r)) {
            Some(record) => records.push(record),
            None => missing.push(index),
        }
    }
    if missing.is_empty() {
        Ok(records)
    } else {
        Err(StudyError::Incomplete {
            dir: out_dir.to_path_buf(),
            missing,
        })
    }
}

/// The folder of case `index`.
pub fn case_folder(out_dir: &Path, index: usize) -> std::path::PathBuf {
    out_dir.join("cases").join(format!("{index:06}"))
}

/// Writes `results.csv` and, when `with_plots`, the plots; returns the plots' warnings.
pub fn write(
    layout: &StudyLayout,
    records: &[CaseRecord],
    out_dir: &Path,
    with_plots: bool,
) -> Result<Vec<String>, StudyError> {
    write_results_csv(
        &out_dir.join("results.csv"),
        &layout.setting_keys(),
        records,
    )?;
    Ok(if with_plots {
        draw_study_plots(layout, records, &out_dir.join("plots"))
    } else {
        Vec::new()
    })
}
