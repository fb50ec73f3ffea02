//! `wingman._wingman`: the simulation stepped from Python (docs/python.md). A
//! [`Simulation`] is a [`LiveRun`]: it steps through the command line's own tick, so its
//! summary has `summary.json`'s numbers; its states are dicts of floats and numpy arrays, its
//! camera frame an (H, W, 4) uint8 array. Errors are Python exceptions carrying the command
//! line's messages: `ScenarioError` (a `ValueError`) for what `wingman run` exits 2 on,
//! `SimulationError` (a `RuntimeError`) for what it exits 1 on.

mod states;

use numpy::{PyArray1, PyArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use wingman::frames::Vec3;
use wingman::output::live::LiveRun;
use wingman::output::preflight;
use wingman::output::summary::RunStatus;
use wingman::sim::RunEnd;
use wingman::study::{Plan, Progress, SweepOptions, run_sweep};

create_exception!(
    _wingman,
    ScenarioError,
    PyValueError,
    "A bad scenario, override, study file or output folder: what `wingman` exits 2 on, its message naming the file, key, value and what is allowed."
);
create_exception!(
    _wingman,
    SimulationError,
    PyRuntimeError,
    "A run that could not set up (no graphics adapter) or diverged, or a study that could not write: what `wingman` exits 1 on."
);

/// A scenario's simulation, stepped from Python.
#[pyclass(unsendable, module = "wingman._wingman")]
struct Simulation {
    run: LiveRun,
}

/// The status name of a run's end (`summary.json`'s `status`), "running" before it.
fn status_name(run: &LiveRun) -> &'static str {
    let intercepted = run.simulation().intercept_time_s().is_some();
    match run.end() {
        None => "running",
        Some(RunEnd::Finished) if intercepted => RunStatus::Intercepted.name(),
        Some(RunEnd::Finished) => RunStatus::Completed.name(),
        Some(RunEnd::Failed(_)) => RunStatus::Diverged.name(),
        Some(RunEnd::Lost { .. }) => RunStatus::Lost.name(),
        Some(RunEnd::FalseLock { .. }) => RunStatus::FalseLock.name(),
        Some(RunEnd::Interrupted) => RunStatus::Interrupted.name(),
    }
}

/// The status after a step, or the failure that ended the run as a `SimulationError`.
fn outcome(run: &LiveRun) -> PyResult<&'static str> {
    match run.end() {
        Some(RunEnd::Failed(e)) => Err(SimulationError::new_err(e.to_string())),
        _ => Ok(status_name(run)),
    }
}

/// The scenario's stem, the run's name in its summary (as `wingman run` names it).
fn stem(path: &Path) -> String {
    path.file_stem().map_or_else(
        || "scenario".to_string(),
        |s| s.to_string_lossy().into_owned(),
    )
}

/// A group scenario (`[group]`) is not one pair: `Simulation` would fly its base pair alone.
fn refuse_group(scenario: &Path, overrides: &[String]) -> PyResult<()> {
    match wingman::output::group::load_checked(scenario, overrides) {
        Ok(None) => Ok(()),
        Ok(Some(_)) => Err(ScenarioError::new_err(format!(
            "{}: a group scenario ([group]); Simulation steps one follower and its target: \
             run the group with `wingman run` or study it with `wingman.sweep`",
            scenario.display()
        ))),
        Err(e) => Err(ScenarioError::new_err(e.to_string())),
    }
}

#[pymethods]
impl Simulation {
    /// Loads and checks the scenario with its `section.key=value` overrides, as `wingman
    /// run SCENARIO --set ...` does, and sets the simulation up (the sensors act for tick 0).
    #[new]
    #[pyo3(signature = (scenario, overrides = Vec::new()))]
    fn new(scenario: PathBuf, overrides: Vec<String>) -> PyResult<Self> {
        refuse_group(&scenario, &overrides)?;
        let loaded = preflight::load(&scenario, &overrides)
            .map_err(|e| ScenarioError::new_err(e.to_string()))?;
        let name = stem(&scenario);
        let run = LiveRun::new(&loaded, &name, None).map_err(|e| match e.is_missing_adapter() {
            true => SimulationError::new_err(e.to_string()),
            false => ScenarioError::new_err(format!("{}: {e}", scenario.display())),
        })?;
        Ok(Self { run })
    }

