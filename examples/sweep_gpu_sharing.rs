//! Measures how a sweep's camera runs should get their GPU device: one device shared by every
//! worker thread, one device per worker, or one per run (what `wingman run` does).
//!
//! `cargo run --release --example sweep_gpu_sharing [CASES] [JOBS] [DURATION_S]`
//!
//! Runs CASES copies (seeds 1..=CASES) of `scenarios/vision_ch4_formation.toml`, shortened to
//! DURATION_S, on JOBS rayon threads in each mode, twice in alternating order, and prints the
//! wall time of each. The sweep (`src/study/run.rs`) uses the mode this measured fastest, one
//! device per worker, kept as here by `wingman::study::workers::Workers`.

use rayon::prelude::*;
use std::path::Path;
use std::time::Instant;
use wingman::output::run_to_directory_on;
use wingman::render::GpuContext;
use wingman::scenario::Scenario;
use wingman::study::workers::Workers;

#[derive(Debug, Clone, Copy)]
enum Mode {
    Shared,
    PerWorker,
    PerRun,
}

fn run_one(scenario: &Scenario, out: &Path, gpu: Option<&GpuContext>) {
    if let Err(e) = run_to_directory_on(scenario, "gpu_sharing", out, gpu, |_| {}) {
        eprintln!("run failed: {e}");
    }
}

fn sweep(
    mode: Mode,
    scenarios: &[Scenario],
    jobs: usize,
) -> Result<f64, Box<dyn std::error::Error>> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(jobs).build()?;
    let dir = tempfile::tempdir()?;
    let shared = match mode {
        Mode::Shared => Some(GpuContext::new()?),
        _ => None,
    };
    let workers = Workers::new(jobs);
    let started = Instant::now();
    pool.install(|| {
        scenarios.par_iter().enumerate().for_each(|(k, s)| {
            let out = dir.path().join(k.to_string());
            match mode {
                Mode::Shared => run_one(s, &out, shared.as_ref()),
                Mode::PerRun => run_one(s, &out, None),
                Mode::PerWorker => workers.with_gpu(|gpu| run_one(s, &out, gpu.ok())),
            }
        })
    });
    Ok(started.elapsed().as_secs_f64())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let number =
        |i: usize, default: f64| args.get(i).and_then(|a| a.parse().ok()).unwrap_or(default);
    let (cases, jobs, duration_s) = (
        number(0, 8.0) as u64,
        number(1, 2.0) as usize,
        number(2, 20.0),
    );
    let scenarios = (1..=cases)
        .map(|seed| {
            let set = [
                format!("run.seed={seed}"),
                format!("run.duration_s={duration_s}"),
                "output.plots=false".to_string(),
            ];
            Scenario::load(Path::new("scenarios/vision_ch4_formation.toml"), &set)
        })
        .collect::<Result<Vec<_>, _>>()?;
    for round in 0..2 {
        let order = if round == 0 {
            [Mode::Shared, Mode::PerWorker, Mode::PerRun]
        } else {
            [Mode::PerRun, Mode::PerWorker, Mode::Shared]
        };
        for mode in order {
            let wall_s = sweep(mode, &scenarios, jobs)?;
            println!("{mode:?}: {cases} runs of {duration_s} s on {jobs} threads in {wall_s:.2} s");
        }
    }
    Ok(())
}
