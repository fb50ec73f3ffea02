//! Studies (`wingman sweep`): many runs of one scenario over axes of scenario keys, full
//! factorial or zipped, replicated over `run.seed`, each case into its own folder, with one
//! `results.csv` and plots; or the apparent-size study (seed 8.2), one rendered frame per
//! relative orientation and range.
//!
//! - [`spec`]: the study file's schema; [`plan`]: its cases, validated before anything runs,
//!   and the shards; [`setting`]: one key a case sets; [`layout`]: `plan.json`, what the
//!   results are made of.
//! - [`run`]: the cases in parallel, resumable; [`workers`]: what each worker keeps across
//!   cases; [`apparent_size`] and [`view`]: the apparent-size case.
//! - [`results`]: a case's record and `results.csv`; [`outputs`]: the sweep folder;
//!   [`plots`]; [`merge`]: shards into one folder.

pub mod apparent_size;
pub mod layout;
pub mod merge;
pub mod outputs;
pub mod plan;
pub mod plots;
pub mod results;
pub mod run;
pub mod setting;
pub mod spec;
pub mod view;
pub mod workers;

pub use merge::{MergeReport, merge_shards};
pub use plan::{Plan, Shard};
pub use run::{Progress, SweepOptions, SweepReport, run_sweep};

use std::path::PathBuf;

/// Why a study could not run. [`StudyError::is_bad_input`] tells a bad study file or folder
/// (exit code 2) from a failure to write (exit code 1).
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// The study file could not be read.
    #[error("{}: cannot read study file: {source}", path.display())]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The study file's schema, axes or fixed overrides are wrong.
    #[error("{}: bad study file: {reason}", path.display())]
    Invalid {
        /// The study file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// A value of an axis makes a bad scenario.
    #[error("{}: bad study file: axis `{axis}`, value {value}: {reason}", path.display())]
    BadValue {
        /// The study file.
        path: PathBuf,
        /// The axis.
        axis: String,
        /// The value, as written.
        value: String,
        /// The scenario loader's message.
        reason: String,
    },
    /// A combination of values makes a bad scenario (each value alone is fine).
    #[error("{}: bad study file: case {case} ({settings}): {reason}", path.display())]
    BadCase {
        /// The study file.
        path: PathBuf,
        /// The case's index.
        case: usize,
        /// Its settings.
        settings: String,
        /// The scenario loader's message.
        reason: String,
    },
    /// The output folder holds another study's results.
    #[error(
        "{}: holds the results of another study (or of this one before its study or scenario \
         file changed); choose another --out or remove it",
        out_dir.display()
    )]
    OtherStudy {
        /// The folder.
        out_dir: PathBuf,
    },
    /// The output folder holds files, but no sweep's `plan.json`.
    #[error(
        "--out {}: the folder is not empty and holds no sweep (no plan.json of one): choose \
         an empty or new folder, or this study's folder",
        out_dir.display()
    )]
    NotThisStudy {
        /// The folder.
        out_dir: PathBuf,
    },
    /// The output folder cannot be made or written (a file, no permission).
    #[error(transparent)]
    OutFolder(crate::output::folder::FolderError),
    /// A folder given to merge is not a sweep folder of the same study.
    #[error("{}: not a shard of this sweep: {reason}", dir.display())]
    NotASweep {
        /// The folder.
        dir: PathBuf,
        /// Why.
        reason: String,
    },
    /// Cases have no complete record (a shard that did not finish).
    #[error(
        "{}: {} case(s) have no results (first: {}); rerun the sweep or shard that holds them",
        dir.display(),
        missing.len(),
        missing.iter().take(10).map(|i| i.to_string()).collect::<Vec<_>>().join(", ")
    )]
    Incomplete {
        /// The folder.
        dir: PathBuf,
        /// The indices of the cases missing.
        missing: Vec<usize>,
    },
    /// The worker threads could not be started.
    #[error("cannot start the worker threads: {0}")]
    Threads(String),
    /// A file could not be written.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// `results.csv` or a case record could not be written.
    #[error(transparent)]
    Results(#[from] results::ResultsError),
}

impl StudyError {
    /// Whether the study file, a folder given or an argument is at fault (exit code 2).
    pub fn is_bad_input(&self) -> bool {
        matches!(
            self,
            Self::Unreadable { .. }
                | Self::Invalid { .. }
                | Self::BadValue { .. }
                | Self::BadCase { .. }
                | Self::OtherStudy { .. }
                | Self::NotThisStudy { .. }
                | Self::OutFolder(_)
                | Self::NotASweep { .. }
        )
    }
}
