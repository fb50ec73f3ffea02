//! The innovation gate re-opened (`estimator.gate_reopen_s`; docs/equations.md, The gate
//! re-opened): a filter whose prediction lost the target keeps every frame out for good
//! unless a streak of frames that agree with each other, kept out for the stated time, is
//! taken; a streak of frames that jump between two readings (fragments, blobs of the ground)
//! is not, nor one whose range is more than `estimator.gate_reopen_range_ratio` off the
//! prediction's. A frame kept out still counts as measured (for the gimbal's search). The
//! bearing gate (`estimator.bearing_gate`) keeps out fragments beside the target that the
//! innovation gate takes.
//!
//! A synthetic pass: the follower flies north at 50 ft/s weaving ±6 ft across its track
//! (6 s period), the 8 ft target 32 ft ahead and 8 ft aside flying with it; exact pixels at
//! 30 frames/s into the Kalman filter with the seed's apparent size model and the gate at
//! 16.3. After 30 s the frames change (below); the check is r̂ against the target's r = R/b
//! 1 s on. (Left alone, the prediction's covariance grows until the frames pass the gate
//! after about 3 s here; a follower flying on the lost prediction for 3 s at its slot had
//! lost the target by then: docs/findings.md, The ring in a tracking window.)

use crate::common;

use wingman::estimation::{KalmanTracker, TargetTracker};
use wingman::frames::{Mat3, Vec3};
use wingman::render::camera::CameraIntrinsics;
use wingman::scenario::{EstimatorSection, SizeModel};
use wingman::sensing::transform::image_from_relative_position;
use wingman::vision::ImageMeasurement;

const SIZE_FT: f64 = 8.0;
const SPEED_FPS: f64 = 50.0;
const FRAME_HZ: f64 = 30.0;

/// What the frames after 30 s show.
#[derive(Clone, Copy)]
enum After {
    /// The target 6 ft farther than the filter's motion model allows it to move (its
    /// prediction is then wrong, as fragments that passed the gate leave it).
    Displaced,
    /// A length 30% long and one 25% short in turn, the target where it was.
    Alternating,
    /// Every length 2.5 times the target's, the target where it was: a blob merged with a
    /// road, which agrees with itself from frame to frame.
    Merged,
    /// Every frame a fragment a 20th of the target's length, 40 px beside it (at the slot
    /// against fields, formation_scene.toml's held-out stream 15 at 57-73 s, where the
    /// vision measured such fragments in 17 frames).
    Fragments,
}

/// The filter of the pass: the seed's apparent size model, the gate at 16.3, re-opened after
/// `reopen_s`.
fn gated(reopen_s: f64) -> EstimatorSection {
    EstimatorSection {
        size_model: SizeModel::Apparent,
        jerk_psd: 1e-4,
        innovation_gate: 16.3,
        gate_reopen_s: reopen_s,
        ..EstimatorSection::default()
    }
}

/// Flies the pass for 31 s and returns |r̂ - r| / |r| at the end (r = R/b of the target as it
/// really is), the frames the gate kept out, and when the tracker last had a measurement.
fn fly(reopen_s: f64, after: After) -> (f64, u64, Option<f64>) {
    fly_with(&gated(reopen_s), after)
}

/// [`fly`] with the filter of `section`.
fn fly_with(section: &EstimatorSection, after: After) -> (f64, u64, Option<f64>) {
    let focal = CameraIntrinsics::from_hfov(640, 480, 60.0).focal_px;
    let mut tracker = KalmanTracker::new(section, focal, 4.0, (1.0, 30.0));
    let camera_from_ned = Mat3::identity();
    let weave = |t: f64| 6.0 * (std::f64::consts::TAU * t / 6.0).sin();
    let weave_rate =
        |t: f64| 6.0 * std::f64::consts::TAU / 6.0 * (std::f64::consts::TAU * t / 6.0).cos();
    let mut error = f64::NAN;
    for index in 0..=(31.0 * FRAME_HZ) as u64 {
        let t_s = index as f64 / FRAME_HZ;
        let follower = Vec3::new(SPEED_FPS * t_s, weave(t_s), 0.0);
        let displaced = matches!(after, After::Displaced) && t_s >= 30.0;
        let extra_ft = if displaced { 6.0 } else { 0.0 };
        let target = Vec3::new(SPEED_FPS * t_s + 32.0 + extra_ft, 8.0, 0.0);
        let relative = target - follower;
        let exact = image_from_relative_position(&relative, &camera_from_ned, SIZE_FT, focal)
            .expect("ahead");
        let fragment = matches!(after, After::Fragments) && t_s >= 30.0;
        let (length_factor, aside_px) = match after {
            After::Alternating if t_s >= 30.0 => ([1.3, 0.75][(index % 2) as usize], 0.0),
            After::Merged if t_s >= 30.0 => (2.5, 0.0),
            _ if fragment => (0.05, 40.0),
            _ => (1.0, 0.0),
        };
        let measured = ImageMeasurement {
            b_i_px: exact.b_i_px * length_factor,
            y_i_px: exact.y_i_px + aside_px,
            ..exact
        };
        let record =
            common::north_camera_frame((index, t_s), measured, exact, focal, follower, relative);
        tracker.fuse_frame(&record, &Vec3::new(SPEED_FPS, weave_rate(t_s), 0.0));
        let truth = relative / SIZE_FT;
        let estimate = tracker.estimate_at(t_s, &follower).expect("running");
        error = (estimate.r - truth).norm() / truth.norm();
    }
    (error, tracker.gated_out(), tracker.last_measured_s())
}

