//! A group run (docs/design.md, Group tracking): the targets of a [`GroupScenario`] and one
//! [`Simulation`] per follower (set up leaders first), stepped in lockstep.
//!
//! The group moves the targets. Each follower tracks its aircraft through a [`Relay`] of
//! that aircraft's truth (the target's state at each tick, or the leading follower's carried
//! from the last frame's tick with its velocity and acceleration), and its camera draws every
//! other aircraft of the group at the frame's instant, carried there over one tick likewise.
//! So the followers' steps from one frame's tick to the next do not depend on one another,
//! and each such stretch takes them on the thread pool at once, one task per follower. The
//! followers' estimators and guidance see their pixels alone. The group stops at the end of
//! the stretch in which any follower's run ends (lost, falsely locked, diverged, or a stop
//! asked for), or at the end of the run.

use super::build::target_of;
use super::{RunEnd, SimError, Simulation, Snapshot};
use crate::follower::AircraftSetupError;
use crate::frames::Vec3;
use crate::render::GpuContext;
use crate::scenario::group::{GroupFollower, GroupScenario};
use crate::scenario::{FollowerModel, Scenario};
use crate::sensing::{OtherAircraft, SensorError};
use crate::world::aircraft::AircraftParams;
use crate::world::relay::{Relay, carried};
use crate::world::target::{TargetModel, TargetState};
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// What a follower tracks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Leader {
    /// The group's target of this index.
    Target(usize),
    /// The follower of this index (stepped before it).
    Follower(usize),
}

/// One follower of a group run: its simulation, what it logged and how it ended.
#[derive(Debug)]
pub struct GroupMember {
    /// Its name.
    pub name: String,
    /// The name of the aircraft it tracks.
    pub tracks: String,
    /// Its simulation.
    pub sim: Simulation,
    /// Its logged snapshots (`telemetry.csv`'s rows).
    pub logged: Vec<Snapshot>,
    /// Why its run ended, once it has.
    pub end: Option<RunEnd>,
    /// Wall time of its set-up and steps.
    pub wall: Duration,
    /// Its size (span) as the others draw it, ft.
    pub size_ft: f64,
    leader: Leader,
    relay: Relay,
    /// Its true state at the last tick (acceleration from the last two ticks).
    truth: TargetState,
}

/// A target of a group run.
#[derive(Debug)]
struct GroupTargetTruth {
    name: String,
    model: Box<dyn TargetModel>,
    size_ft: f64,
}

/// A group run in progress.
#[derive(Debug)]
pub struct Group {
    targets: Vec<GroupTargetTruth>,
    members: Vec<GroupMember>,
    dt_s: f64,
    tick: u64,
    total_ticks: u64,
    /// Ticks between samples of the targets' track (`run.log_every`).
    log_every: u64,
    /// The targets' positions, NED, ft, at the run's start and every `log_every` ticks.
    target_tracks: Vec<Vec<Vec3>>,
}

impl Group {
    /// Sets up the targets and every follower (on `gpu` when given, else each on a device
    /// of its own opened here), leaders first. On lavapipe a device is a queue thread: the
    /// followers' frames, drawn on threads of their own, are then drawn at once rather than
    /// one after another on a shared queue.
    pub fn new(group: &GroupScenario, gpu: Option<&GpuContext>) -> Result<Self, SimError> {
        let mut targets = Vec::new();
        for t in &group.targets {
            targets.push(GroupTargetTruth {
                name: t.name.clone(),
                model: target_of(&t.scenario)?,
                size_ft: t.scenario.target.size_ft,
            });
        }
        let run = &group.followers[0].scenario.run;
        let mut built = Self {
            targets,
            members: Vec::new(),
            dt_s: run.dt_s,
            tick: 0,
            total_ticks: run.total_ticks(),
            log_every: u64::from(run.log_every).max(1),
            target_tracks: Vec::new(),
        };
        built.target_tracks.push(built.target_positions());
        for follower in &group.followers {
            let own_gpu;
            let gpu = match gpu {
                Some(gpu) => gpu,
                None => {
                    own_gpu = GpuContext::new()
                        .map_err(|e| SimError::Sensor(Box::new(SensorError::Gpu(e))))?;
                    &own_gpu
                }
            };
            let member = built.member(follower, gpu)?;
            built.members.push(member);
        }
        built.take_first_frames()?;
        Ok(built)
    }

