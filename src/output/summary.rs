//! `summary.json`: the numbers a run is judged by (docs/design.md, How a run ends; its keys
//! are listed in docs/outputs.md).

use super::airframe_view::AirframeView;
use super::track_check::TrackCheck;
use crate::follower::{FlightEnvelope, LimitTicks, envelope::ANGLES_FROM_S};
use crate::scenario::GimbalSection;
use crate::scenario::{EstimatorKind, GuidanceLawKind};
use crate::sensing::camera::{BackgroundCounts, WindowCounts};
use crate::sensing::losses::LossEpisode;
use crate::sim::{GimbalReading, Simulation, Snapshot, StageTimes};
use crate::vision::BlobStatus;
use crate::vision::ImageMeasurement;
use serde::Serialize;

/// How the run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RunStatus {
    /// Ran its whole duration.
    Completed,
    /// Stopped at interception.
    Intercepted,
    /// Stopped because a state diverged.
    Diverged,
    /// Stopped because the target went unmeasured longer than `run.stop_after_lost_s`.
    Lost,
    /// Stopped because every frame measured something other than the target (by the truth)
    /// for longer than `run.stop_after_lost_s`: the track was not the target.
    FalseLock,
    /// Stopped because the user asked (Ctrl-C).
    Interrupted,
}

impl RunStatus {
    /// Every status, in the order lines that count them list them (a new status goes here
    /// too: a test checks that docs/outputs.md and docs/studies.md name each one).
    pub const ALL: [RunStatus; 6] = [
        Self::Completed,
        Self::Intercepted,
        Self::Lost,
        Self::FalseLock,
        Self::Diverged,
        Self::Interrupted,
    ];

    /// The status's name, as `summary.json`, `results.csv` and the command's lines write it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Completed => "completed",
            Self::Intercepted => "intercepted",
            Self::Diverged => "diverged",
            Self::Lost => "lost",
            Self::FalseLock => "false_lock",
            Self::Interrupted => "interrupted",
        }
    }
}

