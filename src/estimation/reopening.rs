//! The gate re-opened (docs/equations.md, The gate re-opened): frames the innovation and
//! bearing gates keep out, counted in streaks that agree with each other, re-open the gate
//! when a streak lasts long enough.

use super::kalman::{Innovation, TargetFilter};
use crate::frames::{Mat3, Vec3};

/// When frames the gates keep out re-open them (docs/equations.md, The gate
/// re-opened): a streak of them that agree with each other, lasting `after_s`
/// (`estimator.gate_reopen_s`; ∞: never), on a frame whose |r*| is within `range_ratio` of
/// the prediction's |r̂| (`estimator.gate_reopen_range_ratio`).
#[derive(Debug, Clone, Copy)]
pub(super) struct GateReopening {
    pub(super) after_s: f64,
    pub(super) range_ratio: f64,
    /// The frames kept out since the last fused one that agree with each other.
    pub(super) streak: Option<KeptOutStreak>,
}

/// A frame the gates kept out: its capture time, s, r*, covariance and innovation.
pub(super) struct KeptOutFrame<'a> {
    pub(super) t_s: f64,
    pub(super) r_star: &'a Vec3,
    pub(super) covariance: &'a Mat3,
    pub(super) innovation: &'a Innovation,
}

impl GateReopening {
    /// Ends the streak: a frame was fused.
    pub(super) fn end_streak(&mut self) {
        self.streak = None;
    }

    /// Adds `frame` to the streak (a frame without a finite innovation breaks it) and, when
    /// the streak has lasted `after_s` and the frame's range is within `range_ratio` of
    /// `predicted`'s, updates `predicted` on it with its kinematics widened: the innovation
    /// of that update (None: the gate stays shut).
    pub(super) fn take(
        &mut self,
        predicted: &mut TargetFilter,
        frame: &KeptOutFrame,
        gate: f64,
    ) -> Option<Innovation> {
        let innovation = frame.innovation;
        self.streak = innovation.normalised_sq.is_finite().then(|| {
            KeptOutStreak::extended(self.streak, gate, frame.t_s, frame.r_star, frame.covariance)
        });
        let due = self
            .streak
            .is_some_and(|streak| frame.t_s - streak.since_s >= self.after_s);
        if !due {
            return None;
        }
        // A range far off the prediction's is not a drifted prediction but something else
        // measured steadily (the target's blob merged with a road).
        let range_off = predicted.range_off(frame.r_star);
        if range_off > self.range_ratio.ln() || range_off.is_nan() {
            return None;
        }
        // The prediction, not the frames, is what is wrong: widened until this frame's
        // νᵀ S⁻¹ ν is about its 3 degrees of freedom (and its bearing's about its 2), it takes
        // it.
        let factor = (innovation.normalised_sq / 3.0).max(innovation.bearing_normalised_sq / 2.0);
        predicted.widen_kinematics(factor);
        Some(predicted.update(frame.r_star, frame.covariance))
    }
}

/// Frames kept out by the gates since the last fused one, each within the gate of
/// the one before (docs/equations.md, The gate re-opened). Fragments and blobs of the ground
/// jump between frames; the whole target kept out by a lost prediction does not.
#[derive(Debug, Clone, Copy)]
pub(super) struct KeptOutStreak {
    /// Capture time of its first frame, s.
    since_s: f64,
    /// Its last frame's r*.
    r_star: Vec3,
    /// Its last frame's covariance.
    covariance: Mat3,
}

impl KeptOutStreak {
    /// `streak` with a frame the gate kept out added, when the frame agrees with its last one
    /// ((r*ₖ - r*ₖ₋₁)ᵀ (Rₖ + Rₖ₋₁)⁻¹ (·) ≤ `gate`); else a streak the frame begins.
    fn extended(
        streak: Option<Self>,
        gate: f64,
        t_s: f64,
        r_star: &Vec3,
        covariance: &Mat3,
    ) -> Self {
        let agrees = |last: &Self| {
            let step = r_star - last.r_star;
            (covariance + last.covariance)
                .try_inverse()
                .is_some_and(|s_inv| (step.transpose() * s_inv * step)[(0, 0)] <= gate)
        };
        Self {
            since_s: streak.filter(agrees).map_or(t_s, |last| last.since_s),
            r_star: *r_star,
            covariance: *covariance,
        }
    }
}
