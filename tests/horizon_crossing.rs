//! The measurement across the horizon: formation_scene.toml's world (no cloud) with the target
//! flying straight 80 ft ahead of the follower and 20 ft above it, descending at 10 ft/s, so
//! that within 3.5 s it passes from the sky through the horizon line into the ground as the
//! camera sees it.
//!
//! Invariant: on the frames whose target lies within 3° of the horizon (its true elevation
//! from the camera's level; the 8 ft target subtends about ±3° at 80 ft, so it straddles the
//! line), at least 75% are measured `Ok` with the maximal length within 15% of the true
//! one and the centroid within 5 px of the projected reference point, and the run leaves at
//! most 2 frames unmeasured (the first only sets up the motion segmentation's memory).
//! Measured over streams 1-6 (docs/findings.md, The scene and the vision against it): 79-100%
//! of the frames across, 1-2 unmeasured; before the ring skipped the target's own pixels,
//! 30-85% and 1-31 (stream 4, this test's: 32% and 31).

use crate::common;

use std::collections::BTreeMap;

use wingman::vision::BlobStatus;

/// Half the band about the horizon whose frames count as across it, deg.
const ACROSS_DEG: f64 = 3.0;

#[test]
fn the_measurement_holds_across_the_horizon() {
    let report = common::run(
        "formation_scene",
        &[
            "output.frames_every=0",
            "run.seed=4",
            "run.duration_s=3.5",
            "run.stop_after_lost_s=0",
            "scene.cloud_coverage=0.0",
            "target.motion=\"straight\"",
            "target.straight_velocity_fps=[50.0, 0.0, 10.0]",
            "target.initial_position_ft=[80.0, 0.0, -20.0]",
        ],
    );
    // Each frame once, with the relative position of the row that first logged it.
    let mut frames = BTreeMap::new();
    for s in &report.logged {
        if let Some(f) = &s.frame {
            frames.entry(f.index).or_insert((*f, s.relative_ned_ft));
        }
    }
    let across: Vec<_> = frames
        .values()
        .filter(|(_, r)| (-r.z).atan2(r.x.hypot(r.y)).to_degrees().abs() < ACROSS_DEG)
        .collect();
    let held = across
        .iter()
        .filter(|(f, _)| {
            let (Some(m), Some(t)) = (f.measured, f.truth) else {
                return false;
            };
            f.status == BlobStatus::Ok
                && (m.b_i_px / t.b_i_px - 1.0).abs() <= 0.15
                && (m.y_i_px - t.y_i_px).hypot(m.z_i_px - t.z_i_px) <= 5.0
        })
        .count();
    println!(
        "{held} of {} frames across the horizon held; {} unmeasured in the run",
        across.len(),
        report.summary.lost_frames
    );
    assert!(across.len() >= 15, "{} frames across", across.len());
    assert!(
        held as f64 >= 0.75 * across.len() as f64,
        "{held} of {} held",
        across.len()
    );
    assert!(
        report.summary.lost_frames <= 2,
        "{}",
        report.summary.lost_frames
    );
}