/// The summary of one run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Scenario name (file stem).
    pub scenario: String,
    /// How the run ended.
    pub status: RunStatus,
    /// Why it stopped early, if it did.
    pub message: Option<String>,
    /// The outputs that could not be written (a full disk), each `file: reason`; empty when
    /// all were.
    pub unwritten: Vec<String>,
    /// Simulated time, s.
    pub duration_s: f64,
    /// Integration steps taken.
    pub steps: u64,
    /// Camera frames rendered.
    pub frames: u64,
    /// Wall-clock time of the simulation loop, s.
    pub wall_s: f64,
    /// Simulated seconds per wall-clock second.
    pub realtime_factor: f64,
    /// The target's true size b, ft.
    pub b_true_ft: f64,
    /// b̂ at the end, ft.
    pub b_hat_final_ft: f64,
    /// Guidance law: "velocity" or "acceleration".
    pub law: GuidanceLawKind,
    /// The estimator the guidance flew on: "adaptive" or "kalman".
    pub estimator: EstimatorKind,
    /// The Kalman filter's b̂ at the end, ft (null without a filter; with `estimator.kind =
    /// "kalman"` it is `b_hat_final_ft`).
    pub kalman_b_hat_final_ft: Option<f64>,
    /// The Kalman filter's σ of b̂ at the end, ft (null without a filter).
    pub b_sigma_final_ft: Option<f64>,
    /// When the Kalman filter's σ_b / b̂ first fell below `estimator.known_sigma_fraction`, s
    /// (null without a filter or if it never did).
    pub b_known_time_s: Option<f64>,
    /// ‖d̂‖ at the end, in the law's unit: 1/s (velocity law), ft/s (acceleration law).
    pub d_hat_norm_final: f64,
    /// Time of interception, s (null if none).
    pub intercept_time_s: Option<f64>,
    /// Smallest ‖R‖ over the run (every tick), ft.
    pub min_range_ft: f64,
    /// RMS of R - R_c per axis (n, e, d) over the last 20 s of the run (R_c without
    /// excitation), ft.
    pub rms_error_last20s_ft: [f64; 3],
    /// Frames in which the target was not measured.
    pub lost_frames: u64,
    /// Frames measured as a merge, the target joined to another aircraft, for its bearing
    /// alone (`camera.merges = "bearing"`), among the lost ones.
    pub merged_frames: u64,
    /// Each run of delivered frames that did not measure the target: its start, frames,
    /// length and whether the target was found again (camera runs; empty otherwise).
    pub loss_episodes: Vec<LossEpisode>,
    /// The SNR the noisy sensor realised, 10 log10(Σ‖r‖² / Σ‖r* - r‖²) over its samples, dB
    /// (noisy runs).
    pub noise_snr_db: Option<f64>,
    /// What the set-up had to say (e.g. a Riccati observer gain that fell back to the fixed
    /// gain, the estimator gain designed from the covariance).
    pub notes: Vec<String>,
    /// RMS of the measured centroid minus the projection of the target's reference point (the
    /// mesh origin), px (camera runs): a definition's difference as well as the vision's.
    pub centroid_rms_px: Option<f64>,
    /// RMS of the measured centroid minus the true centroid of the silhouette (the union of
    /// the projected mesh triangles), px (camera runs): the vision's own centroid error.
    pub centroid_vs_silhouette_rms_px: Option<f64>,
    /// RMS of measured minus true maximal length, px (camera runs).
    pub length_rms_px: Option<f64>,
    /// The target size the camera saw over the last 20 s (camera runs): see
    /// [`ApparentSize`].
    pub apparent_size_last20s_ft: Option<ApparentSize>,
    /// The view the airframe size model inferred over the last 20 s and the normalised
    /// length it predicted, beside the truth (`estimator.size_model = "airframe"`).
    pub airframe_view_last20s: Option<AirframeView>,
    /// Graphics adapter that rendered the frames (camera runs).
    pub adapter: Option<String>,
    /// Mean wall time per camera frame of each stage, ms (camera runs): render (command
    /// submission), readback (GPU wait and copy), vision, truth (ground truth and sensing),
    /// and, per frame period, guidance, flight control and plant.
    pub per_frame_ms: Option<PerFrameCost>,
    /// How the camera's frames were drawn and measured (camera runs): in the tracking window
    /// (`windowed`, of which `redrawn_whole` were drawn again whole and `binned` binned),
    /// whole without a track (`whole_untracked`), and of the windowed, drawn again whole once
    /// measured, to be saved (`whole_saved`).
    pub frame_regions: Option<WindowCounts>,
    /// The frames by what lay behind the target, by the truth (`[scene] kind = "world"`;
    /// null otherwise): for reporting only.
    pub background: Option<BackgroundCounts>,
    /// Wall time of the continuous loop's stages over the whole run, s.
    pub stage_wall_s: StageWall,
    /// The 6-DOF follower's flight envelope (aircraft runs).
    pub aircraft: Option<AircraftSummary>,
    /// The gimbal's angle ranges and the logged rows at one of its limits (gimballed
    /// cameras).
    pub gimbal: Option<GimbalSummary>,
    /// Whether the track was the target: frames off the target by the truth, the filter's
    /// innovations and b̂ at a bound over the last 20 s, and warnings.
    pub track_check: TrackCheck,
}

