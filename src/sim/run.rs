//! One tick of a run as a driver takes it (docs/design.md, How a run ends): the step, the
//! snapshot to log (every `run.log_every` ticks and at the end), and whether the run ends
//! there: finished, failed, the target lost or falsely locked for longer than
//! `run.stop_after_lost_s`, or a stop asked for. The command line's run and the Python
//! package both step through [`Simulation::run_tick`], so a run stepped from outside is the
//! run `wingman run` writes.

use super::{SimError, Simulation, Snapshot, StepOutcome};

/// Why a run ended.
#[derive(Debug)]
pub enum RunEnd {
    /// It ran its duration, or intercepted (see [`Simulation::intercept_time_s`]).
    Finished,
    /// A state diverged or the camera failed.
    Failed(SimError),
    /// The target went unmeasured from `since_s` for longer than `run.stop_after_lost_s`.
    Lost {
        /// Time of the first unmeasured frame, s.
        since_s: f64,
    },
    /// Every frame from `since_s` measured something other than the target, for longer
    /// than `run.stop_after_lost_s`.
    FalseLock {
        /// Time of the first frame off the target, s.
        since_s: f64,
    },
    /// A stop was asked for (Ctrl-C, SIGTERM).
    Interrupted,
}

/// What one tick of a run gave its driver.
#[derive(Debug)]
pub struct RunTick {
    /// The snapshot to log at this tick (a logging tick, or the run's last).
    pub logged: Option<Snapshot>,
    /// Why the run ended at this tick, if it did.
    pub end: Option<RunEnd>,
}

impl Simulation {
    /// Takes one tick of a run: steps, then decides whether the run ends here and which
    /// snapshot to log. `stop_asked` is asked, while the target is tracked, whether to stop
    /// (the command line's Ctrl-C). After the run's end, further ticks are the driver's
    /// mistake: call it only while the previous tick's `end` was `None`.
    pub fn run_tick(&mut self, stop_asked: impl FnOnce() -> bool) -> RunTick {
        let log_every = u64::from(self.scenario.run.log_every);
        let outcome = match self.step() {
            Ok(outcome) => outcome,
            Err(e) => {
                return RunTick {
                    logged: None,
                    end: Some(RunEnd::Failed(e)),
                };
            }
        };
        if outcome != StepOutcome::Running {
            return RunTick {
                logged: Some(self.snapshot()),
                end: Some(RunEnd::Finished),
            };
        }
        let logging_tick = self.tick.is_multiple_of(log_every);
        let lost_limit_s = self.scenario.run.stop_after_lost_s;
        let too_long = |since: &f64| lost_limit_s > 0.0 && self.time_s() - since > lost_limit_s;
        let lost_since = self.unmeasured_since_s().filter(too_long);
        let false_since = self.off_target_since_s().filter(too_long);
        let end = match (lost_since, false_since) {
            (Some(since_s), _) => Some(RunEnd::Lost { since_s }),
            (None, Some(since_s)) => Some(RunEnd::FalseLock { since_s }),
            (None, None) => stop_asked().then_some(RunEnd::Interrupted),
        };
        RunTick {
            logged: (logging_tick || end.is_some()).then(|| self.snapshot()),
            end,
        }
    }
}
