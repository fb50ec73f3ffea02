//! A group run's outputs (docs/outputs.md, Group runs): one folder per follower holding what a
//! single run writes (`scenario.toml`, `telemetry.csv`, `summary.json`, and the camera's
//! `frames/` when its `output.frames_every` is set), and beside them `group.json`, each
//! follower's result in one table, and `formation.png`, the formation seen from above.

use super::frame_images::{FrameSaver, gimbal_captions};
use super::summary::{RunStatus, Summary};
use super::telemetry::{TelemetryWriter, row_of};
use super::{RunError, folder, interrupt, lock, stopped_status};
use crate::render::GpuContext;
use crate::scenario::group::GroupScenario;
use crate::scenario::{ScenarioError, ScenarioSource};
use crate::sim::group::{Group, GroupMember};
use std::path::Path;
use std::time::Instant;

/// One follower's result in `group.json`.
#[derive(Debug, Clone, serde::Serialize)]
pub struct FollowerResult {
    /// Its name (its folder).
    pub name: String,
    /// The aircraft it tracks.
    pub tracks: String,
    /// How its run ended (`completed` when the group stopped for another follower).
    pub status: RunStatus,
    /// Frames that did not measure anything.
    pub lost_frames: u64,
    /// Frames measured as a merge, for their bearing alone, among the lost ones.
    pub merged_frames: u64,
    /// Frames whose measurement was not of the tracked aircraft (by the truth): a track
    /// captured by another aircraft.
    pub false_lock_frames: u64,
    /// The tracked aircraft's true size, ft.
    pub b_true_ft: f64,
    /// b̂ at the end, ft.
    pub b_hat_final_ft: f64,
    /// (b̂ - b) / b at the end.
    pub b_hat_error_fraction: f64,
    /// RMS of R - R_c per NED axis over the last 20 s, ft (its summary's
    /// `rms_error_last20s_ft`).
    pub slot_rms_last_20s_ft: [f64; 3],
    /// Wall time of its set-up and steps, s (the followers step at once on frame ticks).
    pub wall_s: f64,
}

/// `group.json`: the group's run and each follower's result.
#[derive(Debug, Clone, serde::Serialize)]
pub struct GroupSummary {
    /// The scenario's name.
    pub scenario: String,
    /// Simulated time reached, s.
    pub duration_s: f64,
    /// Wall time of the whole run, s.
    pub wall_s: f64,
    /// Simulated seconds per wall second.
    pub realtime_factor: f64,
    /// Why the group stopped before its end (the first follower whose run ended), if it did.
    pub stopped_by: Option<String>,
    /// The air the followers flew: `independent` (each its own turbulence stream) or
    /// `shared` (one air mass, `[group] gusts`).
    pub gusts: &'static str,
    /// The followers, leaders first.
    pub followers: Vec<FollowerResult>,
}

impl GroupSummary {
    /// One line on the run: time, speed, and each follower's status, b̂ error and frames
    /// lost or falsely locked.
    pub fn one_line(&self, out_dir: &Path) -> String {
        let followers: Vec<String> = (self.followers.iter())
            .map(|f| {
                format!(
                    "{} {:?} b̂ {:+.1}% lost {} false {}",
                    f.name,
                    f.status,
                    100.0 * f.b_hat_error_fraction,
                    f.lost_frames,
                    f.false_lock_frames
                )
            })
            .collect();
        format!(
            "group {:.1} s in {:.1} s ({:.1}x real time): {}; outputs in {}",
            self.duration_s,
            self.wall_s,
            self.realtime_factor,
            followers.join("; "),
            out_dir.display()
        )
    }
}

/// The group the file at `path` describes (`None`: a single pair), every follower's
/// scenario checked as a single run's is before anything is written
/// ([`super::preflight::check`]).
pub fn load_checked(
    path: &Path,
    overrides: &[String],
) -> Result<Option<GroupScenario>, ScenarioError> {
    let Some(group) = GroupScenario::load(path, overrides)? else {
        return Ok(None);
    };
    let source = ScenarioSource {
        path: path.to_path_buf(),
        text: std::fs::read_to_string(path).unwrap_or_default(),
        overrides: overrides.to_vec(),
    };
    for follower in &group.followers {
        super::preflight::check(&follower.scenario, &source)?;
    }
    Ok(Some(group))
}

/// Runs `group` (named `name`) and writes its outputs into `out_dir`; `progress` is told the
/// fraction done now and then. Each follower's folder is written at the end.
pub fn run_group_to_directory(
    group: &GroupScenario,
    name: &str,
    out_dir: &Path,
    gpu: Option<&GpuContext>,
    mut progress: impl FnMut(f64),
) -> Result<GroupSummary, RunError> {
    folder::check(out_dir)?;
    let started = Instant::now();
    let mut run = Group::new(group, gpu).map_err(|e| RunError::Setup(Box::new(e)))?;
    let _lock = lock::lock(out_dir).map_err(folder::FolderError::from)?;
    folder::prepare(out_dir)?;
    folder::mark(out_dir)?;
    let mut next_report = 0.0;
    let mut savers = frame_savers(&run, out_dir);
    let mut warnings = Vec::new();
    while !run.is_over() {
        run.step(interrupt::requested)
            .map_err(|e| RunError::Sim(Box::new(e), out_dir.to_path_buf()))?;
        save_frames(&run, &mut savers, &mut warnings);
        if run.fraction_done() >= next_report {
            progress(run.fraction_done());
            next_report += 0.001;
        }
    }
    for warning in warnings {
        eprintln!("warning: {warning}");
    }
    let wall_s = started.elapsed().as_secs_f64();
    let mut results = Vec::new();
    for member in run.members() {
        let summary = write_member(out_dir, name, member)?;
        results.push(follower_result(member, &summary));
    }
    let summary = group_summary(&run, name, wall_s, results);
    let path = out_dir.join("group.json");
    let json = serde_json::to_string_pretty(&summary).unwrap_or_default();
    std::fs::write(&path, json + "\n").map_err(|source| RunError::Io { path, source })?;
    if group.followers[0].scenario.output.plots {
        let path = out_dir.join("formation.png");
        if let Err(e) = super::group_plot::draw_formation(&path, &run) {
            eprintln!("warning: {} not drawn: {e}", path.display());
        }
    }
    Ok(summary)
}