/// Every key of `summary.json` in the order [`Summary`] writes them, and what it holds (for
/// `docs/outputs.md`; `tests/outputs_doc.rs` checks the list against a run's summary).
#[rustfmt::skip]
pub static SUMMARY_KEYS: &[(&str, &str)] = &[
    ("scenario", "the scenario's name (its file stem)"),
    (
        "status",
        "how the run ended: `completed`, `intercepted`, `lost`, `false_lock`, `diverged` or \
         `interrupted` \
         (the names `wingman run`'s last line, a sweep's `results.csv` and its progress lines \
         use too; a sweep adds `failed` for a case that could not run: docs/studies.md, Case \
         statuses)",
    ),
    ("message", "why it stopped early (null if it did not)"),
    ("unwritten", "the outputs that could not be written (a full disk), each `file: reason`: telemetry cut at its last whole row, a plot (and the plots after it); empty when all were written. `wingman run` then exits 1"),
    ("duration_s", "simulated time, s"),
    ("steps", "integration steps taken"),
    ("frames", "camera frames rendered"),
    ("wall_s", "wall-clock time of the simulation loop, s"),
    ("realtime_factor", "simulated seconds per wall-clock second"),
    ("b_true_ft", "the target's true size b, ft"),
    ("b_hat_final_ft", "b̂ at the end, ft"),
    ("law", "the guidance law: velocity or acceleration"),
    ("estimator", "the estimator the guidance flew on: adaptive or kalman"),
    ("kalman_b_hat_final_ft", "the Kalman filter's b̂ at the end, ft (null without a filter)"),
    ("b_sigma_final_ft", "the Kalman filter's σ_b at the end, ft (null without a filter)"),
    ("b_known_time_s", "when σ_b / b̂ first fell under `estimator.known_sigma_fraction`, s (null without a filter or if it never did)"),
    ("d_hat_norm_final", "‖d̂‖ at the end, in the law's unit: 1/s (velocity law), ft/s (acceleration law)"),
    ("intercept_time_s", "time of interception, s (null if none)"),
    ("min_range_ft", "smallest ‖R‖ over the run, ft"),
    ("rms_error_last20s_ft", "RMS of R - R_c per axis (n, e, d) over the last 20 s, ft"),
    ("lost_frames", "frames in which the target was not measured"),
    ("merged_frames", "frames measured as a merge (the target joined to another aircraft), for its bearing alone, among the lost ones (`camera.merges = \"bearing\"`)"),
    ("loss_episodes", "each run of frames without the target: start, frames, length, found again (camera runs)"),
    ("noise_snr_db", "the SNR the noisy sensor realised, dB (noisy runs)"),
    ("notes", "what the set-up decided, e.g. a Riccati observer gain that fell back to the fixed one (also printed)"),
    ("centroid_rms_px", "RMS of the measured centroid minus the projected reference point, px (camera runs)"),
    ("centroid_vs_silhouette_rms_px", "RMS of the measured centroid minus the exact centroid of the projected mesh's silhouette, px (camera runs)"),
    ("length_rms_px", "RMS of the measured minus the true maximal length, px (camera runs)"),
    ("apparent_size_last20s_ft", "the target size the frames of the last 20 s imply, ‖R‖ / aI, from the measured and from the projected-mesh maximal length (`measured`, `projected`; compare with b̂), ft (camera runs)"),
    ("airframe_view_last20s", "the airframe size model's view of the target over the last 20 s: `predicted_yaw_deg` and `predicted_pitch_deg` (the target's yaw and pitch relative to the line of sight the filter's estimate implied; 0, 0: from behind, yaw 90: side-on, pitch 90: from above) beside `true_yaw_deg` and `true_pitch_deg`, and the normalised maximal length it predicted there beside the projected mesh's (`predicted_normalised_length`, `true_normalised_length`), and where it put the bearing point (`camera.bearing_point`) from the image of the target's reference point beside where the vision measured it (`predicted_bearing_offset_px`, `measured_bearing_offset_px`: (yI, zI), px, means) (null with the other size models)"),
    ("adapter", "the graphics adapter that rendered (camera runs)"),
    ("per_frame_ms", "mean wall time per frame of render submission, readback, vision, truth, estimator, guidance, flight control, plant and `integration` (the steps as a whole), ms (camera runs)"),
    ("frame_regions", "how the frames were drawn and measured: `windowed` in the tracking window, of which `redrawn_whole` drawn again whole and `binned` binned by `camera.measure_max_length_px`; `whole_untracked` without a track; `whole_saved` of the windowed, drawn again whole once measured, to be saved (camera runs)"),
    ("background", "the frames by what lay behind the target, by the truth (`scene.kind = \"world\"`; null otherwise): `sky`, `ground`, `horizon` (ground on one side of the target, sky or cloud on another) and `cloud`, each with its `frames`, `lost` frames and `centroid_vs_silhouette_rms_px` (over its `Ok` frames), and its `trusted` frames (those the estimator took: `Ok`, and not kept out by the Kalman filter's innovation or bearing gate) with `trusted_centroid_vs_silhouette_rms_px` over them"),
    ("stage_wall_s", "wall time of guidance, estimator, control, plant and all steps (`integration`) over the run, s"),
    ("aircraft", "the largest |α| and |β| after the first 5 s, the airspeed and throttle ranges, the largest surface deflections beside their limits, and the ticks at which a command was clamped, per actuator (6-DOF runs)"),
    ("gimbal", "the pan and tilt ranges (°) and the logged rows at which an axis sat within 0.1° of its limit (gimballed cameras)"),
    ("track_check", "whether the track was the target: off_target_frames (measured frames not of the target, by the truth), nis_mean_last20s (the filter's mean normalised innovation squared, 3 when its model holds), b_hat_at_bound_last20s_s, gated_out_frames (frames the filter's innovation or bearing gate kept out), bank_fused_frames (frames whose wing line the filter fused as the target's turn, estimator.target_bank), and warnings"),
];

