//! The track check of a run (docs/outputs.md, The track check): whether what the follower
//! flew on was the target. The simulator knows the truth and counts the frames whose
//! measurement was of something else (a noise blob, a cloud): a false lock that lasts longer
//! than `run.stop_after_lost_s` ends the run as `false_lock`. The follower's own evidence is
//! reported beside it, as the follower could see it without the truth: the filter's
//! normalised innovations over the last 20 s (about 3 when its model holds), how long b̂
//! sat at a bound of the guidance's projection, and the frames its gates kept out.

use crate::sim::{Simulation, Snapshot};
use serde::Serialize;

/// A mean normalised innovation squared over this many times its expected value (3) is
/// reported: the measurements do not behave as the filter's model says the target does.
/// formation.toml reads about 0.1 (its pixel noise figures are conservative); a filter whose
/// model of the target's motion or of the follower's navigation is wrong reads far more
/// (docs/findings.md, The track check).
pub const NIS_WARNING_RATIO: f64 = 10.0;

/// A b̂ at a bound for more than this fraction of the last 20 s is reported.
pub const AT_BOUND_WARNING_FRACTION: f64 = 0.5;

/// The window the follower's evidence is taken over, s.
const WINDOW_S: f64 = 20.0;

/// Whether the track was the target.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrackCheck {
    /// Measured frames whose blob was not the target, by the truth (camera runs).
    pub off_target_frames: u64,
    /// The mean normalised innovation squared of the filter's measurements over the last
    /// 20 s (null without a filter or measurements).
    pub nis_mean_last20s: Option<f64>,
    /// Time b̂ spent at b_min_ft or b_max_ft over the last 20 s, s.
    pub b_hat_at_bound_last20s_s: f64,
    /// Frames the filter's innovation or bearing gate kept out over the whole run
    /// (`estimator.innovation_gate`; 0 without a gate or a filter).
    pub gated_out_frames: u64,
    /// Frames whose wing line the filter fused as the target's turn over the whole run
    /// (`estimator.target_bank = "measured"`; 0 without it or a filter).
    pub bank_fused_frames: u64,
    /// What the check found, in words (empty when nothing).
    pub warnings: Vec<String>,
}

impl TrackCheck {
    /// The check of a run that logged `logged`.
    pub fn of(logged: &[Snapshot], sim: &Simulation) -> Self {
        let from_s = sim.time_s() - WINDOW_S;
        let episodes = sim.false_lock_episodes();
        let off_target_frames = episodes.iter().map(|e| e.frames).sum();
        let nis_mean_last20s = sim
            .estimator()
            .filter()
            .and_then(|f| f.mean_normalised_innovation_since(from_s));
        let guidance = &sim.scenario().guidance;
        let at_bound_s = time_at_bound_s(logged, from_s, (guidance.b_min_ft, guidance.b_max_ft));
        let mut warnings = Vec::new();
        if let Some(first) = episodes.first() {
            warnings.push(format!(
                "{off_target_frames} frames measured something other than the target ({} \
                 episodes, the first at t = {:.2} s)",
                episodes.len(),
                first.start_s
            ));
        }
        if let Some(nis) = nis_mean_last20s.filter(|n| *n > NIS_WARNING_RATIO * 3.0) {
            warnings.push(format!(
                "the filter's normalised innovations averaged {nis:.1} over the last 20 s, \
                 against 3 when its model holds: the measurements are not what it expects of \
                 the target (a false lock, or its model of the target's motion or of the \
                 follower's navigation is wrong)"
            ));
        }
        if at_bound_s > AT_BOUND_WARNING_FRACTION * WINDOW_S.min(sim.time_s()) {
            warnings.push(format!(
                "b̂ sat at a bound of [{}, {}] ft for {at_bound_s:.1} s of the last 20 s",
                guidance.b_min_ft, guidance.b_max_ft
            ));
        }
        Self {
            off_target_frames,
            nis_mean_last20s,
            b_hat_at_bound_last20s_s: at_bound_s,
            gated_out_frames: sim.estimator().filter().map_or(0, |f| f.gated_out()),
            bank_fused_frames: sim.estimator().filter().map_or(0, |f| f.bank_fused()),
            warnings,
        }
    }
}

/// Time the logged b̂ spent at either bound since `from_s`, s (each row counts until the
/// next).
fn time_at_bound_s(logged: &[Snapshot], from_s: f64, (min_ft, max_ft): (f64, f64)) -> f64 {
    let at_bound = |b: f64| b <= min_ft * (1.0 + 1e-9) || b >= max_ft * (1.0 - 1e-9);
    logged
        .windows(2)
        .filter(|w| w[0].t_s >= from_s - 1e-9 && at_bound(w[0].b_hat_ft))
        .fold(0.0, |sum, w| sum + w[1].t_s - w[0].t_s)
}
