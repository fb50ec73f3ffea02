//! `wingman` command line: parse, call the library, map errors to exit codes
//! (0 success, 2 bad scenario or argument, 1 failed run).

use clap::{Parser, Subcommand};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use wingman::output::{RunError, run_to_directory};
use wingman::scenario::Scenario;

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
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scenario".to_string())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Run {
            scenario,
            out,
            overrides,
            quiet,
        } => run(&scenario, out, &overrides, quiet),
    }
}

fn run(path: &Path, out: Option<PathBuf>, overrides: &[String], quiet: bool) -> ExitCode {
    let scenario = match Scenario::load(path, overrides) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let name = stem(path);
    let out_dir = out.unwrap_or_else(|| PathBuf::from("runs").join(&name));
    let show_progress = !quiet && std::io::stderr().is_terminal();
    let bar = show_progress.then(|| {
        let bar = indicatif::ProgressBar::new(1000);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{prefix} [{bar:40}] {percent}% {elapsed}")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar.set_prefix(name.clone());
        bar
    });
    let result = run_to_directory(&scenario, &name, &out_dir, |fraction| {
        if let Some(bar) = &bar {
            bar.set_position((fraction * 1000.0) as u64);
        }
    });
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    match result {
        Ok(report) => {
            for note in &report.summary.notes {
                eprintln!("note: {note}");
            }
            for warning in &report.warnings {
                eprintln!("warning: {warning}");
            }
            let s = &report.summary;
            if !quiet {
                eprintln!(
                    "{}: {:?} at t = {:.2} s in {:.3} s wall ({:.0}x real time); b_hat = {:.3} ft (true {} ft); RMS error last 20 s [{:.3}, {:.3}, {:.3}] ft{}; outputs in {}",
                    s.scenario,
                    s.status,
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
                );
            }
            ExitCode::SUCCESS
        }
        Err(e @ RunError::Sim(..)) | Err(e @ RunError::Io { .. }) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}
