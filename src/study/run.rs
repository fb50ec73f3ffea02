//! Running a study's cases: in parallel on a rayon pool, each into its own folder, skipping
//! the cases a previous run completed (its results; a case that could not run is run again),
//! with progress (cases done by status, time left).
//!
//! Camera cases render on one GPU device per worker thread, opened at its first camera case
//! and kept in [`super::workers`]: the fastest of the three ways `examples/sweep_gpu_sharing.rs`
//! compares (docs/findings.md, Measurements behind the code and tests).

use super::layout::StudyLayout;
use super::plan::{Case, Plan, Shard};
use super::results::{
    CaseRecord, Column, FAILED, Tally, count_statuses, read_record, summary_columns, write_record,
};
use super::spec::StudyKind;
use super::workers::Workers;
use super::{StudyError, outputs};
use crate::output::group::{load_checked, run_group_to_directory};
use crate::output::run_to_directory_on;
use crate::output::summary::RunStatus;
use crate::render::GpuContext;
use crate::scenario::group::GroupScenario;
use crate::scenario::{Scenario, SensorMode};
use rayon::prelude::*;
use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};
use std::time::Instant;

/// How a sweep reports its progress.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Progress {
    /// A progress bar (on a terminal).
    Bar,
    /// A line per finished case (logs of a batch job).
    Lines,
    /// Nothing.
    Quiet,
}

/// How to run a study.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// The sweep's folder.
    pub out_dir: PathBuf,
    /// Worker threads.
    pub jobs: usize,
    /// Only this part of the cases (all without one).
    pub shard: Option<Shard>,
    /// Progress reports.
    pub progress: Progress,
}

/// What a sweep did.
#[derive(Debug, Clone, Default)]
pub struct SweepReport {
    /// Cases of this run (or shard).
    pub cases: usize,
    /// Cases complete from an earlier run, skipped.
    pub skipped: usize,
    /// The cases by status, and those that could not run.
    pub tally: Tally,
    /// Plots that could not be drawn and similar.
    pub warnings: Vec<String>,
}

/// The name of a sweep's worker threads, before their index.
pub const SWEEP_THREAD_PREFIX: &str = "sweep-worker-";

/// Runs the plan's cases (of `options.shard`) that `options.out_dir` does not hold complete,
/// then writes `results.csv` and, for a whole study, the plots.
pub fn run_sweep(plan: &Plan, options: &SweepOptions) -> Result<SweepReport, StudyError> {
    outputs::claim_folder(&plan.layout, &options.out_dir)?;
    let cases: Vec<&Case> = plan.cases_of(options.shard).collect();
    let complete = |c: &&Case| {
        read_record(&outputs::case_folder(&options.out_dir, c.index))
            .is_some_and(|r| plan.layout.is_record_of(c.index, &r) && r.is_final())
    };
    let pending: Vec<&Case> = cases.iter().copied().filter(|c| !complete(c)).collect();
    let skipped = cases.len() - pending.len();
    if options.progress != Progress::Quiet && skipped > 0 {
        eprintln!(
            "{}: {skipped} of {} cases already complete in {}; running the other {}",
            plan.layout.study,
            cases.len(),
            options.out_dir.display(),
            pending.len()
        );
    }
    let tracker = Tracker::new(pending.len(), options.progress);
    let workers = Workers::new(options.jobs);
    let run_pending = |pool: &rayon::ThreadPool| -> Vec<Result<(), StudyError>> {
        pool.install(|| {
            pending
                .par_iter()
                .map(|case| {
                    let dir = outputs::case_folder(&options.out_dir, case.index);
                    let record = run_case_or_crash(plan, case, &dir, &workers);
                    tracker.finished(case, &record);
                    write_record(&dir, &record).map_err(StudyError::from)
                })
                .collect()
        })
    };
    // A scoped pool joins its threads before it returns, before the workers' devices are
    // dropped: a worker thread that exited after its device's driver had been unloaded (the
    // last device dropped) ran the driver's thread-exit hooks in unmapped code, a
    // segmentation fault at the end of a 16-worker sweep on NVIDIA's Vulkan driver.
    let written = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.max(1))
        .thread_name(|index| format!("{SWEEP_THREAD_PREFIX}{index}"))
        .build_scoped(rayon::ThreadBuilder::run, run_pending)
        .map_err(|e| StudyError::Threads(e.to_string()))?;
    tracker.close();
    drop(workers);
    written.into_iter().collect::<Result<(), _>>()?;
    let indices: Vec<usize> = cases.iter().map(|c| c.index).collect();
    let records = outputs::read_records(&plan.layout, &options.out_dir, &indices)?;
    let warnings = outputs::write(
        &plan.layout,
        &records,
        &options.out_dir,
        options.shard.is_none(),
    )?;
    Ok(SweepReport {
        cases: records.len(),
        skipped,
        tally: Tally::of(&records),
        warnings,
    })
}