    /// The simulation of `follower`, tracking its leader (already built) through a relay.
    fn member(&self, follower: &GroupFollower, gpu: &GpuContext) -> Result<GroupMember, SimError> {
        let started = Instant::now();
        let leader = self.leader_of(&follower.tracks);
        let mut scenario = follower.scenario.clone();
        if let Leader::Follower(j) = leader {
            let ahead = &self.members[j];
            scenario.target.size_ft = ahead.size_ft;
            scenario.target.initial_position_ft = ahead.sim.scenario().follower.initial_position_ft;
        }
        let relay = Relay::new(0.0, self.leader_state(leader, 0.0));
        let sim = Simulation::with_target_unsensed(&scenario, Some(gpu), relay.target())?;
        Ok(GroupMember {
            name: follower.name.clone(),
            tracks: follower.tracks.clone(),
            truth: sim.own_state(),
            size_ft: drawn_size_ft(&scenario)?,
            sim,
            logged: Vec::new(),
            end: None,
            wall: started.elapsed(),
            leader,
            relay,
        })
    }

    /// Every follower's sensors act at t = 0, every other aircraft of the group in its
    /// camera: the first frames, and the first row of each follower's telemetry.
    fn take_first_frames(&mut self) -> Result<(), SimError> {
        let targets_now: Vec<TargetState> =
            (self.targets.iter()).map(|t| t.model.state(0.0)).collect();
        for j in 0..self.members.len() {
            let others = self.others_seen_by(j, &targets_now, 0.0);
            let member = &mut self.members[j];
            member.sim.set_other_aircraft(&others);
            member.sim.sense_first()?;
            member.logged.push(member.sim.snapshot());
        }
        Ok(())
    }

    /// The aircraft named `name` (the scenario's checks found it).
    fn leader_of(&self, name: &str) -> Leader {
        match self.targets.iter().position(|t| t.name == name) {
            Some(i) => Leader::Target(i),
            None => Leader::Follower(
                (self.members.iter())
                    .position(|m| m.name == name)
                    .unwrap_or_default(),
            ),
        }
    }

    /// The true state of `leader` at `t_s`: a target's own, a follower's carried there from
    /// its last tick.
    fn leader_state(&self, leader: Leader, t_s: f64) -> TargetState {
        match leader {
            Leader::Target(i) => self.targets[i].model.state(t_s),
            Leader::Follower(j) => {
                let truth = &self.members[j].truth;
                carried(truth, t_s - self.members[j].sim.time_s())
            }
        }
    }

    /// The followers, leaders first.
    pub fn members(&self) -> &[GroupMember] {
        &self.members
    }

    /// The targets' names, in the group's order.
    pub fn target_names(&self) -> Vec<&str> {
        self.targets.iter().map(|t| t.name.as_str()).collect()
    }

    /// The targets' positions (NED, ft, in the order of [`Self::target_names`]) at the
    /// run's start and every `run.log_every` ticks.
    pub fn target_tracks(&self) -> &[Vec<Vec3>] {
        &self.target_tracks
    }

    /// The true position of every target now, NED, ft.
    fn target_positions(&self) -> Vec<Vec3> {
        let t_s = self.time_s();
        (self.targets.iter())
            .map(|t| t.model.position_ned_ft(t_s))
            .collect()
    }

    /// The fraction of the run's ticks taken.
    pub fn fraction_done(&self) -> f64 {
        self.tick as f64 / self.total_ticks.max(1) as f64
    }