/// The gimbal's travel over the logged rows.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GimbalSummary {
    /// Lowest and highest pan, deg.
    pub pan_range_deg: [f64; 2],
    /// Lowest and highest tilt, deg.
    pub tilt_range_deg: [f64; 2],
    /// Logged rows with an axis within 0.1° of a limit (a pan without stops has none).
    pub rows_at_limit: u64,
    /// Logged rows.
    pub rows: u64,
}

impl GimbalSummary {
    /// Over the logged rows, for a gimbal with `[camera.gimbal]` limits `section`.
    fn of(logged: &[Snapshot], section: &GimbalSection) -> Option<Self> {
        let readings: Vec<_> = logged.iter().filter_map(|s| s.gimbal).collect();
        if readings.is_empty() {
            return None;
        }
        let range = |angle: &dyn Fn(&GimbalReading) -> f64| {
            readings
                .iter()
                .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], g| {
                    let a = angle(g).to_degrees();
                    [lo.min(a), hi.max(a)]
                })
        };
        let near = |a_rad: f64, [lo, hi]: [f64; 2]| {
            let a = a_rad.to_degrees();
            a <= lo + 0.1 || a >= hi - 0.1
        };
        let rows_at_limit = readings
            .iter()
            .filter(|g| {
                section
                    .pan_stops_deg()
                    .is_some_and(|stops| near(g.angles.pan_rad, stops))
                    || near(g.angles.tilt_rad, section.tilt_limits_deg)
            })
            .count() as u64;
        Some(Self {
            pan_range_deg: range(&|g| g.angles.pan_rad),
            tilt_range_deg: range(&|g| g.angles.tilt_rad),
            rows_at_limit,
            rows: readings.len() as u64,
        })
    }
}

/// Wall time of the continuous loop's stages, s (see [`StageTimes`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StageWall {
    /// Measurement hold, command, excitation and guidance law, at every RK4 stage.
    pub guidance: f64,
    /// The estimator's work at frames and samples.
    pub estimator: f64,
    /// Flight controller.
    pub control: f64,
    /// Follower's equations of motion.
    pub plant: f64,
    /// The steps without the sensors: the three stages above plus RK4's own work, bounds and
    /// checks.
    pub integration: f64,
}

impl From<StageTimes> for StageWall {
    fn from(t: StageTimes) -> Self {
        Self {
            guidance: t.guidance.as_secs_f64(),
            estimator: t.estimator.as_secs_f64(),
            control: t.control.as_secs_f64(),
            plant: t.plant.as_secs_f64(),
            integration: t.integration.as_secs_f64(),
        }
    }
}

