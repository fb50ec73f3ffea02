//! A run's outputs (docs/outputs.md): the resolved scenario, telemetry, summary and plots, and the
//! driver that steps a simulation while writing them.

pub mod aircraft_figures;
pub mod airframe_view;
pub mod columns;
pub mod figure_set;
pub mod figures;
pub mod folder;
pub mod frame_images;
pub mod group;
mod group_plot;
pub mod interrupt;
pub mod live;
pub mod lock;
pub mod outputs_doc;
pub mod plots;
pub mod preflight;
pub mod rerun_export;
pub mod summary;
pub mod telemetry;
pub mod track_check;
pub mod video;
pub mod video_encoders;

use crate::render::GpuContext;
use crate::scenario::Scenario;
use crate::sim::{RunEnd, SimError, Simulation, Snapshot};
use std::path::{Path, PathBuf};
use std::time::Instant;
use summary::{RunStatus, Summary};
use telemetry::{TelemetryWriter, row_of};

/// Why a run could not start or finish.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The simulation could not be set up from the scenario; nothing was written.
    #[error("{0}")]
    Setup(Box<SimError>),
    /// The output folder cannot take the run; nothing was written.
    #[error("{0}")]
    Folder(#[from] folder::FolderError),
    /// An output file could not be written.
    #[error("{}", io_message(path, source))]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The simulation stopped; telemetry up to that point and a summary were written.
    #[error("{} (telemetry up to that point is in {})", .0, .1.display())]
    Sim(Box<SimError>, PathBuf),
}

impl RunError {
    /// Whether the scenario or the command line is to blame (rather than the run or the
    /// machine): a set-up the scenario's values do not allow, or an output folder that
    /// cannot take the run. A machine without a graphics adapter is not the scenario's fault.
    pub fn is_input_error(&self) -> bool {
        match self {
            Self::Setup(e) => !e.is_missing_adapter(),
            Self::Folder(_) => true,
            _ => false,
        }
    }
}

/// An I/O failure in one line: a full disk says so plainly.
fn io_message(path: &Path, source: &std::io::Error) -> String {
    if source.kind() == std::io::ErrorKind::StorageFull {
        format!("no space left on device writing {}", path.display())
    } else {
        format!("cannot write {}: {source}", path.display())
    }
}

/// What the operating system said of a write, in words (a full disk plainly).
pub fn io_reason(source: &std::io::Error) -> String {
    if source.kind() == std::io::ErrorKind::StorageFull {
        "no space left on device".to_string()
    } else {
        source.to_string()
    }
}

/// What a finished run reports.
#[derive(Debug, Clone)]
pub struct RunReport {
    /// The summary as written to `summary.json` (its status says whether the run completed,
    /// intercepted, lost the target or was interrupted).
    pub summary: Summary,
    /// Warnings that did not stop the run (e.g. frames that could not be saved).
    pub warnings: Vec<String>,
    /// Every logged snapshot, as written to `telemetry.csv`.
    pub logged: Vec<Snapshot>,
}

fn io_error(path: &Path) -> impl Fn(std::io::Error) -> RunError + '_ {
    move |source| RunError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Runs `scenario` (named `name` in the summary) and writes every output into `out_dir`.
/// The simulation is set up before anything is written, and an earlier run's files in
/// `out_dir` are cleared (see [`folder`]). `progress` is called with the fraction done now and
/// then. The run stops early when a state diverges (an error), when the target has gone
/// unmeasured longer than `run.stop_after_lost_s` (status `lost`) and when a stop is asked
/// for ([`interrupt`], status `interrupted`); telemetry, summary and plots are written in
/// every case.
pub fn run_to_directory(
    scenario: &Scenario,
    name: &str,
    out_dir: &Path,
    progress: impl FnMut(f64),
) -> Result<RunReport, RunError> {
    run_to_directory_on(scenario, name, out_dir, None, progress)
}