/// [`run_case`], with a case that panics recorded as [`FAILED`] (the panic's message printed
/// by Rust's hook) rather than ending the sweep.
fn run_case_or_crash(plan: &Plan, case: &Case, dir: &Path, workers: &Workers) -> CaseRecord {
    std::panic::catch_unwind(AssertUnwindSafe(|| run_case(plan, case, dir, workers)))
        .unwrap_or_else(|panic| {
            let why = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            let mut record = blank_record(case);
            record.message = Some(format!("the case crashed: {why}"));
            record
        })
}

/// A case's record before it runs: status [`FAILED`], no numbers.
fn blank_record(case: &Case) -> CaseRecord {
    CaseRecord {
        case: case.index,
        point: case.point,
        replicate: case.replicate,
        settings: case.cells(),
        status: FAILED.into(),
        message: None,
        columns: vec![],
    }
}

/// Runs one case into `dir` (emptied first) and returns its record; a case that cannot start
/// or that diverges is a record with its status, never an error.
fn run_case(plan: &Plan, case: &Case, dir: &Path, workers: &Workers) -> CaseRecord {
    let _ = std::fs::remove_dir_all(dir);
    let mut record = blank_record(case);
    if let Err(e) = std::fs::create_dir_all(dir) {
        record.message = Some(format!("cannot create {}: {e}", dir.display()));
        return record;
    }
    let overrides = case.scenario_overrides(&plan.set);
    let outcome = match plan.kind {
        StudyKind::Sweep => load_case(plan, &overrides).map(|flown| match flown {
            CaseScenario::Group(group) => run_group(&group, &plan.layout.study, dir, workers),
            CaseScenario::Pair(scenario) => run_scenario(&plan.layout, &scenario, dir, workers),
        }),
        StudyKind::ApparentSize => Scenario::load(&plan.scenario_path, &overrides)
            .map_err(|e| e.to_string())
            .and_then(|scenario| workers.measure_view(overrides, scenario, case, dir))
            .map(|columns| ("completed".to_string(), None, columns)),
    };
    match outcome {
        Ok((status, message, columns)) => {
            record.status = status;
            record.message = message;
            record.columns = columns;
        }
        Err(message) => record.message = Some(message),
    }
    record
}

/// What a sweep case flies.
pub enum CaseScenario {
    /// A group scenario (`[group]`).
    Group(GroupScenario),
    /// A single pair.
    Pair(Box<Scenario>),
}

impl CaseScenario {
    /// Every follower's scenario (the pair's alone for a pair).
    pub fn scenarios(&self) -> Vec<&Scenario> {
        match self {
            Self::Group(group) => group.followers.iter().map(|f| &f.scenario).collect(),
            Self::Pair(scenario) => vec![scenario.as_ref()],
        }
    }
}

/// The scenario a sweep case with `overrides` flies; the error line when it does not load.
pub fn load_case(plan: &Plan, overrides: &[String]) -> Result<CaseScenario, String> {
    match load_checked(&plan.scenario_path, overrides) {
        Ok(Some(group)) => Ok(CaseScenario::Group(group)),
        Ok(None) => Scenario::load(&plan.scenario_path, overrides)
            .map(|scenario| CaseScenario::Pair(Box::new(scenario)))
            .map_err(|e| e.to_string()),
        Err(e) => Err(e.to_string()),
    }
}