/// The 6-DOF follower's extremes over the run (seed Figs 7.5-7.6, 7.12-7.13).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AircraftSummary {
    /// α and β extremes are taken from this time on, s.
    pub angles_from_s: f64,
    /// Largest |α| from `angles_from_s` on, deg.
    pub max_abs_alpha_deg: f64,
    /// Largest |β| from `angles_from_s` on, deg.
    pub max_abs_beta_deg: f64,
    /// Lowest and highest airspeed, ft/s.
    pub airspeed_range_fps: [f64; 2],
    /// Largest |δe|, |δa|, |δr| (actuator positions), deg.
    pub max_abs_surfaces_deg: [f64; 3],
    /// Their limits, deg.
    pub surface_limits_deg: [f64; 3],
    /// Lowest and highest throttle position.
    pub throttle_range: [f64; 2],
    /// Ticks at which a command was clamped to its actuator's limit.
    pub limit_ticks: LimitTicks,
    /// Ticks at which the thrust range limited the commanded flight path.
    pub flight_path_limited_ticks: u64,
    /// Ticks recorded.
    pub ticks: u64,
}

impl AircraftSummary {
    fn new(e: &FlightEnvelope, surface_limits_rad: [f64; 3]) -> Self {
        Self {
            angles_from_s: ANGLES_FROM_S,
            max_abs_alpha_deg: e.max_abs_alpha_rad.to_degrees(),
            max_abs_beta_deg: e.max_abs_beta_rad.to_degrees(),
            airspeed_range_fps: e.airspeed_range_fps,
            max_abs_surfaces_deg: e.max_abs_surfaces_rad.map(f64::to_degrees),
            surface_limits_deg: surface_limits_rad.map(f64::to_degrees),
            throttle_range: e.throttle_range,
            limit_ticks: e.limit_ticks,
            flight_path_limited_ticks: e.flight_path_limited_ticks,
            ticks: e.ticks,
        }
    }
}

/// Mean wall-clock cost per camera frame, ms.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PerFrameCost {
    /// Building and submitting the draw.
    pub render: f64,
    /// Waiting for the GPU and reading the frame back.
    pub readback: f64,
    /// Image pipeline.
    pub vision: f64,
    /// Ground truth and sensing transform.
    pub truth: f64,
    /// The estimator's work on the frame (the Kalman filter's prediction and update).
    pub estimator: f64,
    /// Measurement hold, command, excitation and guidance law over one frame period.
    pub guidance: f64,
    /// Flight controller over one frame period.
    pub control: f64,
    /// Follower's equations of motion over one frame period.
    pub plant: f64,
    /// All of the above but the camera: the steps over one frame period (the three stages,
    /// RK4's own work, bounds and checks).
    pub integration: f64,
}

