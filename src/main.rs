//! `wingman` command line: parse, call the library, map errors to exit codes
//! (0 success, 2 bad scenario, study file or argument, 1 failed run or write).

use clap::{Parser, Subcommand};
use std::io::IsTerminal;
use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;
use wingman::output::frame_images::render_frame_at;
use wingman::output::rerun_export::export_rerun;
use wingman::output::summary::{RunStatus, Summary};
use wingman::output::video::export_video;
use wingman::output::video_encoders::Encoder;
use wingman::output::{RunReport, folder, interrupt, preflight, run_to_directory};
use wingman::scenario::Scenario;
use wingman::study::results::Tally;
use wingman::study::run::load_case;
use wingman::study::{Plan, Progress, Shard, StudyError, SweepOptions, merge_shards, run_sweep};

#[derive(Parser)]
#[command(
    name = "wingman",
    version,
    about = "Vision-in-the-loop aerial tracking simulator"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scenario and write telemetry, summary and plots.
    Run {
        /// Scenario file (TOML).
        scenario: PathBuf,
        /// Output directory (default: runs/<scenario stem>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Override a scenario value: section.key=value (repeatable).
        #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
        overrides: Vec<String>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Render the follower camera's view at one instant of a scenario, with the measurement
    /// (status colour) and the truth (projected mesh) drawn on it.
    Render {
        /// Scenario file (TOML).
        scenario: PathBuf,
        /// Time of the frame, s.
        #[arg(long = "at", value_name = "T_S")]
        at_s: f64,
        /// Output PNG (default: runs/<scenario stem>/frame_<T>.png).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Override a scenario value: section.key=value (repeatable).
        #[arg(long = "set", value_name = "SECTION.KEY=VALUE")]
        overrides: Vec<String>,
    },
    /// Run a study (many runs over axes of scenario keys, or the apparent-size study) and
    /// write one folder per case, results.csv and plots; `sweep merge` combines shards.
    #[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
    Sweep {
        #[command(subcommand)]
        merge: Option<SweepCommand>,
        /// Study file (TOML).
        #[arg(required = true)]
        study: Option<PathBuf>,
        /// Output directory (default: runs/<study stem>, or runs/<study stem>-shard-I-of-N).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Cases run at once (default: the number of cores).
        #[arg(long)]
        jobs: Option<NonZeroUsize>,
        /// Run only shard I of N (0 <= I < N): the cases whose index is I modulo N.
        #[arg(long, value_name = "I/N")]
        shard: Option<Shard>,
        /// No progress output.
        #[arg(long)]
        quiet: bool,
    },
    /// Turn a finished run folder into something to watch: a video of its saved frames, or
    /// a Rerun recording (docs/viewer.md).
    Export {
        #[command(subcommand)]
        what: ExportCommand,
    },
}

#[derive(Subcommand)]
enum ExportCommand {
    /// The saved frames (frames/*.png) as a video at the camera's rate, captioned with time
    /// and track status: MP4 through ffmpeg when it is on the PATH, an animated PNG otherwise.
    Video {
        /// A run folder (written by `wingman run`).
        run_dir: PathBuf,
        /// The video file (default: RUN_DIR/video.mp4, or RUN_DIR/video.apng without ffmpeg).
        #[arg(long)]
        out: Option<PathBuf>,
        /// auto (ffmpeg when on the PATH, else apng), ffmpeg or apng.
        #[arg(long, value_enum, default_value = "auto")]
        encoder: EncoderArg,
    },
    /// The run as a Rerun recording (frames with the measurement, the 3-D scene, the time
    /// series), written by the Python package (`python -m wingman.rerun`); open it with
    /// `rerun FILE.rrd`.
    Rerun {
        /// A run folder (written by `wingman run`).
        run_dir: PathBuf,
        /// The recording (.rrd).
        #[arg(long)]
        out: PathBuf,
    },
}

/// `--encoder` of `export video`.
#[derive(Clone, Copy, clap::ValueEnum)]
enum EncoderArg {
    Auto,
    Ffmpeg,
    Apng,
}

