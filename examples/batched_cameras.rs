//! The cost of N cameras' frames at one instant (a group run's frame tick), three ways on one
//! device: N submissions one after another; N submissions from N threads at once (what a
//! group run does, each follower on its own thread); one submission for all
//! (`Renderer::begin_frames`), read back by each camera.
//!
//! `cargo run --release --example batched_cameras [FRAMES] [CAMERAS]`
//!
//! Each camera (640x480, 4 samples, 60° wide) draws the tracked aircraft 33 ft ahead with the
//! others beside it in its 200x200 px tracking window, turning a little each frame. Prints
//! the milliseconds per instant (all N frames drawn and read back) of each way, three rounds
//! in alternating order.

use rayon::prelude::*;
use std::time::Instant;
use wingman::frames::{EulerAngles, Vec3};
use wingman::render::camera::{AircraftPose, CameraIntrinsics, TargetPoseInCamera};
use wingman::render::{CameraImage, GpuContext, ImageRegion, RenderSettings, Renderer, TargetMesh};

#[derive(Debug, Clone, Copy)]
enum Way {
    OneAfterAnother,
    Threads,
    OneSubmission,
}

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let frames: u64 = args.next().map_or(Ok(300), |n| n.parse())?;
    let cameras: usize = args.next().map_or(Ok(3), |n| n.parse())?;
    let gpu = GpuContext::new()?;
    println!(
        "adapter: {}, {cameras} cameras, {frames} instants",
        gpu.description()
    );
    let mesh = TargetMesh::target_aircraft(1.0)?;
    let mut settings = RenderSettings::new(CameraIntrinsics::from_hfov(640, 480, 60.0));
    settings.msaa_samples = 4;
    let mut renderers = Vec::new();
    for _ in 0..cameras {
        renderers.push(Renderer::new(&gpu, settings, &mesh)?);
    }
    let region = ImageRegion::covering(220.0, 420.0, 140.0, 340.0, &settings.intrinsics)
        .ok_or_else(|| anyhow::anyhow!("the window is outside the image"))?;
    let mut images = vec![CameraImage::default(); cameras];
    for round in 0..3 {
        for way in [Way::OneAfterAnother, Way::Threads, Way::OneSubmission] {
            let started = Instant::now();
            for index in 0..frames {
                let poses = poses(index, cameras);
                draw(way, &mut renderers, &poses, &region, index, &mut images)?;
            }
            let per_instant_ms = started.elapsed().as_secs_f64() * 1e3 / frames as f64;
            println!("round {round} {way:?}: {per_instant_ms:.3} ms per instant");
        }
    }
    Ok(())
}

/// Camera `k`'s view at instant `index`: the tracked aircraft 33 ft ahead, banked a little
/// more each instant, and the others 9 ft beside it, one per other camera.
fn poses(index: u64, cameras: usize) -> Vec<(TargetPoseInCamera, Vec<AircraftPose>)> {
    let at = |lateral_ft: f64, k: usize| TargetPoseInCamera {
        position_body_ft: Vec3::new(33.0, lateral_ft, 0.0),
        body_from_target: EulerAngles::new(0.002 * index as f64 + 0.1 * k as f64, 0.05, 0.0)
            .body_from_ned()
            .transpose(),
    };
    (0..cameras)
        .map(|k| {
            let others = (1..cameras)
                .map(|j| AircraftPose {
                    pose: at(9.0 * j as f64, k),
                    scale: 1.0,
                })
                .collect();
            (at(0.0, k), others)
        })
        .collect()
}

/// Draws and reads back instant `index`'s frames of every camera, the `way` given.
fn draw(
    way: Way,
    renderers: &mut [Renderer],
    poses: &[(TargetPoseInCamera, Vec<AircraftPose>)],
    region: &ImageRegion,
    index: u64,
    images: &mut [CameraImage],
) -> anyhow::Result<()> {
    let one = |renderer: &mut Renderer,
               (pose, others): &(TargetPoseInCamera, Vec<AircraftPose>),
               image: &mut CameraImage| {
        renderer.set_other_aircraft(others);
        let pending = renderer.begin_frame_in(pose, region)?;
        renderer.finish_frame(pending, index, image)
    };
    let cameras = renderers.iter_mut().zip(poses).zip(images.iter_mut());
    match way {
        Way::OneAfterAnother => {
            for ((renderer, pose), image) in cameras {
                one(renderer, pose, image)?;
            }
        }
        Way::Threads => {
            let cameras: Vec<_> = cameras.collect();
            (cameras.into_par_iter())
                .map(|((renderer, pose), image)| one(renderer, pose, image))
                .collect::<Result<Vec<()>, _>>()?;
        }
        Way::OneSubmission => {
            let mut frames = Vec::new();
            let mut outputs = Vec::new();
            for ((renderer, (pose, others)), image) in cameras {
                renderer.set_other_aircraft(others);
                frames.push((renderer, *pose, *region));
                outputs.push(image);
            }
            let pending = Renderer::begin_frames(&mut frames)?;
            for (((renderer, _, _), frame), image) in frames.iter_mut().zip(pending).zip(outputs) {
                renderer.finish_frame(frame, index, image)?;
            }
        }
    }
    Ok(())
}
