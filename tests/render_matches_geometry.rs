//! The rendered silhouette is where `CameraIntrinsics::image_from_body` puts the mesh.
//!
//! Invariants: (1) every pixel whose centre lies inside the projected mesh by more than
//! `EPS_PX` is dark and every pixel whose centre lies outside by more than `EPS_PX` is sky
//! (1x sampling; `EPS_PX` covers the rasteriser's sub-pixel vertex snapping: Vulkan guarantees
//! at least 4 sub-pixel bits, 1/16 px, lavapipe uses 8); (2) hence the silhouette's bounding box
//! agrees with the projected vertices' bounding box within 1 px (a pixel is drawn when its
//! centre is covered, so each side can fall short by under a pixel); (3) a target behind the
//! camera leaves a sky-only frame; (4) 4x multisampling produces fractional edge pixels that
//! 1x sampling never does.

use std::f64::consts::FRAC_PI_2;

use crate::render_support::*;
use wingman::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use wingman::render::settings::DEFAULT_SKY_RGB;
use wingman::render::{CameraImage, RenderSettings, Renderer};

/// Rasteriser snapping margin, px (see the module docs).
const EPS_PX: f64 = 0.07;
/// Grey between the target's brightest face (100) and the sky (196).
const DARK_BELOW: u8 = 148;

fn render(cam: CameraIntrinsics, msaa: u32, p: &TargetPoseInCamera) -> CameraImage {
    let mut settings = RenderSettings::new(cam);
    settings.msaa_samples = msaa;
    let mut renderer = match Renderer::new(gpu(), settings, &aircraft()) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    };
    match renderer.render(p, 0) {
        Ok(f) => f.clone(),
        Err(e) => panic!("{e}"),
    }
}

fn poses() -> Vec<TargetPoseInCamera> {
    vec![
        pose([33.0, 8.0, 0.5], [0.0, 0.0, 0.0]),
        pose([60.0, -10.0, 5.0], [0.4, 0.2, 2.0]),
        pose([20.0, 3.0, -2.0], [-0.3, -0.5, 0.8]),
        pose([80.0, 20.0, 10.0], [0.6, 0.3, -0.7]),
        pose([12.0, 0.0, 0.0], [0.0, -1.2, 0.3]),
        // Partly outside the image on the right.
        pose([15.0, 7.5, 0.0], [0.0, 0.0, FRAC_PI_2]),
    ]
}

#[test]
fn silhouette_matches_cpu_projection_pixel_by_pixel() {
    let cam = CameraIntrinsics::from_hfov(320, 240, 60.0);
    let mesh = aircraft();
    for p in poses() {
        let frame = render(cam, 1, &p);
        let dark = dark_mask(&frame, DARK_BELOW);
        let coverage = cpu_coverage(&cam, &mesh, &p, EPS_PX);
        let (mut inside, mut edge) = (0, 0);
        for (k, (&d, &c)) in dark.iter().zip(&coverage).enumerate() {
            let (u, v) = (k as u32 % cam.width_px, k as u32 / cam.width_px);
            match c {
                Coverage::Inside => {
                    inside += 1;
                    assert!(
                        d,
                        "pose {p:?}: pixel ({u}, {v}) inside the projection is not dark"
                    );
                }
                Coverage::Outside => {
                    assert!(
                        !d,
                        "pose {p:?}: pixel ({u}, {v}) outside the projection is dark"
                    )
                }
                Coverage::Edge => edge += 1,
            }
        }
        assert!(
            inside > 30,
            "pose {p:?}: target too small to test ({inside} px)"
        );
        eprintln!("{inside} px inside, {edge} px within {EPS_PX} px of an edge");
    }
}

fn projected_bbox(cam: &CameraIntrinsics, p: &TargetPoseInCamera) -> (f64, f64, f64, f64) {
    let uv: Vec<(f64, f64)> = projected_vertices(cam, &aircraft(), p)
        .into_iter()
        .map(|x| x.expect("in front"))
        .collect();
    (
        uv.iter().map(|x| x.0).fold(f64::MAX, f64::min),
        uv.iter().map(|x| x.1).fold(f64::MAX, f64::min),
        uv.iter().map(|x| x.0).fold(f64::MIN, f64::max),
        uv.iter().map(|x| x.1).fold(f64::MIN, f64::max),
    )
}