#[derive(Subcommand)]
enum SweepCommand {
    /// Combine the folders of a sweep's shards into the folder one machine would write.
    Merge {
        /// Shard folders (each written by `wingman sweep STUDY --shard I/N`).
        #[arg(required = true)]
        shards: Vec<PathBuf>,
        /// The merged sweep's folder.
        #[arg(long)]
        out: PathBuf,
    },
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scenario".to_string())
}

fn main() -> ExitCode {
    quiet_mesa_runtime_dir();
    let cli = Cli::parse();
    match cli.command {
        Command::Run {
            scenario,
            out,
            overrides,
            quiet,
        } => run(&scenario, out, &overrides, quiet),
        Command::Render {
            scenario,
            at_s,
            out,
            overrides,
        } => render(&scenario, at_s, out, &overrides),
        Command::Sweep {
            merge: Some(SweepCommand::Merge { shards, out }),
            ..
        } => merge(&shards, &out),
        Command::Sweep {
            study,
            out,
            jobs,
            shard,
            quiet,
            ..
        } => match study {
            Some(study) => sweep(&study, out, jobs, shard, quiet),
            None => ExitCode::from(2),
        },
        Command::Export { what } => export(what),
    }
}

/// `wingman export video|rerun`: exit code 2 for a bad argument, 1 when the encoder or the
/// Python package failed or is missing.
fn export(what: ExportCommand) -> ExitCode {
    let (result, bad_input) = match what {
        ExportCommand::Video {
            run_dir,
            out,
            encoder,
        } => {
            let encoder = match encoder {
                EncoderArg::Auto => Encoder::Auto,
                EncoderArg::Ffmpeg => Encoder::Ffmpeg,
                EncoderArg::Apng => Encoder::Apng,
            };
            match export_video(&run_dir, out.as_deref(), encoder) {
                Ok(videos) => {
                    for v in videos {
                        eprintln!(
                            "video: {}: {} frames of {}x{} px at {} fps, encoded by {}",
                            v.path.display(),
                            v.frames,
                            v.width_px,
                            v.height_px,
                            v.fps,
                            v.encoder
                        );
                    }
                    return ExitCode::SUCCESS;
                }
                Err(e) => (e.to_string(), e.is_bad_input()),
            }
        }
        ExportCommand::Rerun { run_dir, out } => match export_rerun(&run_dir, &out) {
            Ok(()) => return ExitCode::SUCCESS,
            Err(e) => (e.to_string(), e.is_bad_input()),
        },
    };
    eprintln!("error: {result}");
    ExitCode::from(if bad_input { 2 } else { 1 })
}

/// Exit code 2 for a bad study file or folder, 1 for a failure to write.
fn study_failure(e: &StudyError) -> ExitCode {
    eprintln!("error: {e}");
    ExitCode::from(if e.is_bad_input() { 2 } else { 1 })
}

fn sweep(
    path: &Path,
    out: Option<PathBuf>,
    jobs: Option<NonZeroUsize>,
    shard: Option<Shard>,
    quiet: bool,
) -> ExitCode {
    let plan = match Plan::load(path) {
        Ok(plan) => plan,
        Err(e) => return study_failure(&e),
    };
    if plan.kind == wingman::study::spec::StudyKind::Sweep {
        // The cases this process runs (its shard's): whether any of them draws a world.
        let cases: Vec<_> = (plan.cases.iter())
            .filter(|case| shard.is_none_or(|s| s.holds(case.index)))
            .filter_map(|case| load_case(&plan, &case.scenario_overrides(&plan.set)).ok())
            .collect();
        set_lavapipe_threads(&cases.iter().flat_map(|c| c.scenarios()).collect::<Vec<_>>());
    }
    let name = stem(path);
    let out_dir = out.unwrap_or_else(|| match shard {
        Some(s) => PathBuf::from("runs").join(format!("{name}-shard-{}-of-{}", s.index, s.count)),
        None => PathBuf::from("runs").join(&name),
    });
    let jobs = jobs
        .or_else(|| std::thread::available_parallelism().ok())
        .map_or(1, NonZeroUsize::get);
    let progress = match (quiet, std::io::stderr().is_terminal()) {
        (true, _) => Progress::Quiet,
        (false, true) => Progress::Bar,
        (false, false) => Progress::Lines,
    };
    let started = std::time::Instant::now();
    let options = SweepOptions {
        out_dir: out_dir.clone(),
        jobs,
        shard,
        progress,
    };
    match run_sweep(&plan, &options) {
        Ok(report) => {
            for warning in &report.warnings {
                eprintln!("warning: {warning}");
            }
            if !quiet {
                eprintln!(
                    "{name}: {} cases ({} complete before): {}; {:.1} s on {jobs} worker(s); results in {}",
                    report.cases,
                    report.skipped,
                    report.tally.counts,
                    started.elapsed().as_secs_f64(),
                    out_dir.join("results.csv").display()
                );
            }
            not_run_failure(&report.tally, "run the same command again")
        }
        Err(e) => study_failure(&e),
    }
}