impl Summary {
    /// Builds the summary from the logged snapshots and the final simulation; `stopped` is
    /// why and how the run stopped early, if it did.
    pub fn build(
        name: &str,
        logged: &[Snapshot],
        sim: &Simulation,
        wall_s: f64,
        stopped: Option<(RunStatus, String)>,
    ) -> Self {
        let duration_s = sim.time_s();
        let last = logged.last();
        let rms_error_last20s_ft = rms_error_since(logged, duration_s - 20.0);
        let b_hat_final_ft = last.map_or(f64::NAN, |s| s.b_hat_ft);
        let intercepted = sim.intercept_time_s().is_some();
        let (status, message) =
            final_status(stopped, intercepted, &rms_error_last20s_ft, b_hat_final_ft);
        let camera = sim.camera();
        let per_frame_ms = per_frame_cost(sim);
        let aircraft = aircraft_summary(sim);
        Self {
            scenario: name.to_string(),
            status,
            message,
            unwritten: Vec::new(),
            duration_s,
            steps: sim.tick(),
            frames: camera.map_or(0, |c| c.frames()),
            wall_s,
            realtime_factor: if wall_s > 0.0 {
                duration_s / wall_s
            } else {
                f64::INFINITY
            },
            b_true_ft: sim.scenario().target.size_ft,
            b_hat_final_ft,
            law: sim.scenario().guidance.law,
            estimator: sim.scenario().estimator.kind,
            kalman_b_hat_final_ft: last.and_then(|s| s.filter.estimate()).map(|f| f.b_hat_ft),
            b_sigma_final_ft: last.and_then(|s| s.filter.estimate()).map(|f| f.b_sigma_ft),
            b_known_time_s: sim.estimator().filter().and_then(|t| t.known_since_s()),
            d_hat_norm_final: last.map_or(f64::NAN, |s| s.target_motion.vector().norm()),
            intercept_time_s: sim.intercept_time_s(),
            min_range_ft: sim.min_range_ft(),
            rms_error_last20s_ft,
            lost_frames: camera.map_or(0, |c| c.lost_frames()),
            merged_frames: camera.map_or(0, |c| c.merged_frames()),
            loss_episodes: sim.loss_episodes(),
            noise_snr_db: sim.noisy_sensor().and_then(|n| n.realised_snr_db()),
            notes: sim.notes().to_vec(),
            centroid_rms_px: camera.and_then(|c| c.errors().centroid_rms_px()),
            centroid_vs_silhouette_rms_px: camera
                .and_then(|c| c.errors().silhouette_centroid_rms_px()),
            length_rms_px: camera.and_then(|c| c.errors().length_rms_px()),
            apparent_size_last20s_ft: camera.and_then(|c| {
                ApparentSize::since(logged, c.intrinsics().focal_px, duration_s - 20.0)
            }),
            airframe_view_last20s: camera.zip(sim.estimator().filter()).and_then(|(c, f)| {
                AirframeView::since(
                    &f.predicted_views_since(duration_s - 20.0),
                    logged,
                    c.intrinsics().focal_px,
                    sim.scenario().target.size_ft,
                    duration_s - 20.0,
                )
            }),
            adapter: camera.map(|c| c.adapter().to_string()),
            per_frame_ms,
            frame_regions: camera.map(|c| c.window_counts()),
            background: camera.and_then(|c| c.background()),
            stage_wall_s: sim.stage_times().into(),
            aircraft,
            gimbal: GimbalSummary::of(logged, &sim.scenario().camera.gimbal),
            track_check: TrackCheck::of(logged, sim),
        }
    }

    /// Pretty JSON text.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }
}

/// Mean wall time per camera frame of each stage (camera runs with frames).
fn per_frame_cost(sim: &Simulation) -> Option<PerFrameCost> {
    let stages = sim.stage_times();
    sim.camera().filter(|c| c.frames() > 0).map(|c| {
        let t = c.timings();
        let per = |d: std::time::Duration| 1e3 * d.as_secs_f64() / c.frames() as f64;
        PerFrameCost {
            render: per(t.render),
            readback: per(t.readback),
            vision: per(t.vision),
            truth: per(t.truth),
            estimator: per(stages.estimator),
            guidance: per(stages.guidance),
            control: per(stages.control),
            plant: per(stages.plant),
            integration: per(stages.integration),
        }
    })
}

/// The 6-DOF follower's envelope (aircraft runs).
fn aircraft_summary(sim: &Simulation) -> Option<AircraftSummary> {
    sim.follower()
        .aircraft()
        .zip(sim.flight_envelope())
        .map(|(a, e)| {
            let limits = &a.params().actuators;
            AircraftSummary::new(
                e,
                [limits.elevator.max, limits.aileron.max, limits.rudder.max],
            )
        })
}

/// The target size a camera run's frames imply, ‖R‖ / aI (see
/// [`crate::vision::ImageMeasurement::apparent_size_ft`]), averaged over the measured frames:
/// what the guidance's r* says the target's size is, to set beside b̂ and the true b.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ApparentSize {
    /// From the measured maximal length, ft.
    pub measured: f64,
    /// From the projected mesh's maximal length (the truth), ft.
    pub projected: f64,
}