/// Invariant: after the displacement, the filter without re-opening keeps every frame of
/// the second out and stays over 10% off (measured 15.8%); re-opened after 0.5 s it takes
/// them and ends within 5% of the target (measured 2.5%: the jump it took still settling in
/// r̂'s velocity).
#[test]
fn a_consistent_streak_reopens_the_gate() {
    let (shut, shut_out, _) = fly(0.0, After::Displaced);
    let (open, open_out, _) = fly(0.5, After::Displaced);
    println!("never re-opened: {shut:.4} off, {shut_out} kept out; 0.5 s: {open:.4}, {open_out}");
    assert!(shut > 0.1 && shut_out > 25, "{shut}, {shut_out}");
    assert!(open < 0.05 && open_out < 20, "{open}, {open_out}");
}

/// Invariant: frames that jump between a long and a short reading, each off the prediction,
/// never make a streak: re-opening after 0.5 s, the filter keeps every one of the second
/// out and stays on the target (within 2%).
#[test]
fn frames_that_disagree_do_not_reopen_it() {
    let (error, kept_out, _) = fly(0.5, After::Alternating);
    println!("alternating lengths: {error:.4} off, {kept_out} kept out");
    assert!(error < 0.02, "{error}");
    assert!(kept_out > 25, "{kept_out}");
}

/// Invariant: a frame the gate keeps out is still a measurement of something where the
/// target was looked for, so the gimbal's search (which starts once no measurement has come
/// for `camera.gimbal.search_after_s`) does not start while the gate keeps frames out.
/// With the apparent size model nothing else moves the filter's own time, which stayed at
/// the last fused frame (30 s) before `last_measured_s` was kept for itself.
#[test]
fn a_frame_kept_out_counts_as_measured() {
    let (_, kept_out, last_measured_s) = fly(0.0, After::Displaced);
    assert!(kept_out > 25, "{kept_out}");
    assert_eq!(last_measured_s, Some(31.0));
}

/// Invariant: a streak whose length is 2.5 times the prediction's (a blob merged with a
/// road: formation_scene.toml's streams 20, 23 and 24 in the approach) agrees with itself, but
/// it does not re-open the gate with the default bound (a range within a factor of 2 of the
/// prediction's): r̂ stays within 5% of the target. Without the bound it re-opens, and r̂
/// reads the target at 40% of its range.
#[test]
fn a_streak_far_off_the_predicted_range_does_not_reopen_it() {
    let (bounded, bounded_out, _) = fly(0.5, After::Merged);
    let unbounded_section = EstimatorSection {
        gate_reopen_range_ratio: 1e6,
        ..gated(0.5)
    };
    let (unbounded, unbounded_out, _) = fly_with(&unbounded_section, After::Merged);
    println!(
        "merged: bounded {bounded:.4} off, {bounded_out} kept out; unbounded {unbounded:.4}, {unbounded_out}"
    );
    assert!(
        bounded < 0.05 && bounded_out > 25,
        "{bounded}, {bounded_out}"
    );
    assert!(unbounded > 0.3, "{unbounded}");
}

/// Invariant: fragments a 20th of the target's length 40 px beside it pass the innovation
/// gate (their short length puts them far along their own rays, where the range is uncertain
/// enough to explain the innovation) and pull r̂ off the target (measured: every one fused,
/// 0.9% off after 1 s); the bearing gate at 13.8 (`estimator.bearing_gate`; docs/equations.md,
/// The bearing gate) keeps every one out (31), and r̂ stays on the target's prediction
/// (0.0000). Their streak does not re-open the gate: their range is 20 times the prediction's.
#[test]
fn the_bearing_gate_keeps_fragments_beside_the_target_out() {
    let (without, without_out, _) = fly(0.5, After::Fragments);
    let bearing = EstimatorSection {
        bearing_gate: 13.8,
        ..gated(0.5)
    };
    let (with, with_out, _) = fly_with(&bearing, After::Fragments);
    println!(
        "fragments: innovation gate alone {without:.4} off, {without_out} kept out; \
         with the bearing gate {with:.4}, {with_out}"
    );
    assert!(with < 1e-3 && with_out == 31, "{with}, {with_out}");
    assert!(
        without > 5e-3 && without_out == 0,
        "{without}, {without_out}"
    );
}