/// [`run_to_directory`], with a camera rendering on `gpu` when given (a device shared by the
/// runs of a sweep) and on a device of its own otherwise.
pub fn run_to_directory_on(
    scenario: &Scenario,
    name: &str,
    out_dir: &Path,
    gpu: Option<&GpuContext>,
    mut progress: impl FnMut(f64),
) -> Result<RunReport, RunError> {
    folder::check(out_dir)?;
    let started = Instant::now();
    let mut sim = Simulation::on_gpu(scenario, gpu).map_err(|e| RunError::Setup(Box::new(e)))?;
    // Held until the last file is written: a second run into the folder is refused.
    let _lock = lock::lock(out_dir).map_err(folder::FolderError::from)?;
    folder::prepare(out_dir)?;
    folder::mark(out_dir)?;
    // The summary's space is taken first: on a disk that fills up it is what remains.
    let reserve_path = out_dir.join(SUMMARY_FILE).with_extension("json.partial");
    std::fs::write(&reserve_path, vec![b' '; SUMMARY_RESERVE_BYTES])
        .map_err(io_error(&reserve_path))?;
    let scenario_path = out_dir.join("scenario.toml");
    std::fs::write(&scenario_path, scenario.to_toml_string()).map_err(io_error(&scenario_path))?;
    let telemetry_path = out_dir.join("telemetry.csv");
    let mut recorder = Recorder {
        telemetry: Some(
            TelemetryWriter::create(&telemetry_path).map_err(io_error(&telemetry_path))?,
        ),
        telemetry_path: telemetry_path.clone(),
        logged: Vec::new(),
        warnings: Vec::new(),
        unwritten: Vec::new(),
        frame_saver: (scenario.output.frames_every > 0).then(|| {
            frame_images::FrameSaver::new(
                &out_dir.join("frames"),
                scenario.output.frames_every,
                scenario.output.overlay,
            )
        }),
    };
    recorder.log(sim.snapshot());
    let end = step_to_end(&mut sim, &mut recorder, &mut progress);
    recorder.finish_telemetry();
    let wall_s = started.elapsed().as_secs_f64();
    let stopped = stopped_status(&end, &sim);
    let mut summary = Summary::build(name, &recorder.logged, &sim, wall_s, stopped);
    summary.unwritten = std::mem::take(&mut recorder.unwritten);
    write_outputs_after_telemetry(out_dir, scenario, &recorder.logged, &mut summary)
        .map_err(io_error(&out_dir.join(SUMMARY_FILE)))?;
    match end {
        RunEnd::Failed(e) => Err(RunError::Sim(Box::new(e), telemetry_path)),
        _ => Ok(RunReport {
            summary,
            warnings: recorder.warnings,
            logged: recorder.logged,
        }),
    }
}

/// The summary's file in a run's folder.
const SUMMARY_FILE: &str = "summary.json";
/// Space kept for the summary from the start of the run, bytes (a summary takes 2-8 KB).
const SUMMARY_RESERVE_BYTES: usize = 64 * 1024;

/// Writes the summary (small, so first: on a full disk it is what remains), then the plots;
/// a plot that cannot be written is named in the summary's `unwritten`, written again. Fails
/// only when the first summary cannot be written.
fn write_outputs_after_telemetry(
    out_dir: &Path,
    scenario: &Scenario,
    logged: &[Snapshot],
    summary: &mut Summary,
) -> std::io::Result<()> {
    let summary_path = out_dir.join(SUMMARY_FILE);
    write_whole(&summary_path, &summary.to_json())?;
    if !scenario.output.plots {
        return Ok(());
    }
    if let Err(e) = figures::draw_all(&out_dir.join("plots"), scenario, logged) {
        summary
            .unwritten
            .push(format!("plots (none after this one): {e}"));
        if let Err(e) = write_whole(&summary_path, &summary.to_json()) {
            let reason = io_reason(&e);
            summary
                .unwritten
                .push(format!("{SUMMARY_FILE} naming the plot: {reason}"));
        }
    }
    Ok(())
}

/// Writes `text` into `path` whole or not at all: into the file beside it (the space
/// reserved at the start, when it is there) cut to the text's length, then renamed over
/// `path` (a full disk leaves the earlier file, never a cut-off one).
fn write_whole(path: &Path, text: &str) -> std::io::Result<()> {
    use std::io::Write;
    let partial = path.with_extension("json.partial");
    std::fs::OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(false)
        .open(&partial)
        .and_then(|mut file| {
            file.write_all(text.as_bytes())?;
            file.set_len(text.len() as u64)
        })
        .and_then(|()| std::fs::rename(&partial, path))
        .inspect_err(|_| {
            let _ = std::fs::remove_file(&partial);
        })
}

/// Why a lost run stopped.
fn lost_message(sim: &Simulation, since_s: f64) -> String {
    format!(
        "target lost: unmeasured from t = {since_s:.3} s to t = {:.3} s, longer than \
         run.stop_after_lost_s = {} s",
        sim.time_s(),
        sim.scenario().run.stop_after_lost_s
    )
}

/// Why a run that tracked something other than the target stopped.
fn false_lock_message(sim: &Simulation, since_s: f64) -> String {
    format!(
        "false lock: every frame from t = {since_s:.3} s to t = {:.3} s measured something \
         other than the target, longer than run.stop_after_lost_s = {} s",
        sim.time_s(),
        sim.scenario().run.stop_after_lost_s
    )
}

/// What the run writes as it goes: telemetry rows (kept for the summary and plots) and
/// saved frames. A telemetry file the disk stops taking is closed with the whole rows it
/// holds, and the run goes on (its summary and plots come from the rows kept in memory).
struct Recorder {
    telemetry: Option<TelemetryWriter>,
    telemetry_path: PathBuf,
    logged: Vec<Snapshot>,
    warnings: Vec<String>,
    /// The outputs that could not be written, each `file: reason`.
    unwritten: Vec<String>,
    frame_saver: Option<frame_images::FrameSaver>,
}

