//! formation_scene.toml against the ground, with and without the target's colour as the
//! explanation of the pixels the remembered background does not explain
//! (`camera.target_colour_tolerance_deg`; docs/findings.md, The target's colour as the
//! pixel's explanation). Stream 14, held out (the tolerance, 4°, was set on streams 1-10
//! over 140 s, where a run lasted a median 57 s with it against 19 s without), 30 s, the
//! target against fields and roads from 200 ft: with the colour the run completes with no
//! frame measured off the target (443 frames against ground, 11 unmeasured, the centroid
//! 2.4 px RMS from the silhouette's there); without it the ground takes the track and the
//! run ends in a false lock at 10.1 s (measured).
//!
//! The spread over the held-out streams 11-20, 30 s each (measured): with the colour all ten
//! complete, frames off the target a median 0 and at worst 21 (stream 12), the centroid
//! against ground a median 2.6 px RMS and at worst 4.1 (stream 19); without it eight end in
//! a false lock at 10.1-23.3 s, and the centroid against ground reads a median 51 px.
//!
//! Since formation_scene.toml takes its expected length from the estimator (docs/findings.md,
//! The ring in a tracking window), stream 14 measures 3 frames off the target in its
//! approach, and those frames move its centroid against ground to 6.9 px RMS (1.98 px with
//! the last length as the expected one, on the same build); since a whole-covered pixel is
//! always a mixture with the target's colour (docs/findings.md, A whole-covered pixel's
//! rounding), 1 frame and 4.85 px; since a core pixel must be a mixture with it
//! (docs/findings.md, A changed background inside the blob), 1 frame and 4.49 px; since
//! fragments are told apart by their distance (docs/findings.md, Fragments told apart by
//! their distance), 1.66 px; since the bearing gate weighs fragments (docs/findings.md, The
//! bearing gate: a fragment's length cannot explain its bearing), 1.64 px. The
//! bounds below are stream 14's with room for the last bits a GPU's pixels differ by: at
//! most 5 frames off the target, the centroid under 8 px against ground. Since the bearing
//! gate, the run without the colour no longer ends in a false lock (it did at 10.1 s) but
//! measures 10 frames off the target: without the colour the run ends in a false lock or
//! measures more than the 5 frames off the target that bound the run with it.

use crate::common;

use std::collections::BTreeMap;
use std::sync::OnceLock;
use wingman::output::RunReport;
use wingman::output::summary::RunStatus;
use wingman::sensing::camera::FrameBackground;
use wingman::vision::BlobStatus;

/// formation_scene.toml on stream 14 for 30 s, with `overrides`.
fn scene(overrides: &[&str]) -> RunReport {
    let mut all = vec!["run.seed=14", "run.duration_s=30", "output.frames_every=0"];
    all.extend_from_slice(overrides);
    common::run("formation_scene", &all)
}

/// The shipped scenario's run, shared by the tests that read it.
fn shipped() -> &'static RunReport {
    static SHIPPED: OnceLock<RunReport> = OnceLock::new();
    SHIPPED.get_or_init(|| scene(&[]))
}

#[test]
fn the_targets_colour_keeps_the_track_against_the_ground() {
    let shipped = shipped();
    let without = scene(&["camera.target_colour_tolerance_deg=0"]);
    let (s, w) = (&shipped.summary, &without.summary);
    println!(
        "with the colour: {:?} at {:.1} s, {} frames off the target, ground {:?}, b̂ {:.2}; \
         without: {:?} at {:.1} s, {} off",
        s.status,
        s.duration_s,
        s.track_check.off_target_frames,
        s.background.as_ref().map(|b| &b.ground),
        s.b_hat_final_ft,
        w.status,
        w.duration_s,
        w.track_check.off_target_frames,
    );
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    assert!(s.track_check.off_target_frames <= 5);
    let ground = s.background.as_ref().map(|b| b.ground);
    let centroid_px = ground.and_then(|g| g.centroid_vs_silhouette_rms_px);
    assert!(centroid_px.is_some_and(|px| px < 8.0), "{ground:?}");
    let off = w.track_check.off_target_frames;
    assert!(
        w.status == RunStatus::FalseLock || off > 5,
        "{:?}, {off} off",
        w.status
    );
}