/// Exit code 1, with the cases named, when some case could not run (status `failed`): a
/// sweep whose node had no graphics adapter must not look successful; 0 otherwise.
fn not_run_failure(tally: &Tally, retry: &str) -> ExitCode {
    let Some((first, why)) = tally.not_run.first() else {
        return ExitCode::SUCCESS;
    };
    eprintln!(
        "error: {} case(s) could not run and have no result (first: case {first}: {why}); {retry} to retry them",
        tally.not_run.len()
    );
    ExitCode::from(1)
}

fn merge(shards: &[PathBuf], out: &Path) -> ExitCode {
    match merge_shards(shards, out) {
        Ok(report) => {
            for warning in &report.warnings {
                eprintln!("warning: {warning}");
            }
            eprintln!(
                "merged {} shard folder(s): {} cases: {}; results in {}",
                shards.len(),
                report.cases,
                report.tally.counts,
                out.join("results.csv").display()
            );
            not_run_failure(&report.tally, "rerun the shards that hold them, then merge")
        }
        Err(e) => study_failure(&e),
    }
}

/// Mesa's Vulkan layers print "XDG_RUNTIME_DIR is invalid or not set" when the variable
/// names no folder: point it at a private one first (before any thread starts).
fn quiet_mesa_runtime_dir() {
    if let Some(dir) = wingman::render::gpu::runtime_dir_to_set() {
        // SAFETY: called first thing in main, while the program has one thread.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", dir) };
    }
}

/// Gives lavapipe's rasterizer threads the number that suits the frames of `scenarios`, when
/// the user set none (`wingman::render::gpu::lavapipe_threads_to_set`): before the first GPU
/// context, and only while the program still has one thread.
fn set_lavapipe_threads(scenarios: &[&Scenario]) {
    use wingman::scenario::SceneKind;
    let world = scenarios.iter().any(|s| s.scene.kind == SceneKind::World);
    let one_thread = std::fs::read_dir("/proc/self/task").is_ok_and(|tasks| tasks.count() == 1);
    if let (Some(threads), true) = (
        wingman::render::gpu::lavapipe_threads_to_set(world),
        one_thread,
    ) {
        // SAFETY: no other thread runs (checked above), so none reads the environment now.
        unsafe { std::env::set_var("LP_NUM_THREADS", threads) };
    }
}

/// Loads the scenario and checks its assets and resources; the error line on failure.
fn load_checked(path: &Path, overrides: &[String]) -> Result<Scenario, String> {
    preflight::load(path, overrides).map_err(|e| e.to_string())
}

/// `--out` of `render`: a PNG file, not a folder.
fn check_png_out(out: &Path) -> Result<(), String> {
    if out.is_dir() {
        return Err(format!(
            "--out {}: is a folder, not a .png file",
            out.display()
        ));
    }
    if !out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
    {
        return Err(format!(
            "--out {}: frames are written as PNG: name a .png file",
            out.display()
        ));
    }
    Ok(())
}

