//! formation_scene.toml at the slot, where the target flies at the follower's level and is
//! seen on the horizon's haze and the distant fields (docs/findings.md, The ring in a
//! tracking window). Held-out stream 11, 70 s. Until the local colour model's ring was taken
//! on the tracking window's border, the ring's points about a wing pixel lay beyond the
//! window or on the target itself, the wings were explained as background, and fragments
//! were measured: on the build before, lengths under 0.7 of the silhouette's in 67 of 751
//! frames over 30-55 s, r̂ drifted 5 ft long, and at 55-58 s the follower closed from 31.5 to
//! 15 ft and lost the target.

use crate::common;

use std::collections::BTreeMap;
use wingman::output::summary::RunStatus;
use wingman::vision::BlobStatus;

/// Invariant: the run holds the slot (no frame off the target, RMS over 50-70 s under 3 ft
/// per axis, b̂ within 5%) and the length at the slot (30-70 s) reads under 0.7 of the
/// silhouette's in fewer than 4% of the frames. Measured: 0 off, RMS [2.35, 1.39, 1.20] ft,
/// b̂ 7.90 ft, short lengths in 0 of 1199 frames (before the bearing gate on fragments: RMS
/// [2.36, 1.33, 1.18] ft, b̂ 7.85 ft, 1 short; 0 before fragments were told apart by their
/// distance, with RMS [2.34, 1.38, 1.24] ft and b̂ 7.92 ft; 14 before a whole-covered pixel was
/// always the target's colour: docs/findings.md, A whole-covered pixel's rounding); on the
/// build before that, with the ring's points beyond the window left out (the gate's
/// re-opening and the memory's exclusion about the prediction kept), the run still
/// completed (RMS [2.58, 1.29, 1.23] ft), but 240 of 1199 lengths were short.
#[test]
fn the_target_on_the_horizon_is_held_at_the_slot() {
    let report = common::run(
        "formation_scene",
        &["run.seed=11", "run.duration_s=70", "output.frames_every=0"],
    );
    let mut frames = BTreeMap::new();
    for s in &report.logged {
        if let Some(f) = &s.frame {
            frames.entry(f.index).or_insert(*f);
        }
    }
    let at_slot: Vec<_> = frames.values().filter(|f| f.t_s >= 30.0).collect();
    let short = at_slot
        .iter()
        .filter(|f| match (f.status, f.measured, f.truth) {
            (BlobStatus::Ok, Some(m), Some(t)) => m.b_i_px < 0.7 * t.b_i_px,
            _ => false,
        })
        .count();
    let s = &report.summary;
    println!(
        "{:?} at {:.1} s, {} frames off the target, {} lost, b̂ {:.3} ft, RMS {:?} ft; \
         {short} of {} lengths at the slot short",
        s.status,
        s.duration_s,
        s.track_check.off_target_frames,
        s.lost_frames,
        s.b_hat_final_ft,
        s.rms_error_last20s_ft,
        at_slot.len(),
    );
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    assert!(s.track_check.off_target_frames <= 5);
    assert!(s.rms_error_last20s_ft.iter().all(|&rms| rms < 3.0));
    assert!((s.b_hat_final_ft / 8.0 - 1.0).abs() < 0.05);
    assert!(
        (short as f64) < 0.04 * at_slot.len() as f64,
        "{short} short"
    );
}