/// Invariant: a frame is trusted (`meas_trusted`, the summary's `background.*.trusted`) when
/// the estimator took it: every frame not `Ok` is untrusted, the untrusted `Ok` frames are
/// exactly those the gates kept out, and the frames against ground the estimator
/// took are at most those measured there, and at most as far from the silhouette's centroid,
/// as the held frames' own columns say too (measured on stream 14: 484 frames against
/// ground, 1 of them lost, 460 trusted; 1.64 px RMS over every `Ok` frame, 0.97 px over the
/// trusted ones; the gates kept out 23 of the 899
/// frames held. Before the bearing gate: 478 frames, 1 lost, 457 trusted, 1.66 and 1.01 px,
/// 20 kept out; before fragments were told apart by their distance: 448 frames, 3 lost, 408
/// trusted, 4.49 and 2.24 px, 40 kept out).
#[test]
fn a_trusted_frame_is_one_the_estimator_took() {
    let report = shipped();
    let mut held: BTreeMap<u64, (BlobStatus, bool)> = BTreeMap::new();
    for snapshot in &report.logged {
        if let Some(frame) = snapshot.frame {
            let trusted = snapshot.frame_trusted.expect("a held frame is settled");
            held.insert(frame.index, (frame.status, trusted));
        }
    }
    let not_ok_trusted = held
        .values()
        .filter(|(status, trusted)| *status != BlobStatus::Ok && *trusted)
        .count();
    let kept_out = held
        .values()
        .filter(|(status, trusted)| *status == BlobStatus::Ok && !*trusted)
        .count() as u64;
    let s = &report.summary;
    let ground = s.background.as_ref().expect("a world scene").ground;
    println!(
        "{} frames held, {kept_out} kept out (gate: {}), ground {ground:?}",
        held.len(),
        s.track_check.gated_out_frames
    );
    assert_eq!(not_ok_trusted, 0);
    assert!(kept_out > 0);
    assert_eq!(kept_out, s.track_check.gated_out_frames);
    assert!(ground.trusted > 0 && ground.trusted <= ground.frames - ground.lost);
    let (all, trusted) = (
        ground.centroid_vs_silhouette_rms_px.expect("measured"),
        ground
            .trusted_centroid_vs_silhouette_rms_px
            .expect("trusted"),
    );
    assert!(trusted <= all, "{trusted} > {all}");
    // The bar (1 px RMS of the silhouette's centroid over the frames against ground)
    // holds on this run too: 0.97 px on lavapipe. The bound, 1.2 px, is a choice, not a
    // measurement: a GPU's pixels differ from lavapipe's in the last bits and move a closed
    // loop's frames (docs/findings.md, The scene's frame in the tracking region, and on a
    // GPU), and this run has not been measured on one. Over 140 s formation_scene.toml's
    // streams 1-10 read 0.905 px pooled and 11-20 0.902 px (docs/findings.md, The centroid
    // bar, as the scene runs now).
    assert!(
        trusted < 1.2,
        "{trusted} px over the trusted frames against ground"
    );
    // The telemetry's frames (`meas_background`, `centroid_vs_silhouette_px`) add up to the
    // summary's figure.
    let mut against_ground: BTreeMap<u64, f64> = BTreeMap::new();
    for snapshot in &report.logged {
        if let (Some(frame), Some(true)) = (snapshot.frame, snapshot.frame_trusted)
            && frame.background == Some(FrameBackground::Ground)
        {
            let off_px = frame
                .centroid_vs_silhouette_px
                .expect("a trusted frame's distance");
            against_ground.insert(frame.index, off_px);
        }
    }
    assert_eq!(against_ground.len() as u64, ground.trusted);
    let per_frame = common::rms(against_ground.values().copied());
    assert!(
        (per_frame - trusted).abs() < 1e-9 * trusted,
        "{per_frame} against {trusted}"
    );
}