    /// The group's time now, s.
    pub fn time_s(&self) -> f64 {
        self.tick as f64 * self.dt_s
    }

    /// Whether the group has stopped: a follower's run ended, or the run's end is reached.
    pub fn is_over(&self) -> bool {
        self.tick >= self.total_ticks || self.members.iter().any(|m| m.end.is_some())
    }

    /// Takes the next stretch of ticks of every follower (nothing once [`Self::is_over`]):
    /// up to the next tick at which any camera takes a frame, so that a stretch holds at most
    /// one frame, on its first tick; `stop_asked` as [`Simulation::run_tick`]'s. The targets
    /// move through the stretch first. Every follower is given its leader at each tick of the
    /// stretch (a target's own state; a leading follower's carried there from the stretch's
    /// start, as only the renderer, on the first tick, and the truth outputs read it) and the
    /// other aircraft at the first tick, so that the followers' steps are independent: each
    /// stretch takes them on the thread pool at once, one task per follower
    /// (docs/findings.md, Group tracking, the cost). A follower whose run ends stops there;
    /// the others finish the stretch.
    pub fn step(&mut self, stop_asked: impl Fn() -> bool + Sync) -> Result<(), SimError> {
        if self.is_over() {
            return Ok(());
        }
        let ticks = self.stretch_ticks();
        let target_states = self.advance_targets(ticks)?;
        let frame_tick = self.is_any_frame_tick(self.tick + 1);
        // The others are drawn only in frames: they are placed on frame ticks alone.
        let views: Vec<MemberView> = (0..self.members.len())
            .map(|j| MemberView {
                leader: (1..=ticks)
                    .map(|i| {
                        let t_s = self.tick_end_s(i);
                        let targets_now = &target_states[(i - 1) as usize];
                        (t_s, self.state_at(self.members[j].leader, targets_now, t_s))
                    })
                    .collect(),
                others: frame_tick
                    .then(|| self.others_seen_by(j, &target_states[0], self.tick_end_s(1))),
            })
            .collect();
        let (dt_s, stop_asked) = (self.dt_s, &stop_asked);
        let members: Vec<_> = self.members.iter_mut().zip(views).collect();
        members
            .into_par_iter()
            .for_each(|(member, view)| member.step(dt_s, view, stop_asked));
        self.tick += ticks;
        Ok(())
    }

    /// The ticks of the next stretch: up to, not including, the next tick after the first at
    /// which any follower's camera takes a frame, and not beyond the run's end.
    fn stretch_ticks(&self) -> u64 {
        let left = self.total_ticks - self.tick;
        (2..=left)
            .find(|i| self.is_any_frame_tick(self.tick + i))
            .map_or(left, |i| i - 1)
    }

    /// Whether any follower's camera takes a frame at the group's tick `tick`.
    fn is_any_frame_tick(&self, tick: u64) -> bool {
        (self.members.iter()).any(|m| (m.sim.camera()).is_some_and(|c| c.is_frame_tick(tick)))
    }

    /// Moves the targets through the next `ticks` ticks: their states at each (the targets'
    /// order), their track sampled every `run.log_every` ticks.
    fn advance_targets(&mut self, ticks: u64) -> Result<Vec<Vec<TargetState>>, SimError> {
        let mut states: Vec<Vec<TargetState>> = Vec::new();
        for i in 1..=ticks {
            let (t_s, t_next_s) = (self.tick_start_s(i), self.tick_end_s(i));
            for target in &mut self.targets {
                target
                    .model
                    .advance(t_s, self.dt_s)
                    .map_err(|diverged| SimError::Diverged {
                        t_s: t_next_s,
                        what: format!("target {}: {}", target.name, diverged.what),
                    })?;
            }
            let now: Vec<TargetState> = (self.targets.iter())
                .map(|t| t.model.state(t_next_s))
                .collect();
            if (self.tick + i).is_multiple_of(self.log_every) {
                (self.target_tracks).push(now.iter().map(|s| s.position_ned_ft).collect());
            }
            states.push(now);
        }
        Ok(states)
    }