impl Recorder {
    fn log(&mut self, snapshot: Snapshot) {
        if let Some(writer) = self.telemetry.as_mut()
            && let Err(e) = writer.write(&row_of(&snapshot))
        {
            self.telemetry_failed(&e, snapshot.t_s);
        }
        self.logged.push(snapshot);
    }

    /// Writes the rows still held back.
    fn finish_telemetry(&mut self) {
        let t_s = self.logged.last().map_or(0.0, |s| s.t_s);
        if let Some(Err(e)) = self.telemetry.as_mut().map(|w| w.flush()) {
            self.telemetry_failed(&e, t_s);
        }
    }

    fn telemetry_failed(&mut self, error: &std::io::Error, t_s: f64) {
        let name = self.telemetry_path.file_name().unwrap_or_default();
        self.unwritten.push(format!(
            "{}: {} at t = {t_s:.3} s (the rows before are whole)",
            name.to_string_lossy(),
            io_reason(error)
        ));
        self.telemetry = None;
    }

    /// Saves the camera's latest frame when it is one to keep; a failure to save is a
    /// warning, and no frame is offered after it.
    fn save_frame(&mut self, sim: &Simulation) {
        if let (Some(saver), Some(camera)) = (self.frame_saver.as_mut(), sim.camera())
            && let Err(e) = saver.offer(camera, || {
                frame_images::gimbal_captions(sim.gimbal_reading())
            })
        {
            self.warnings.push(format!("frame not saved: {e}"));
            self.frame_saver = None;
        }
    }
}

/// The status and message of a run that ended early (`None` for one that finished).
pub fn stopped_status(end: &RunEnd, sim: &Simulation) -> Option<(RunStatus, String)> {
    Some(match end {
        RunEnd::Finished => return None,
        RunEnd::Failed(e) => (RunStatus::Diverged, e.to_string()),
        RunEnd::Lost { since_s } => (RunStatus::Lost, lost_message(sim, *since_s)),
        RunEnd::FalseLock { since_s } => (RunStatus::FalseLock, false_lock_message(sim, *since_s)),
        RunEnd::Interrupted => (RunStatus::Interrupted, "interrupted (Ctrl-C)".to_string()),
    })
}

/// Steps `sim` to its end through [`Simulation::run_tick`], logging what it gives and saving
/// frames; returns why it ended.
fn step_to_end(
    sim: &mut Simulation,
    recorder: &mut Recorder,
    progress: &mut impl FnMut(f64),
) -> RunEnd {
    let progress_every = (sim.total_ticks() / 1000).max(1);
    loop {
        let tick = sim.run_tick(interrupt::requested);
        recorder.save_frame(sim);
        if let Some(snapshot) = tick.logged {
            recorder.log(snapshot);
        }
        if let Some(end) = tick.end {
            return end;
        }
        if sim.tick().is_multiple_of(progress_every) {
            progress(sim.tick() as f64 / sim.total_ticks() as f64);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A full disk is said plainly, in one line.
    #[test]
    fn full_disk_is_said_plainly() {
        let e = RunError::Io {
            path: PathBuf::from("runs/x/telemetry.csv"),
            source: std::io::ErrorKind::StorageFull.into(),
        };
        assert_eq!(
            e.to_string(),
            "no space left on device writing runs/x/telemetry.csv"
        );
    }

    /// A plot that cannot be written is named in the summary, which was written before it
    /// and is written again; the run itself is not lost.
    #[test]
    fn failed_plots_are_named_in_the_summary() {
        let dir = tempfile::tempdir().expect("temp dir");
        // A file where the plots' folder goes.
        std::fs::write(dir.path().join("plots"), "in the way").expect("file");
        std::fs::write(
            dir.path().join("summary.json"),
            r#"{"scenario": "x", "status": "completed", "steps": 0, "duration_s": 0}"#,
        )
        .expect("an earlier run");
        let scenario =
            Scenario::from_toml_str("[run]\nduration_s = 0.1\n", Path::new("s.toml"), &[])
                .expect("valid");
        let report = run_to_directory(&scenario, "s", dir.path(), |_| {}).expect("ran");
        assert_eq!(
            report.summary.unwritten.len(),
            1,
            "{:?}",
            report.summary.unwritten
        );
        assert!(report.summary.unwritten[0].starts_with("plots"));
        let written = std::fs::read_to_string(dir.path().join("summary.json")).expect("summary");
        assert!(written.contains("plots (none after this one)"), "{written}");
        assert!(!dir.path().join("summary.json.partial").exists());
    }
}
