//! `wingman sweep merge SHARD_DIR... --out DIR`: the shards' case folders copied into one
//! sweep folder, then `results.csv` and the plots written as one machine would write them.
//! A case's result is taken from the first shard that has one; a case no shard has a result
//! of but that one could not run is copied as it is (status `failed`), and the merge says so.

use super::StudyError;
use super::outputs::{self, case_folder, claim_folder, read_layout};
use super::results::{RECORD_FILE, Tally, read_record};
use std::path::{Path, PathBuf};

/// What a merge did.
#[derive(Debug, Clone, Default)]
pub struct MergeReport {
    /// Cases in the merged study.
    pub cases: usize,
    /// The cases by status, and those that could not run.
    pub tally: Tally,
    /// Plots that could not be drawn and similar.
    pub warnings: Vec<String>,
}

/// Merges shard folders of one study into `out_dir`. Every shard must hold the same
/// `plan.json`; every case must have a record in one of them (the first result is taken, or
/// else the first record of a case that could not run).
pub fn merge_shards(shard_dirs: &[PathBuf], out_dir: &Path) -> Result<MergeReport, StudyError> {
    let Some(first) = shard_dirs.first() else {
        return Err(StudyError::NotASweep {
            dir: out_dir.to_path_buf(),
            reason: "no shard folder to merge".into(),
        });
    };
    let layout = read_layout(first)?;
    for dir in &shard_dirs[1..] {
        if read_layout(dir)? != layout {
            return Err(StudyError::NotASweep {
                dir: dir.clone(),
                reason: format!(
                    "its plan.json differs from {}'s: another study",
                    first.display()
                ),
            });
        }
    }
    claim_folder(&layout, out_dir)?;
    let mut missing = Vec::new();
    for index in 0..layout.cases.len() {
        let record_in = |dir: &&PathBuf, result: bool| {
            read_record(&case_folder(dir, index))
                .is_some_and(|r| layout.is_record_of(index, &r) && (r.is_final() || !result))
        };
        let holder = (shard_dirs.iter().find(|dir| record_in(dir, true)))
            .or_else(|| shard_dirs.iter().find(|dir| record_in(dir, false)));
        match holder {
            Some(dir) => copy_case(&case_folder(dir, index), &case_folder(out_dir, index))?,
            None => missing.push(index),
        }
    }
    if !missing.is_empty() {
        return Err(StudyError::Incomplete {
            dir: out_dir.to_path_buf(),
            missing,
        });
    }
    let indices: Vec<usize> = (0..layout.cases.len()).collect();
    let records = outputs::read_records(&layout, out_dir, &indices)?;
    let warnings = outputs::write(&layout, &records, out_dir, true)?;
    Ok(MergeReport {
        cases: records.len(),
        tally: Tally::of(&records),
        warnings,
    })
}

/// Copies a case folder (and its subfolders) over `to`, unless both are the same folder.
fn copy_case(from: &Path, to: &Path) -> Result<(), StudyError> {
    let same = from
        .canonicalize()
        .ok()
        .zip(to.canonicalize().ok())
        .is_some_and(|(a, b)| a == b);
    if same {
        return Ok(());
    }
    let _ = std::fs::remove_dir_all(to);
    // The record goes last: a merge stopped midway leaves no case that looks complete.
    copy_tree(from, to, Some(RECORD_FILE))
        .and_then(|()| std::fs::copy(from.join(RECORD_FILE), to.join(RECORD_FILE)).map(drop))
        .map_err(|source| StudyError::Io {
            path: to.to_path_buf(),
            source,
        })
}

/// Copies a folder's files and subfolders, but for the file named `skip` at its top.
fn copy_tree(from: &Path, to: &Path, skip: Option<&str>) -> std::io::Result<()> {
    std::fs::create_dir_all(to)?;
    for entry in std::fs::read_dir(from)? {
        let entry = entry?;
        let target = to.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            copy_tree(&entry.path(), &target, None)?;
        } else if skip.is_none_or(|name| entry.file_name() != name) {
            std::fs::copy(entry.path(), target)?;
        }
    }
    Ok(())
}
