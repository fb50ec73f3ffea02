//! Several aircraft in one frame: the renderer draws the target and every other aircraft
//! given to it (`Renderer::set_other_aircraft`), each where the pinhole projection of its own
//! pose and scale puts the mesh, the nearer surface in front.
//!
//! Invariants: (1) with one sample per pixel, every pixel whose centre lies inside the CPU
//! projection of any aircraft (the target's mesh, scaled, at its pose) by more than `EPS_PX`
//! is dark and every pixel outside all of them by more than `EPS_PX` is sky; (2) the frame
//! does not depend on which aircraft is the target and which the other (depth, not drawing
//! order, decides what is in front); (3) the frame drawn in a window around every aircraft
//! is the frame drawn whole, and a frame drawn in a region of the image (the tracking
//! window) holds there the whole frame's pixels, the aircraft outside it left undrawn; (4) an
//! aircraft wholly behind the camera changes nothing.

use crate::render_support::*;
use wingman::render::camera::{AircraftPose, CameraIntrinsics, TargetPoseInCamera};
use wingman::render::{CameraImage, ImageRegion, RenderSettings, Renderer};

/// Rasteriser snapping margin, px (as tests/render_matches_geometry.rs).
const EPS_PX: f64 = 0.07;
/// Grey between the target's brightest face (100) and the sky (196).
const DARK_BELOW: u8 = 148;

fn render(
    cam: CameraIntrinsics,
    msaa: u32,
    windowed: bool,
    target: &TargetPoseInCamera,
    others: &[AircraftPose],
) -> CameraImage {
    let mut settings = RenderSettings::new(cam);
    settings.msaa_samples = msaa;
    settings.target_window = windowed;
    let mut renderer = Renderer::new(gpu(), settings, &aircraft()).expect("renderer");
    renderer.set_other_aircraft(others);
    renderer.render(target, 0).expect("frame").clone()
}

/// A target and two others: a larger one beside it, a smaller one partly in front of it.
fn scene() -> (TargetPoseInCamera, Vec<AircraftPose>) {
    let target = pose([60.0, 2.0, 1.0], [0.3, 0.9, 0.4]);
    let others = vec![
        AircraftPose {
            pose: pose([90.0, -25.0, -6.0], [0.0, 0.7, -0.5]),
            scale: 1.5,
        },
        AircraftPose {
            pose: pose([40.0, 3.5, 1.5], [-0.4, 1.1, 2.0]),
            scale: 0.6,
        },
    ];
    (target, others)
}

#[test]
fn every_aircraft_is_where_its_projection_puts_it() {
    let cam = CameraIntrinsics::from_hfov(320, 240, 60.0);
    let (target, others) = scene();
    let frame = render(cam, 1, false, &target, &others);
    let dark = dark_mask(&frame, DARK_BELOW);
    let mut coverages = vec![cpu_coverage(&cam, &aircraft(), &target, EPS_PX)];
    for other in &others {
        let mesh = aircraft().scaled(other.scale);
        coverages.push(cpu_coverage(&cam, &mesh, &other.pose, EPS_PX));
    }
    let mut inside_of = vec![0usize; coverages.len()];
    for (k, &d) in dark.iter().enumerate() {
        let (u, v) = (k as u32 % cam.width_px, k as u32 / cam.width_px);
        let of_pixel: Vec<Coverage> = coverages.iter().map(|c| c[k]).collect();
        if let Some(i) = of_pixel.iter().position(|c| *c == Coverage::Inside) {
            inside_of[i] += 1;
            assert!(d, "pixel ({u}, {v}) inside aircraft {i} is not dark");
        } else if of_pixel.iter().all(|c| *c == Coverage::Outside) {
            assert!(!d, "pixel ({u}, {v}) outside every aircraft is dark");
        }
    }
    assert!(
        inside_of.iter().all(|&n| n > 30),
        "each aircraft covers pixels: {inside_of:?}"
    );
}

#[test]
fn depth_not_order_decides_what_is_in_front() {
    let cam = CameraIntrinsics::from_hfov(320, 240, 60.0);
    let (target, others) = scene();
    let near = others[1];
    let as_drawn = render(cam, 4, true, &target, &[near]);
    // The near aircraft as the target (drawn first) and the target as the other: with
    // scale 1 the other's transform is the target's, exactly.
    let swapped_target = AircraftPose {
        pose: target,
        scale: 1.0,
    };
    let near_mesh = aircraft().scaled(near.scale);
    let mut settings = RenderSettings::new(cam);
    settings.msaa_samples = 4;
    let mut renderer = Renderer::new(gpu(), settings, &near_mesh).expect("renderer");
    renderer.set_other_aircraft(&[AircraftPose {
        scale: 1.0 / near.scale,
        ..swapped_target
    }]);
    let swapped = renderer.render(&near.pose, 0).expect("frame").clone();
    let differing = as_drawn
        .rgba
        .chunks(4)
        .zip(swapped.rgba.chunks(4))
        .filter(|(a, b)| a.iter().zip(*b).any(|(x, y)| x.abs_diff(*y) > 2))
        .count();
    // Only pixels along edges, where the scaled mesh's f32 vertices round differently.
    assert!(
        differing < 40,
        "{differing} pixels differ with the order swapped"
    );
    let alone = render(cam, 4, true, &target, &[]);
    let hidden = as_drawn
        .rgba
        .chunks(4)
        .zip(alone.rgba.chunks(4))
        .filter(|(a, b)| a != b)
        .count();
    assert!(hidden > 100, "the near aircraft covers part of the target");
}

#[test]
fn window_frame_is_the_whole_frame() {
    let cam = CameraIntrinsics::from_hfov(320, 240, 60.0);
    let (target, mut others) = scene();
    others.push(AircraftPose {
        pose: pose([-50.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
        scale: 1.0,
    });
    for msaa in [1, 4] {
        let windowed = render(cam, msaa, true, &target, &others);
        let whole = render(cam, msaa, false, &target, &others);
        assert!(windowed.rgba == whole.rgba, "msaa {msaa}: window differs");
    }
    let behind_only = render(cam, 1, true, &target, &others[2..]);
    let alone = render(cam, 1, true, &target, &[]);
    assert!(behind_only.rgba == alone.rgba);
}

#[test]
fn region_frame_holds_the_whole_frame_there() {
    let cam = CameraIntrinsics::from_hfov(320, 240, 60.0);
    let (target, others) = scene();
    let whole = render(cam, 4, true, &target, &others);
    let mut settings = RenderSettings::new(cam);
    settings.msaa_samples = 4;
    let mut renderer = Renderer::new(gpu(), settings, &aircraft()).expect("renderer");
    renderer.set_other_aircraft(&others);
    // Around the target (and the near aircraft over it), away from the large one.
    let region = ImageRegion {
        u0_px: 150,
        v0_px: 100,
        width_px: 60,
        height_px: 50,
    };
    let part = renderer.render_region(&target, &region, 0).expect("frame");
    for v in 0..region.height_px {
        for u in 0..region.width_px {
            let (wu, wv) = (u + region.u0_px, v + region.v0_px);
            assert_eq!(part.pixel(u, v), whole.pixel(wu, wv), "pixel ({wu}, {wv})");
        }
    }
}
