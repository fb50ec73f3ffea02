//! Rendered pixels measured by the image pipeline agree with the geometry.
//!
//! Over a grid of 60 relative poses (ranges 20-250 ft, bearings and elevations across the
//! field of view where the whole target fits in the image, six target attitudes) at 640x480, 60° field of view, 4x multisampling:
//! (1) the measured centroid is within 0.5 px of the exact centroid of the projected
//! silhouette (computed on the CPU by 8x8 supersampling of the projected triangles), and for
//! symmetric views (the target on the optical axis seen square from above, a mirror-symmetric
//! planform: off the axis, perspective makes even a symmetric silhouette lopsided) the measured centroid's
//! column is within 0.5 px of the projected target centre's; (2) the measured maximal length
//! is within 1.5 px of the true maximal length of the projected mesh (`vision::truth`).
//!
//! The poses are `render_support::sixty_poses`. Attitudes keep the wing at least 15° from edge-on: at 250 ft a wing 0.12 ft thick seen
//! edge-on projects to a quarter of a pixel, which no camera resolves; that loss is a finding
//! of the camera-in-the-loop scenario (its length error is in its summary), not hidden here.

use crate::render_support::*;
use wingman::render::TargetMesh;
use wingman::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use wingman::vision::{BlobStatus, image_truth};

/// Sub-samples per pixel side of the CPU reference silhouette.
const SUPERSAMPLE: usize = 8;

/// Exact-coverage centroid (u, v) of the projected mesh, by supersampling each triangle's
/// bounding box (every vertex must be in front of the camera).
fn silhouette_centroid(
    cam: &CameraIntrinsics,
    mesh: &TargetMesh,
    pose: &TargetPoseInCamera,
) -> (f64, f64) {
    let (w, h) = (cam.width_px as usize, cam.height_px as usize);
    let (sw, sh) = (w * SUPERSAMPLE, h * SUPERSAMPLE);
    let mut covered = vec![false; sw * sh];
    let uv: Vec<(f64, f64)> = projected_vertices(cam, mesh, pose)
        .into_iter()
        .map(|p| p.expect("vertex in front of the camera"))
        .collect();
    let step = 1.0 / SUPERSAMPLE as f64;
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| uv[i as usize]);
        let area2 = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
        if area2.abs() < 1e-12 {
            continue;
        }
        let edge = |p0: (f64, f64), p1: (f64, f64), p: (f64, f64)| {
            area2.signum() * ((p1.0 - p0.0) * (p.1 - p0.1) - (p1.1 - p0.1) * (p.0 - p0.0))
        };
        let to_sub = |x: f64, n: usize| ((x / step).floor().max(0.0) as usize).min(n);
        let (su0, su1) = (
            to_sub(a.0.min(b.0).min(c.0), sw),
            to_sub(a.0.max(b.0).max(c.0) + step, sw),
        );
        let (sv0, sv1) = (
            to_sub(a.1.min(b.1).min(c.1), sh),
            to_sub(a.1.max(b.1).max(c.1) + step, sh),
        );
        for sv in sv0..sv1 {
            for su in su0..su1 {
                let p = ((su as f64 + 0.5) * step, (sv as f64 + 0.5) * step);
                if edge(a, b, p) >= 0.0 && edge(b, c, p) >= 0.0 && edge(c, a, p) >= 0.0 {
                    covered[sv * sw + su] = true;
                }
            }
        }
    }
    let (mut su, mut sv, mut n) = (0.0, 0.0, 0.0);
    for (k, _) in covered.iter().enumerate().filter(|(_, c)| **c) {
        su += ((k % sw) as f64 + 0.5) * step;
        sv += ((k / sw) as f64 + 0.5) * step;
        n += 1.0;
    }
    (su / n, sv / n)
}

#[test]
fn measured_centroid_and_length_match_geometry_over_60_poses() {
    let mut rig = MeasuringRig::new();
    let cam = rig.cam;
    let mut checked = 0;
    let mut failures = Vec::new();
    let (mut worst_centroid, mut worst_length) = (0.0f64, 0.0f64);
    for case in sixty_poses() {
        let PoseCase {
            range_ft,
            bearing_deg,
            elevation_deg,
            attitude,
            pose: p,
        } = case;
        let symmetric = attitude == POSE_ATTITUDES[0];
        let m = rig.measure(&p);
        let label = format!(
            "range {range_ft} bearing {bearing_deg} elevation {elevation_deg} attitude {attitude:?}"
        );
        if m.status != BlobStatus::Ok {
            failures.push(format!("{label}: status {:?}", m.status));
            continue;
        }
        let truth = image_truth(&rig.mesh.vertices_ft, &p, &cam).expect("target in front");
        let (cu, cv) = silhouette_centroid(&cam, &rig.mesh, &p);
        let centroid_error = (m.centroid_u_px - cu).hypot(m.centroid_v_px - cv);
        if centroid_error >= 0.5 {
            failures.push(format!("{label}: centroid off by {centroid_error:.3} px"));
        }
        if symmetric && bearing_deg == 0.0 && elevation_deg == 0.0 {
            let (u_centre, _) = cam.pixel_from_image(truth.y_i_px, truth.z_i_px);
            let lateral = (m.centroid_u_px - u_centre).abs();
            if lateral >= 0.5 {
                failures.push(format!("{label}: column off the centre by {lateral:.3} px"));
            }
        }
        let length_error = (m.max_length_px - truth.b_i_px).abs();
        if length_error >= 1.5 {
            failures.push(format!(
                "{label}: length {:.2} vs true {:.2} px",
                m.max_length_px, truth.b_i_px
            ));
        }
        worst_centroid = worst_centroid.max(centroid_error);
        worst_length = worst_length.max(length_error);
        checked += 1;
    }
    assert!(checked >= 50, "only {checked} poses");
    eprintln!(
        "{checked} poses: worst centroid error {worst_centroid:.3} px, worst length error {worst_length:.3} px"
    );
    assert!(
        failures.is_empty(),
        "{} of {checked} poses fail:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
