//! A run's outputs (DESIGN §4): the resolved scenario, telemetry, summary and plots, and the
//! driver that steps a simulation while writing them.

pub mod aircraft_figures;
pub mod figures;
pub mod frame_images;
pub mod plots;
pub mod summary;
pub mod telemetry;

use crate::render::GpuContext;
use crate::scenario::Scenario;
use crate::sim::{SimError, Simulation, Snapshot, StepOutcome};
use std::path::{Path, PathBuf};
use std::time::Instant;
use summary::Summary;
use telemetry::{TelemetryWriter, row_of};

/// Why a run could not finish.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// An output file could not be written.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The simulation stopped; telemetry up to that point and a summary were written.
    #[error("{0} (telemetry up to that point is in {1})")]
    Sim(Box<SimError>, PathBuf),
}

/// What a finished run reports.
#[derive(Debug, Clone)]
pub struct RunReport {
    /// The summary as written to `summary.json`.
    pub summary: Summary,
    /// Warnings that did not stop the run (e.g. plots that could not be drawn).
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
/// `progress` is called with the fraction done now and then.
pub fn run_to_directory(
    scenario: &Scenario,
    name: &str,
    out_dir: &Path,
    progress: impl FnMut(f64),
) -> Result<RunReport, RunError> {
    run_to_directory_on(scenario, name, out_dir, None, progress)
}

/// Offers the camera's latest frame to the saver; a frame that cannot be saved becomes a
/// warning and ends the saving (the run goes on).
fn save_frame(
    frame_saver: &mut Option<frame_images::FrameSaver>,
    sim: &Simulation,
    warnings: &mut Vec<String>,
) {
    if let (Some(saver), Some(camera)) = (frame_saver.as_mut(), sim.camera())
        && let Err(e) = saver.offer(camera, || {
            frame_images::gimbal_captions(sim.gimbal_reading())
        })
    {
        warnings.push(format!("frame not saved: {e}"));
        *frame_saver = None;
    }
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
    std::fs::create_dir_all(out_dir).map_err(io_error(out_dir))?;
    let scenario_path = out_dir.join("scenario.toml");
    std::fs::write(&scenario_path, scenario.to_toml_string()).map_err(io_error(&scenario_path))?;
    let telemetry_path = out_dir.join("telemetry.csv");
    let mut telemetry =
        TelemetryWriter::create(&telemetry_path).map_err(io_error(&telemetry_path))?;

    let started = Instant::now();
    let mut sim = Simulation::on_gpu(scenario, gpu)
        .map_err(|e| RunError::Sim(Box::new(e), telemetry_path.clone()))?;
    let mut logged: Vec<Snapshot> = Vec::new();
    let log_every = u64::from(scenario.run.log_every);
    let progress_every = (sim.total_ticks() / 100).max(1);
    let mut frame_saver = (scenario.output.frames_every > 0).then(|| {
        frame_images::FrameSaver::new(
            &out_dir.join("frames"),
            scenario.output.frames_every,
            scenario.output.overlay,
        )
    });
    let mut warnings = Vec::new();
    let mut log = |snapshot: Snapshot, telemetry: &mut TelemetryWriter| -> Result<(), RunError> {
        telemetry
            .write(&row_of(&snapshot))
            .map_err(io_error(&telemetry_path))?;
        logged.push(snapshot);
        Ok(())
    };
    log(sim.snapshot(), &mut telemetry)?;
    let failure = loop {
        let outcome = sim.step();
        save_frame(&mut frame_saver, &sim, &mut warnings);
        match outcome {
            Ok(StepOutcome::Running) => {
                if sim.tick().is_multiple_of(log_every) {
                    log(sim.snapshot(), &mut telemetry)?;
                }
                if sim.tick().is_multiple_of(progress_every) {
                    progress(sim.tick() as f64 / sim.total_ticks() as f64);
                }
            }
            Ok(StepOutcome::Finished | StepOutcome::Intercepted { .. }) => {
                log(sim.snapshot(), &mut telemetry)?;
                break None;
            }
            Err(e) => break Some(e),
        }
    };
    telemetry.flush().map_err(io_error(&telemetry_path))?;
    let wall_s = started.elapsed().as_secs_f64();

    let summary = Summary::build(name, &logged, &sim, wall_s, failure.as_ref());
    let summary_path = out_dir.join("summary.json");
    std::fs::write(&summary_path, summary.to_json()).map_err(io_error(&summary_path))?;

    if scenario.output.plots
        && let Err(e) = figures::draw_all(&out_dir.join("plots"), scenario, &logged)
    {
        warnings.push(format!("plots not drawn: {e}"));
    }
    match failure {
        Some(e) => Err(RunError::Sim(Box::new(e), telemetry_path)),
        None => Ok(RunReport {
            summary,
            warnings,
            logged,
        }),
    }
}