    /// The state of `aircraft` at `t_s`: a target's from `targets_now` (the targets' states
    /// then), a follower's carried there from its last tick.
    fn state_at(&self, aircraft: Leader, targets_now: &[TargetState], t_s: f64) -> TargetState {
        match aircraft {
            Leader::Target(k) => targets_now[k],
            follower => self.leader_state(follower, t_s),
        }
    }

    /// The time at the start of the stretch's tick `i` (from 1), s.
    fn tick_start_s(&self, i: u64) -> f64 {
        (self.tick + i - 1) as f64 * self.dt_s
    }

    /// The time at the end of the stretch's tick `i` (from 1), s.
    fn tick_end_s(&self, i: u64) -> f64 {
        self.tick_start_s(i) + self.dt_s
    }

    /// Every aircraft follower `j`'s camera draws at `t_s` (the targets' states then in
    /// `targets_now`): all but itself and the one it tracks.
    fn others_seen_by(
        &self,
        j: usize,
        targets_now: &[TargetState],
        t_s: f64,
    ) -> Vec<OtherAircraft> {
        let leader = self.members[j].leader;
        let targets = (0..self.targets.len())
            .filter(|i| leader != Leader::Target(*i))
            .map(|i| (Leader::Target(i), self.targets[i].size_ft));
        let followers = (0..self.members.len())
            .filter(|k| *k != j && leader != Leader::Follower(*k))
            .map(|k| (Leader::Follower(k), self.members[k].size_ft));
        targets
            .chain(followers)
            .map(|(aircraft, size_ft)| {
                let state = self.state_at(aircraft, targets_now, t_s);
                OtherAircraft {
                    position_ned_ft: state.position_ned_ft,
                    attitude: state.attitude,
                    size_ft,
                }
            })
            .collect()
    }
}

/// What a follower is given for a stretch of ticks: its leader at each tick, and the other
/// aircraft at the first when a camera takes a frame there.
struct MemberView {
    /// The leader's state and its time at the end of each tick, s.
    leader: Vec<(f64, TargetState)>,
    others: Option<Vec<OtherAircraft>>,
}

impl GroupMember {
    /// The ticks of a stretch of this follower, each `dt_s` long, its leader and the others
    /// given in `view`; its true state after it, the acceleration from its last tick's change
    /// of velocity. Stops where its run ends.
    fn step(&mut self, dt_s: f64, view: MemberView, stop_asked: &(impl Fn() -> bool + Sync)) {
        let started = Instant::now();
        if let Some(others) = view.others {
            self.sim.set_other_aircraft(&others);
        }
        let mut velocity_before = self.truth.velocity_ned_fps;
        let last = view.leader.len().saturating_sub(1);
        for (i, (t_s, leader)) in view.leader.into_iter().enumerate() {
            if self.end.is_some() {
                break;
            }
            if i == last {
                velocity_before = self.sim.own_state().velocity_ned_fps;
            }
            self.relay.set(t_s, leader);
            let tick = self.sim.run_tick(stop_asked);
            self.logged.extend(tick.logged);
            self.end = tick.end;
        }
        let mut truth = self.sim.own_state();
        truth.accel_ned_fps2 = (truth.velocity_ned_fps - velocity_before) / dt_s;
        self.truth = truth;
        self.wall += started.elapsed();
    }
}

/// A follower's size as the others' cameras draw it: its airframe's span (the 6-DOF
/// aircraft), or the scenario's target size (a kinematic follower has no airframe).
fn drawn_size_ft(scenario: &Scenario) -> Result<f64, SimError> {
    if scenario.follower.model != FollowerModel::Aircraft {
        return Ok(scenario.target.size_ft);
    }
    let params = AircraftParams::from_scenario_path(&scenario.follower.aircraft)
        .map_err(AircraftSetupError::from)?;
    Ok(params.geometry.span_ft)
}