    /// Takes one tick (`run.dt_s`); the run's status after it: "running", or how it ended
    /// ("completed", "intercepted", "lost", "false_lock"); raises `SimulationError` when it
    /// diverged. After its end it takes no more ticks.
    fn step(&mut self) -> PyResult<&'static str> {
        self.run.step();
        outcome(&self.run)
    }

    /// Steps until the time reaches `t_s` or the run ends; the status as `step()` gives it.
    fn run_until(&mut self, t_s: f64) -> PyResult<&'static str> {
        self.run.run_until(t_s);
        outcome(&self.run)
    }

    /// The run's status: "running", or how it ended.
    #[getter]
    fn status(&self) -> &'static str {
        status_name(&self.run)
    }

    /// Simulated time, s.
    #[getter]
    fn time_s(&self) -> f64 {
        self.run.simulation().time_s()
    }

    /// Ticks taken.
    #[getter]
    fn tick(&self) -> u64 {
        self.run.simulation().tick()
    }

    /// Ticks of the whole run.
    #[getter]
    fn total_ticks(&self) -> u64 {
        self.run.simulation().total_ticks()
    }

    /// The tick, s (`run.dt_s`).
    #[getter]
    fn dt_s(&self) -> f64 {
        self.run.simulation().scenario().run.dt_s
    }

    /// Ticks per camera frame; None without a camera.
    #[getter]
    fn frame_period_ticks(&self) -> Option<u64> {
        let scenario = self.run.simulation().scenario();
        let camera = self.run.simulation().camera();
        camera.map(|_| scenario.camera.period_ticks(scenario.run.dt_s))
    }

    /// The resolved scenario as TOML text (what `scenario.toml` of a run holds).
    fn scenario_toml(&self) -> String {
        self.run.simulation().scenario().to_toml_string()
    }

    /// The camera's image size (width, height), px; None without a camera.
    fn frame_size(&self) -> Option<(u32, u32)> {
        let camera = self.run.simulation().camera()?;
        let intrinsics = camera.intrinsics();
        Some((intrinsics.width_px, intrinsics.height_px))
    }

    /// The last camera frame measured, as a new (H, W, 4) uint8 array of RGBA (one copy: the
    /// renderer draws the next frame into the same buffer); None without a camera, before
    /// the first frame, and for a frame drawn only in its tracking window (set
    /// `output.frames_every` to draw every n-th frame whole).
    fn frame<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let Some((image, _, _)) = self.run.simulation().camera().and_then(|c| c.last_frame())
        else {
            return Ok(None);
        };
        let shape = [image.height_px as usize, image.width_px as usize, 4];
        let array = PyArray1::from_slice(py, &image.rgba).reshape(shape)?;
        Ok(Some(array.into_any()))
    }

    /// Every stage's state now (see docs/python.md, States).
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        states::snapshot_dict(py, &self.run.simulation().snapshot())
    }

    /// The camera frame the guidance holds (its measurement and truth); None before one.
    fn measurement<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<Option<Bound<'py, pyo3::types::PyDict>>> {
        let held = self.run.simulation().camera().and_then(|c| c.held_record());
        held.map(|record| states::frame_dict(py, &record))
            .transpose()
    }

    /// The summary of the run so far as `summary.json`'s JSON text (at the end, its numbers
    /// but the wall times).
    fn summary_json(&self) -> String {
        self.run.summary().to_json()
    }

    /// Logged rows so far (`telemetry.csv`'s, every `run.log_every` ticks).
    #[getter]
    fn logged_rows(&self) -> usize {
        self.run.logged().len()
    }

    /// Adds `offset` (NED: a velocity, ft/s, for the velocity law; an acceleration, ft/s², for
    /// the acceleration law) to the guidance's command from the next tick on; None removes it.
    #[pyo3(signature = (offset = None))]
    fn set_command_offset(&mut self, offset: Option<[f64; 3]>) {
        let offset = offset.map(Vec3::from);
        self.run.simulation_mut().set_command_offset(offset);
    }
}

/// Runs a study as `wingman sweep STUDY --out OUT --jobs JOBS --quiet` does; the path of its
/// results.csv. A case that could not run raises `SimulationError` naming it.
#[pyfunction]
#[pyo3(signature = (study, out, jobs = 1))]
fn sweep(study: PathBuf, out: PathBuf, jobs: usize) -> PyResult<PathBuf> {
    let plan = Plan::load(&study).map_err(|e| ScenarioError::new_err(e.to_string()))?;
    let options = SweepOptions {
        out_dir: out.clone(),
        jobs: jobs.max(1),
        shard: None,
        progress: Progress::Quiet,
    };
    let report = run_sweep(&plan, &options).map_err(|e| {
        let message = e.to_string();
        match e.is_bad_input() {
            true => ScenarioError::new_err(message),
            false => SimulationError::new_err(message),
        }
    })?;
    if let Some((case, why)) = report.tally.not_run.first() {
        return Err(SimulationError::new_err(format!(
            "{} case(s) could not run and have no result (first: case {case}: {why})",
            report.tally.not_run.len()
        )));
    }
    Ok(out.join("results.csv"))
}

/// The folder Mesa's Vulkan layers are to be given as XDG_RUNTIME_DIR, when the variable
/// names none (they print a warning otherwise); None when it is fine.
#[pyfunction]
fn runtime_dir_to_set() -> Option<PathBuf> {
    wingman::render::gpu::runtime_dir_to_set()
}

#[pymodule]
fn _wingman(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Simulation>()?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(runtime_dir_to_set, m)?)?;
    // The shipped scenarios of the clone the package was built from (the environments'
    // default scenario).
    m.add(
        "SCENARIOS_DIR",
        concat!(env!("CARGO_MANIFEST_DIR"), "/../scenarios"),
    )?;
    m.add("ScenarioError", m.py().get_type::<ScenarioError>())?;
    m.add("SimulationError", m.py().get_type::<SimulationError>())?;
    Ok(())
}