fn render(path: &Path, at_s: f64, out: Option<PathBuf>, overrides: &[String]) -> ExitCode {
    let out = out.unwrap_or_else(|| {
        PathBuf::from("runs")
            .join(stem(path))
            .join(format!("frame_{at_s:.3}s.png"))
    });
    let scenario = match check_png_out(&out).and_then(|()| load_checked(path, overrides)) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if !(at_s.is_finite() && at_s >= 0.0 && at_s <= scenario.run.duration_s) {
        eprintln!(
            "error: --at {at_s} is outside the scenario's [0, {}] s",
            scenario.run.duration_s
        );
        return ExitCode::from(2);
    }
    match render_frame_at(&scenario, at_s, &out) {
        Ok(record) => {
            let describe = |m: Option<wingman::vision::ImageMeasurement>, none: &str| {
                m.map_or_else(
                    || none.to_string(),
                    |m| {
                        format!(
                            "yI {:.2}, zI {:.2}, bI {:.2} px",
                            m.y_i_px, m.z_i_px, m.b_i_px
                        )
                    },
                )
            };
            let measured = describe(record.measured, "nothing");
            let truth = describe(record.truth, "target partly behind the camera");
            eprintln!(
                "frame at t = {:.3} s: {} measured {measured}; truth {truth}; written to {}",
                record.t_s,
                record.status.label(),
                out.display()
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}

/// A progress bar on a terminal: done, elapsed, time left and the realtime factor.
fn progress_bar(name: &str, quiet: bool) -> Option<indicatif::ProgressBar> {
    let show = !quiet && std::io::stderr().is_terminal();
    show.then(|| {
        let bar = indicatif::ProgressBar::new(1000);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{prefix} [{bar:30}] {percent}% {elapsed} elapsed, {msg}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar.set_prefix(name.to_string());
        bar
    })
}

fn run(path: &Path, out: Option<PathBuf>, overrides: &[String], quiet: bool) -> ExitCode {
    let name = stem(path);
    let out_dir = out.unwrap_or_else(|| PathBuf::from("runs").join(&name));
    match wingman::output::group::load_checked(path, overrides) {
        Ok(Some(group)) => {
            let scenarios: Vec<_> = group.followers.iter().map(|f| &f.scenario).collect();
            set_lavapipe_threads(&scenarios);
            return run_group(&group, &name, &out_dir, quiet);
        }
        Ok(None) => {}
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    }
    let checked = load_checked(path, overrides).and_then(|s| {
        folder::check(&out_dir)
            .map(|()| s)
            .map_err(|e| e.to_string())
    });
    let scenario = match checked {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    set_lavapipe_threads(&[&scenario]);
    if let Err(e) = interrupt::install_stop_handlers() {
        eprintln!("warning: Ctrl-C and SIGTERM will not stop the run cleanly: {e}");
    }
    let bar = progress_bar(&name, quiet);
    let duration_s = scenario.run.duration_s;
    let started = Instant::now();
    let result = run_to_directory(&scenario, &name, &out_dir, |fraction| {
        if let Some(bar) = &bar {
            bar.set_position((fraction * 1000.0) as u64);
            let wall_s = started.elapsed().as_secs_f64();
            bar.set_message(progress_message(fraction, duration_s, wall_s));
        }
    });
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    match result {
        Ok(report) => finish(&report, &out_dir, quiet),
        // The folder's own message names it (`--out DIR: ...`).
        Err(e @ wingman::output::RunError::Folder(_)) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
        Err(e) if e.is_input_error() => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(2)
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}

/// Runs a group scenario (docs/design.md, Group tracking) into `out_dir`: exit code 0 when
/// every follower kept its track to the end, 1 when one did not or the run failed, 2 for a
/// scenario or folder the run cannot take.
fn run_group(
    group: &wingman::scenario::group::GroupScenario,
    name: &str,
    out_dir: &Path,
    quiet: bool,
) -> ExitCode {
    if let Err(e) = interrupt::install_stop_handlers() {
        eprintln!("warning: Ctrl-C and SIGTERM will not stop the run cleanly: {e}");
    }
    let bar = progress_bar(name, quiet);
    let result = wingman::output::group::run_group_to_directory(group, name, out_dir, None, |f| {
        if let Some(bar) = &bar {
            bar.set_position((f * 1000.0) as u64);
        }
    });
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    match result {
        Ok(summary) => {
            if !quiet {
                eprintln!("{}", summary.one_line(out_dir));
            }
            match (&summary.stopped_by, interrupt::signal()) {
                (Some(why), Some(_)) => {
                    eprintln!("interrupted: {why}");
                    interrupted_exit_code()
                }
                (Some(why), None) => {
                    eprintln!("error: {why}");
                    ExitCode::from(1)
                }
                (None, _) => ExitCode::SUCCESS,
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(if e.is_input_error() { 2 } else { 1 })
        }
    }
}

/// The progress bar's message: the wall time left at the pace so far and the realtime
/// factor (simulated seconds per wall second).
fn progress_message(fraction: f64, duration_s: f64, wall_s: f64) -> String {
    if fraction.is_nan() || fraction <= 0.0 || wall_s <= 0.0 {
        return "starting".to_string();
    }
    let left_s = (wall_s * (1.0 - fraction) / fraction).max(0.0).round() as u64;
    format!(
        "{}m {:02}s left, {:.1}x real time",
        left_s / 60,
        left_s % 60,
        fraction * duration_s / wall_s
    )
}

/// Prints the run's notes, warnings and final line; the exit code of its status (0
/// completed or intercepted, 1 lost, diverged or with outputs not written, 130 or 143
/// interrupted).
fn finish(report: &RunReport, out_dir: &Path, quiet: bool) -> ExitCode {
    for note in &report.summary.notes {
        eprintln!("note: {note}");
    }
    for warning in &report.warnings {
        eprintln!("warning: {warning}");
    }
    let s = &report.summary;
    let line = final_line(s, out_dir);
    match s.status {
        // A full disk: the run's result is in its summary, but outputs are missing.
        RunStatus::Completed | RunStatus::Intercepted if !s.unwritten.is_empty() => {
            eprintln!("error: not written: {}; {line}", s.unwritten.join("; "));
            ExitCode::from(1)
        }
        RunStatus::Completed | RunStatus::Intercepted => {
            if !quiet {
                eprintln!("{line}");
            }
            ExitCode::SUCCESS
        }
        RunStatus::Lost | RunStatus::FalseLock | RunStatus::Diverged => {
            eprintln!(
                "error: {}; {line}",
                s.message.as_deref().unwrap_or("stopped")
            );
            ExitCode::from(1)
        }
        RunStatus::Interrupted => {
            eprintln!("interrupted: {line}");
            interrupted_exit_code()
        }
    }
}

/// 128 + the signal that stopped the run, as a shell reports a process the signal ended:
/// 130 for Ctrl-C, 143 for SIGTERM.
fn interrupted_exit_code() -> ExitCode {
    let signal = interrupt::signal().unwrap_or(libc::SIGINT);
    ExitCode::from(u8::try_from(128 + signal).unwrap_or(130))
}

/// One line on the run: status, time, speed, b̂, errors, frames lost, where the outputs are.
fn final_line(s: &Summary, out_dir: &Path) -> String {
    let frames = if s.frames > 0 {
        format!("; {} frames, {} lost", s.frames, s.lost_frames)
    } else {
        String::new()
    };
    format!(
        "{}: {} at t = {:.2} s in {:.3} s wall ({:.0}x real time); b_hat = {:.3} ft (true {} ft); RMS error last 20 s [{:.3}, {:.3}, {:.3}] ft{}{frames}; outputs in {}",
        s.scenario,
        s.status.name(),
        s.duration_s,
        s.wall_s,
        s.realtime_factor,
        s.b_hat_final_ft,
        s.b_true_ft,
        s.rms_error_last20s_ft[0],
        s.rms_error_last20s_ft[1],
        s.rms_error_last20s_ft[2],
        s.intercept_time_s
            .map(|t| format!("; intercepted at {t:.3} s"))
            .unwrap_or_default(),
        out_dir.display()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quarter of a 140 s run done in 10 s: 30 s left at 3.5 times real time.
    #[test]
    fn progress_shows_time_left_and_realtime_factor() {
        assert_eq!(
            progress_message(0.25, 140.0, 10.0),
            "0m 30s left, 3.5x real time"
        );
        assert_eq!(
            progress_message(0.5, 140.0, 100.0),
            "1m 40s left, 0.7x real time"
        );
        assert_eq!(progress_message(0.0, 140.0, 0.0), "starting");
    }
}