impl ApparentSize {
    /// Over the distinct frames with status ok taken at t ≥ `from_s` (None without any).
    fn since(logged: &[Snapshot], focal_px: f64, from_s: f64) -> Option<Self> {
        let mut frames: Vec<_> = logged
            .iter()
            .filter_map(|s| s.frame)
            .filter(|f| f.t_s >= from_s - 1e-9 && f.status == BlobStatus::Ok)
            .collect();
        frames.dedup_by_key(|f| f.index);
        let pairs: Vec<_> = frames
            .iter()
            .filter_map(|f| f.measured.zip(f.truth).map(|m| (m, f.range_ft)))
            .collect();
        if pairs.is_empty() {
            return None;
        }
        let mean = |size: &dyn Fn(&(ImageMeasurement, ImageMeasurement), f64) -> f64| {
            pairs.iter().map(|(m, r)| size(m, *r)).sum::<f64>() / pairs.len() as f64
        };
        Some(Self {
            measured: mean(&|(m, _), r| m.apparent_size_ft(focal_px, r)),
            projected: mean(&|(_, t), r| t.apparent_size_ft(focal_px, r)),
        })
    }
}

/// How the run ended and why: the early stop when there was one, else intercepted or
/// completed; but a run whose RMS error or final b̂ is not finite (a state that overflowed
/// without tripping the divergence checks) is `diverged`, never `completed`.
fn final_status(
    stopped: Option<(RunStatus, String)>,
    intercepted: bool,
    rms_error_ft: &[f64; 3],
    b_hat_ft: f64,
) -> (RunStatus, Option<String>) {
    if let Some((status, message)) = stopped {
        return (status, Some(message));
    }
    if rms_error_ft
        .iter()
        .chain([&b_hat_ft])
        .any(|x| !x.is_finite())
    {
        let rms: Vec<String> = rms_error_ft.iter().map(|x| format!("{x:.3}")).collect();
        let message = format!(
            "the results are not finite (b_hat = {b_hat_ft:.3} ft, RMS error [{}] ft)",
            rms.join(", ")
        );
        return (RunStatus::Diverged, Some(message));
    }
    if intercepted {
        (RunStatus::Intercepted, None)
    } else {
        (RunStatus::Completed, None)
    }
}

/// Per-axis RMS of R - R_c over the snapshots with t ≥ `from_s`.
pub fn rms_error_since(logged: &[Snapshot], from_s: f64) -> [f64; 3] {
    let mut sum = [0.0; 3];
    let mut n = 0usize;
    for s in logged.iter().filter(|s| s.t_s >= from_s - 1e-9) {
        let e = s.relative_ned_ft - s.command_ned_ft;
        for (acc, v) in sum.iter_mut().zip(e.iter()) {
            *acc += v * v;
        }
        n += 1;
    }
    if n == 0 {
        return [f64::NAN; 3];
    }
    sum.map(|s| (s / n as f64).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Results that are not finite are never reported as completed or intercepted; an early
    /// stop keeps its own status.
    #[test]
    fn non_finite_results_are_diverged() {
        let finite = [1.0, 2.0, 3.0];
        assert_eq!(
            final_status(None, false, &finite, 8.0),
            (RunStatus::Completed, None)
        );
        let (status, message) = final_status(None, false, &[f64::NAN, 0.0, 0.0], 8.0);
        assert_eq!(status, RunStatus::Diverged);
        assert!(message.expect("why").contains("not finite"));
        let (status, _) = final_status(None, true, &finite, f64::INFINITY);
        assert_eq!(status, RunStatus::Diverged);
        let lost = Some((RunStatus::Lost, "lost".to_string()));
        assert_eq!(
            final_status(lost, false, &[f64::NAN; 3], 8.0).0,
            RunStatus::Lost
        );
    }
}
