//! Frames per second of render + readback on this machine's adapter (lavapipe in CI).
//!
//! `cargo run --release --example render_fps [FRAMES] [OUT_DIR]` renders the target 33 ft ahead,
//! turning a little each frame, at 640x480 and 1920x1080 with 1 and 4 samples, with a noisy
//! gradient sky (a full-screen background pass), and with formation_scene.toml's world (ground
//! 300 ft below, 30% cloud 600 ft above, sun 30° up; the camera level, looking north across
//! the horizon). Each is timed twice: the whole frame, and the tracking region a run draws
//! while it tracks (the target's projected box and the tracker's margin). It prints frames/s
//! with the split between submission and readback. With OUT_DIR it also saves the first
//! whole frame of each as a PNG there.

use std::path::{Path, PathBuf};
use std::time::Instant;

use wingman::frames::{EulerAngles, Vec3};
use wingman::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use wingman::render::window::{FramePlan, plan_frame};
use wingman::render::{
    Background, CameraInWorld, GpuContext, ImageRegion, PixelNoise, RenderSettings, Renderer, Sky,
    TargetMesh,
};
use wingman::scenario::Scenario;
use wingman::sensing::camera::world_scene;

/// The backgrounds measured.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Backdrop {
    /// The default uniform sky.
    Uniform,
    /// A vertical gradient with pixel noise.
    GradientNoise,
    /// formation_scene.toml's world (its `[scene]`, the start at NED down 0).
    World,
}

/// The background of `backdrop`.
fn background(backdrop: Backdrop) -> Background {
    match backdrop {
        Backdrop::Uniform => Background::default(),
        Backdrop::GradientNoise => Background {
            sky: Sky::VerticalGradient {
                top_rgb: [120, 160, 215],
                bottom_rgb: [215, 220, 225],
            },
            noise: Some(PixelNoise {
                std_grey_levels: 4.0,
                seed: 1,
            }),
        },
        Backdrop::World => {
            let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/formation_scene.toml");
            let scenario = Scenario::load(&path, &[]).expect("the shipped scenario loads");
            Background {
                sky: Sky::World(world_scene(&scenario.scene, 0.0)),
                noise: None,
            }
        }
    }
}

/// Pixels kept around the target's projected box in the tracking region, as the tracker's
/// prediction keeps them one frame on (its fixed margin and the blob's clearance).
const REGION_MARGIN_PX: f64 = 15.0;

/// The target's pose in frame `k`: 33 ft ahead, turning a little each frame.
fn pose(k: u32) -> TargetPoseInCamera {
    TargetPoseInCamera {
        position_body_ft: Vec3::new(33.0, 8.0, 0.5),
        body_from_target: EulerAngles::new(0.3, 0.1, 0.02 * f64::from(k))
            .body_from_ned()
            .transpose(),
    }
}

/// The tracking region of frame 0: the target's projected box and the tracker's margin
/// (`None`, the whole image, when the plan draws the whole frame).
fn tracking_region(mesh: &TargetMesh, intrinsics: &CameraIntrinsics) -> Option<ImageRegion> {
    let FramePlan::Window(window) = plan_frame(&mesh.vertices_ft, &pose(0), intrinsics) else {
        return None;
    };
    let (u0, v0) = (window.u0_px as f64, window.v0_px as f64);
    ImageRegion::covering(
        u0 - REGION_MARGIN_PX,
        u0 + f64::from(window.width_px) + REGION_MARGIN_PX,
        v0 - REGION_MARGIN_PX,
        v0 + f64::from(window.height_px) + REGION_MARGIN_PX,
        intrinsics,
    )
}

/// Renders `frames` frames (of `region`, or whole) after a first one and prints their rate
/// and the split between submission and readback.
fn time_frames(
    renderer: &mut Renderer,
    region: Option<&ImageRegion>,
    frames: u32,
    label: &str,
) -> anyhow::Result<()> {
    let draw = |renderer: &mut Renderer, k: u32| match region {
        Some(region) => renderer
            .render_region(&pose(k), region, u64::from(k))
            .map(|_| ()),
        None => renderer.render(&pose(k), u64::from(k)).map(|_| ()),
    };
    draw(renderer, 0)?;
    let (mut submit_s, mut readback_s, mut noise_s) = (0.0, 0.0, 0.0);
    let start = Instant::now();
    for k in 1..=frames {
        draw(renderer, k)?;
        let t = renderer.last_timings();
        submit_s += t.submit_s;
        readback_s += t.readback_s;
        noise_s += t.noise_s;
    }
    let (n, wall_s) = (f64::from(frames), start.elapsed().as_secs_f64());
    println!(
        "{label}: {:.0} frames/s, {:.3} ms per frame (submit {:.3} ms, readback {:.3} ms, noise {:.2} ms)",
        n / wall_s,
        1e3 * wall_s / n,
        1e3 * submit_s / n,
        1e3 * readback_s / n,
        1e3 * noise_s / n
    );
    Ok(())
}

fn main() -> anyhow::Result<()> {
    let frames: u32 = match std::env::args().nth(1) {
        Some(n) => n.parse()?,
        None => 200,
    };
    let out_dir = std::env::args().nth(2).map(PathBuf::from);
    let gpu = GpuContext::new()?;
    println!("adapter: {}", gpu.description());
    let mesh = TargetMesh::target_aircraft(1.0)?;
    for (width, height) in [(640, 480), (1920, 1080)] {
        for (msaa, backdrop) in [
            (1, Backdrop::Uniform),
            (4, Backdrop::Uniform),
            (1, Backdrop::GradientNoise),
            (1, Backdrop::World),
            (4, Backdrop::World),
        ] {
            let intrinsics = CameraIntrinsics::from_hfov(width, height, 60.0);
            let mut settings = RenderSettings::new(intrinsics);
            settings.msaa_samples = msaa;
            settings.background = background(backdrop);
            let mut renderer = Renderer::new(&gpu, settings, &mesh)?;
            renderer.set_camera_in_world(&CameraInWorld::default());
            if let Some(dir) = &out_dir {
                let name = format!("target_{width}x{height}_msaa{msaa}_{backdrop:?}.png");
                renderer.render(&pose(0), 0)?.save_png(&dir.join(name))?;
            }
            let label = format!("{width}x{height} msaa {msaa} {backdrop:?}");
            time_frames(&mut renderer, None, frames, &format!("{label} whole"))?;
            let region = tracking_region(&mesh, &intrinsics);
            if let Some(region) = region.filter(|r| !r.is_whole(&intrinsics)) {
                let label = format!("{label} region {}x{}", region.width_px, region.height_px);
                time_frames(&mut renderer, Some(&region), frames, &label)?;
            }
        }
    }
    Ok(())
}