/// A frame saver per follower whose scenario saves frames (`output.frames_every`), into its
/// folder's `frames/`.
fn frame_savers(run: &Group, out_dir: &Path) -> Vec<Option<FrameSaver>> {
    (run.members().iter())
        .map(|m| {
            let output = &m.sim.scenario().output;
            (output.frames_every > 0).then(|| {
                let dir = out_dir.join(&m.name).join("frames");
                FrameSaver::new(&dir, output.frames_every, output.overlay)
            })
        })
        .collect()
}

/// Offers each follower's latest frame to its saver; a failure to save is a warning, and
/// that follower saves no more.
fn save_frames(run: &Group, savers: &mut [Option<FrameSaver>], warnings: &mut Vec<String>) {
    for (member, slot) in run.members().iter().zip(savers.iter_mut()) {
        if let (Some(saver), Some(camera)) = (slot.as_mut(), member.sim.camera())
            && let Err(e) = saver.offer(camera, || gimbal_captions(member.sim.gimbal_reading()))
        {
            warnings.push(format!("{}: frame not saved: {e}", member.name));
            *slot = None;
        }
    }
}

/// The group's summary after its run, with each follower's result.
fn group_summary(
    run: &Group,
    name: &str,
    wall_s: f64,
    followers: Vec<FollowerResult>,
) -> GroupSummary {
    let duration_s = run.time_s();
    let stopped_by = run.members().iter().find_map(|m| {
        let (status, message) = stopped_status(m.end.as_ref()?, &m.sim)?;
        Some(format!("{}: {status:?}: {message}", m.name))
    });
    GroupSummary {
        scenario: name.to_string(),
        duration_s,
        wall_s,
        realtime_factor: duration_s / wall_s.max(1e-9),
        stopped_by,
        gusts: if run
            .members()
            .iter()
            .any(|m| m.sim.scenario().run.shared_air_seed.is_some())
        {
            "shared"
        } else {
            "independent"
        },
        followers,
    }
}

/// One follower's line of `group.json`, from its own summary (`summary.json`'s numbers).
fn follower_result(m: &GroupMember, summary: &Summary) -> FollowerResult {
    let (b_true_ft, b_hat_final_ft) = (summary.b_true_ft, summary.b_hat_final_ft);
    FollowerResult {
        name: m.name.clone(),
        tracks: m.tracks.clone(),
        status: summary.status,
        lost_frames: summary.lost_frames,
        merged_frames: summary.merged_frames,
        false_lock_frames: summary.track_check.off_target_frames,
        b_true_ft,
        b_hat_final_ft,
        b_hat_error_fraction: (b_hat_final_ft - b_true_ft) / b_true_ft,
        slot_rms_last_20s_ft: summary.rms_error_last20s_ft,
        wall_s: m.wall.as_secs_f64(),
    }
}

/// Writes follower `member`'s folder: its scenario, telemetry, summary and, with
/// `output.plots`, the single run's figures; returns its summary.
fn write_member(out_dir: &Path, name: &str, member: &GroupMember) -> Result<Summary, RunError> {
    let dir = out_dir.join(&member.name);
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| RunError::Io { path, source }
    };
    std::fs::create_dir_all(&dir).map_err(io(&dir))?;
    let scenario_path = dir.join("scenario.toml");
    std::fs::write(&scenario_path, member.sim.scenario().to_toml_string())
        .map_err(io(&scenario_path))?;
    let telemetry_path = dir.join("telemetry.csv");
    let mut writer = TelemetryWriter::create(&telemetry_path).map_err(io(&telemetry_path))?;
    for snapshot in &member.logged {
        writer
            .write(&row_of(snapshot))
            .map_err(io(&telemetry_path))?;
    }
    writer.flush().map_err(io(&telemetry_path))?;
    let stopped = member
        .end
        .as_ref()
        .and_then(|e| stopped_status(e, &member.sim));
    let run_name = format!("{name}/{}", member.name);
    let wall_s = member.wall.as_secs_f64();
    let mut summary = Summary::build(&run_name, &member.logged, &member.sim, wall_s, stopped);
    let summary_path = dir.join(super::SUMMARY_FILE);
    super::write_outputs_after_telemetry(&dir, member.sim.scenario(), &member.logged, &mut summary)
        .map_err(io(&summary_path))?;
    Ok(summary)
}