/// A sweep case of a group scenario (`[group]`): the group's run into `dir`, named `name` (the
/// study's, as a pair's case is), on the worker's device; its status is the first stopped
/// follower's (`completed` when none stopped), its numbers every follower's summary's, each
/// named after the follower (`f1.b_hat_final_ft`), and the group's `duration_s`, `wall_s` and
/// `realtime_factor`.
fn run_group(
    group: &GroupScenario,
    name: &str,
    dir: &Path,
    workers: &Workers,
) -> (String, Option<String>, Vec<Column>) {
    let ran = workers.with_gpu(|gpu| match gpu {
        Ok(gpu) => {
            run_group_to_directory(group, name, dir, Some(gpu), |_| {}).map_err(|e| e.to_string())
        }
        Err(message) => Err(message.to_string()),
    });
    let summary = match ran {
        Ok(summary) => summary,
        Err(message) => return (FAILED.into(), Some(message), vec![]),
    };
    let mut columns: Vec<Column> = vec![
        ("duration_s".into(), summary.duration_s.into()),
        ("wall_s".into(), summary.wall_s.into()),
        ("realtime_factor".into(), summary.realtime_factor.into()),
    ];
    let status = (summary.followers.iter())
        .map(|f| f.status)
        .find(|s| *s != RunStatus::Completed)
        .unwrap_or(RunStatus::Completed);
    for follower in &summary.followers {
        let own = std::fs::read_to_string(dir.join(&follower.name).join("summary.json"))
            .ok()
            .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok());
        let Some(own) = own else { continue };
        let prefixed = summary_columns(&own)
            .into_iter()
            .map(|(column, value)| (format!("{}.{column}", follower.name), value));
        columns.extend(prefixed);
    }
    (status.name().to_string(), summary.stopped_by, columns)
}

/// A sweep case: `wingman run` into `dir`; the status, message and numbers of the summary it
/// wrote (`failed` and the error when it wrote none).
fn run_scenario(
    layout: &StudyLayout,
    scenario: &Scenario,
    dir: &Path,
    workers: &Workers,
) -> (String, Option<String>, Vec<Column>) {
    let run =
        |gpu: Option<&GpuContext>| run_to_directory_on(scenario, &layout.study, dir, gpu, |_| {});
    let result = if scenario.sensor.mode == SensorMode::Camera {
        workers.with_gpu(|gpu| match gpu {
            Ok(gpu) => run(Some(gpu)).map(|_| ()).map_err(|e| e.to_string()),
            Err(message) => Err(message.to_string()),
        })
    } else {
        run(None).map(|_| ()).map_err(|e| e.to_string())
    };
    let summary = std::fs::read_to_string(dir.join("summary.json"))
        .ok()
        .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok());
    match summary {
        Some(summary) => {
            let status = summary["status"].as_str().unwrap_or(FAILED).to_string();
            let message = summary["message"]
                .as_str()
                .map(str::to_string)
                .or(result.err());
            (status, message, summary_columns(&summary))
        }
        None => (FAILED.into(), result.err(), vec![]),
    }
}

/// Counts finished cases by status and shows them, with the status names of `results.csv`.
struct Tracker {
    bar: Option<indicatif::ProgressBar>,
    lines: bool,
    total: usize,
    statuses: Mutex<Vec<String>>,
    started: Instant,
}

impl Tracker {
    fn new(total: usize, progress: Progress) -> Self {
        let bar = (progress == Progress::Bar && total > 0).then(|| {
            let bar = indicatif::ProgressBar::new(total as u64);
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "[{bar:30}] {pos}/{len} cases ({msg}), {eta} left",
                )
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
            bar.set_message(count_statuses([]));
            bar
        });
        Self {
            bar,
            lines: progress == Progress::Lines,
            total,
            statuses: Mutex::default(),
            started: Instant::now(),
        }
    }

    fn finished(&self, case: &Case, record: &CaseRecord) {
        let (done, counts) = {
            let mut statuses = self.statuses.lock().unwrap_or_else(PoisonError::into_inner);
            statuses.push(record.status.clone());
            let counts = count_statuses(statuses.iter().map(String::as_str));
            (statuses.len(), counts)
        };
        if let Some(bar) = &self.bar {
            bar.set_message(counts);
            bar.inc(1);
        } else if self.lines {
            let elapsed_s = self.started.elapsed().as_secs_f64();
            let left_s = elapsed_s / done as f64 * (self.total - done) as f64;
            eprintln!(
                "case {} {}: {done}/{} done ({counts}), about {left_s:.0} s left",
                case.index, record.status, self.total
            );
        }
    }

    fn close(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
