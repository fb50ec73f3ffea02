//! A run stepped from outside and kept in memory (the Python package): the simulation, its
//! logged snapshots and how it ended, and the summary `wingman run` would write for it. It
//! steps through the command line's own tick ([`Simulation::run_tick`]), so its summary has
//! the same numbers as `summary.json` for the same scenario (but the wall times).

use super::stopped_status;
use super::summary::Summary;
use crate::render::GpuContext;
use crate::scenario::Scenario;
use crate::sim::{RunEnd, SimError, Simulation, Snapshot};
use std::time::{Duration, Instant};

/// A run in memory, stepped tick by tick.
#[derive(Debug)]
pub struct LiveRun {
    name: String,
    sim: Simulation,
    logged: Vec<Snapshot>,
    end: Option<RunEnd>,
    /// Wall time of the set-up and the ticks so far.
    wall: Duration,
}

impl LiveRun {
    /// Sets up `scenario` (named `name` in the summary; a camera rendering on `gpu` when
    /// given) and logs its first snapshot, as `wingman run` does.
    pub fn new(
        scenario: &Scenario,
        name: &str,
        gpu: Option<&GpuContext>,
    ) -> Result<Self, SimError> {
        let started = Instant::now();
        let sim = Simulation::on_gpu(scenario, gpu)?;
        let logged = vec![sim.snapshot()];
        Ok(Self {
            name: name.to_string(),
            sim,
            logged,
            end: None,
            wall: started.elapsed(),
        })
    }

    /// Takes one tick unless the run has ended; why it ended, if it has.
    pub fn step(&mut self) -> Option<&RunEnd> {
        if self.end.is_none() {
            let started = Instant::now();
            let tick = self.sim.run_tick(|| false);
            self.logged.extend(tick.logged);
            self.end = tick.end;
            self.wall += started.elapsed();
        }
        self.end.as_ref()
    }

    /// Steps until the simulation's time reaches `t_s` or the run ends; why it ended, if
    /// it has.
    pub fn run_until(&mut self, t_s: f64) -> Option<&RunEnd> {
        while self.end.is_none() && self.sim.time_s() < t_s {
            self.step();
        }
        self.end.as_ref()
    }

    /// Why the run ended (`None` while it goes on).
    pub fn end(&self) -> Option<&RunEnd> {
        self.end.as_ref()
    }

    /// The simulation.
    pub fn simulation(&self) -> &Simulation {
        &self.sim
    }

    /// The simulation, to set its command offset
    /// ([`Simulation::set_command_offset`]).
    pub fn simulation_mut(&mut self) -> &mut Simulation {
        &mut self.sim
    }

    /// The snapshots logged so far (`telemetry.csv`'s rows).
    pub fn logged(&self) -> &[Snapshot] {
        &self.logged
    }

    /// The summary of the run so far: at its end, `summary.json`'s numbers.
    pub fn summary(&self) -> Summary {
        let stopped = self.end.as_ref().and_then(|e| stopped_status(e, &self.sim));
        Summary::build(
            &self.name,
            &self.logged,
            &self.sim,
            self.wall.as_secs_f64(),
            stopped,
        )
    }
}