#[test]
fn silhouette_bbox_and_centroid_match_projected_vertices() {
    let cam = CameraIntrinsics::from_hfov(320, 240, 60.0);
    let mesh = aircraft();
    // All but the last pose (clipped by the image edge).
    for (k, p) in poses()[..5].iter().enumerate() {
        let frame = render(cam, 1, p);
        let dark = dark_mask(&frame, DARK_BELOW);
        let drawn = mask_bbox(&dark, cam.width_px).expect("target visible");
        let projected = projected_bbox(&cam, p);
        // A pixel is drawn only if its centre is covered, so the drawn box never reaches more
        // than 0.5 px (+ snapping) beyond the projected vertices...
        let reach = 0.5 + EPS_PX;
        assert!(
            drawn.0 >= projected.0 - reach
                && drawn.1 >= projected.1 - reach
                && drawn.2 <= projected.2 + reach
                && drawn.3 <= projected.3 + reach,
            "pose {p:?}: drawn box {drawn:?} reaches beyond projected {projected:?}"
        );
        // ...and falls short by at most 1 px where the extremes are wider than a pixel. Poses 0
        // (wing edge-on) and 3 (80 ft away) have pointed tips thinner than a pixel, which may
        // cover no pixel centre near their vertex.
        if ![0, 3].contains(&k) {
            let gaps = [
                drawn.0 - projected.0,
                drawn.1 - projected.1,
                projected.2 - drawn.2,
                projected.3 - drawn.3,
            ];
            assert!(
                gaps.iter().all(|g| *g <= 1.0),
                "pose {p:?}: drawn box {drawn:?} vs projected {projected:?}"
            );
        }
        // Box and centroid vs the CPU rasterisation at exact pixel centres (no margin): they
        // can differ only in the few pixels whose centre is within EPS_PX of an edge, which
        // moves the centroid by well under 0.1 px for these silhouettes (≥ 30 px).
        let cpu: Vec<bool> = cpu_coverage(&cam, &mesh, p, 0.0)
            .iter()
            .map(|c| *c != Coverage::Outside)
            .collect();
        let cpu_box = mask_bbox(&cpu, cam.width_px).expect("visible");
        let sides = [
            (drawn.0, cpu_box.0),
            (drawn.1, cpu_box.1),
            (drawn.2, cpu_box.2),
            (drawn.3, cpu_box.3),
        ];
        assert!(
            sides.iter().all(|(a, b)| (a - b).abs() <= 1.0),
            "pose {p:?}: drawn box {drawn:?} vs CPU {cpu_box:?}"
        );
        let (cu, cv) = mask_centroid(&dark, cam.width_px).expect("visible");
        let (eu, ev) = mask_centroid(&cpu, cam.width_px).expect("visible");
        assert!(
            (cu - eu).abs() < 0.1 && (cv - ev).abs() < 0.1,
            "pose {p:?}: centroid ({cu:.3}, {cv:.3}) vs CPU ({eu:.3}, {ev:.3})"
        );
    }
}

#[test]
fn target_behind_the_camera_leaves_only_sky() {
    let cam = CameraIntrinsics::from_hfov(160, 120, 60.0);
    let sky = [
        DEFAULT_SKY_RGB[0],
        DEFAULT_SKY_RGB[1],
        DEFAULT_SKY_RGB[2],
        255,
    ];
    for p in [
        pose([-30.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
        pose([-5.0, 1.0, -1.0], [0.5, 0.5, 3.0]),
        // Wing tip 0.2 ft ahead of the camera: nearer than the near plane.
        pose([-3.8, 0.0, 0.0], [0.0, 0.0, FRAC_PI_2]),
    ] {
        for msaa in [1, 4] {
            let frame = render(cam, msaa, &p);
            // Compare counts, not frames: a failing `assert_eq!` on frames prints every byte.
            let not_sky = frame.rgba.chunks_exact(4).filter(|px| *px != sky).count();
            assert_eq!(not_sky, 0, "pose {p:?}, {msaa} samples");
        }
    }
}

#[test]
fn target_straddling_the_camera_plane_renders() {
    // Fuselage from 2.8 ft behind to 3.2 ft ahead of the camera: clipped, not a crash.
    let cam = CameraIntrinsics::from_hfov(160, 120, 60.0);
    let frame = render(cam, 4, &pose([1.0, 0.0, 0.5], [0.0, 0.0, 0.0]));
    assert!(dark_mask(&frame, DARK_BELOW).iter().any(|&d| d));
}

#[test]
fn four_samples_give_fractional_edge_pixels() {
    let cam = CameraIntrinsics::from_hfov(320, 240, 60.0);
    let p = pose([40.0, 2.0, 1.0], [0.3, 0.2, 0.5]);
    // Greys strictly between the brightest target face (100) and the sky (196), with a margin
    // of 2 levels for rounding: only a pixel partly covered can have them.
    let between = |f: &CameraImage| {
        f.grey_levels()
            .iter()
            .filter(|&&g| g > 102 && g < 194)
            .count()
    };
    let one = render(cam, 1, &p);
    let four = render(cam, 4, &p);
    assert_eq!(between(&one), 0);
    let dark = dark_mask(&four, DARK_BELOW).iter().filter(|&&d| d).count();
    assert!(
        between(&four) * 5 > dark,
        "{} fractional px for {dark} dark px",
        between(&four)
    );
}
