//! Per-frame cost of the camera: render + readback + image pipeline, at 640x480 and
//! 1920x1080, with 1 and 4 samples per pixel, on whatever adapter wgpu finds (lavapipe in CI):
//! the whole image (`..._msaaN`, the `camera.pipeline = "whole"` reference) and the tracking
//! window (`..._msaaN_window`: drawn, read back and measured in the window the tracker
//! predicts from the previous frame's measurement, as `camera.pipeline = "window"` does).
//! Run with `cargo bench --bench frame_pipeline`; frames/s = 1 / time per iteration.
//!
//! `camera_capture/...` times one frame of the camera stage as `formation.toml` runs it
//! (`CameraSensor::capture`: drawing, readback, image pipeline, truth, one frame of latency),
//! the target at the slot, at 640x480 and 1920x1080, measuring every pixel
//! (`..._full`, `camera.measure_max_length_px = 0`) or binning targets over 160 px
//! (`..._binned160`, the scenario's setting).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use wingman::frames::Mat3;
use wingman::frames::{EulerAngles, Vec3};
use wingman::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use wingman::render::{GpuContext, ImageRegion, RenderSettings, Renderer, TargetMesh};
use wingman::scenario::Scenario;
use wingman::sensing::{CameraConfig, CameraSensor, CaptureGeometry, FollowerPose};
use wingman::vision::{BlobSelection, TrackingWindow, VisionConfig, VisionPipeline};

fn frame_pipeline(c: &mut Criterion) {
    let gpu = match GpuContext::new() {
        Ok(gpu) => gpu,
        Err(e) => {
            eprintln!("frame_pipeline: {e}");
            return;
        }
    };
    eprintln!("adapter: {}", gpu.description());
    let mesh = match TargetMesh::target_aircraft(1.0) {
        Ok(mesh) => mesh,
        Err(e) => {
            eprintln!("frame_pipeline: {e}");
            return;
        }
    };
    // The seed's formation geometry: 33 ft at 14° bearing, target banked in a turn.
    let pose = TargetPoseInCamera {
        position_body_ft: Vec3::new(32.0, 8.0, 0.0),
        body_from_target: EulerAngles::new(0.3, 0.05, 0.2).body_from_ned().transpose(),
    };
    let mut group = c.benchmark_group("render_readback_measure");
    group.sample_size(20);
    for (width_px, height_px) in [(640, 480), (1920, 1080)] {
        for msaa_samples in [1, 4] {
            let mut settings =
                RenderSettings::new(CameraIntrinsics::from_hfov(width_px, height_px, 60.0));
            settings.msaa_samples = msaa_samples;
            let (Ok(mut renderer), Ok(mut vision)) = (
                Renderer::new(&gpu, settings, &mesh),
                VisionPipeline::new(VisionConfig::default()),
            ) else {
                eprintln!("frame_pipeline: cannot build the renderer at {width_px}x{height_px}");
                continue;
            };
            let name = format!("{width_px}x{height_px}_msaa{msaa_samples}");
            let mut index = 0u64;
            group.bench_function(&name, |b| {
                b.iter(|| {
                    index += 1;
                    let Ok(frame) = renderer.render(&pose, index) else {
                        return;
                    };
                    let measured = vision.measure(
                        &frame.rgba,
                        frame.width_px,
                        frame.height_px,
                        BlobSelection::Largest,
                    );
                    black_box(measured.ok());
                });
            });
            let cam = settings.intrinsics;
            let mut tracker = TrackingWindow::new(cam, 1.0 / 30.0, vision.region_clearance_px());
            group.bench_function(format!("{name}_window"), |b| {
                b.iter(|| {
                    index += 1;
                    let region = tracker
                        .predict(index, &Mat3::identity())
                        .unwrap_or_else(|| ImageRegion::whole(&cam));
                    let Ok(frame) = renderer.render_region(&pose, &region, index) else {
                        return;
                    };
                    let Ok(measured) =
                        vision.measure_region(&frame.rgba, &region, &cam, BlobSelection::Largest)
                    else {
                        return;
                    };
                    tracker.observe(index, &measured.blob, &Mat3::identity());
                    black_box(measured);
                });
            });
        }
    }
    group.finish();
}

/// Frame `index` at the slot: the target 32 ft ahead and 8 ft right, level, the follower
/// swaying by a degree so that the tracker's window moves.
fn slot_geometry(index: u64) -> CaptureGeometry {
    let sway = 0.017 * (0.2 * index as f64).sin();
    CaptureGeometry::exact(
        Vec3::new(32.0, 8.0, 0.0),
        EulerAngles::new(0.1, 0.02, 0.0),
        FollowerPose::at_origin(EulerAngles::new(sway, 0.02, sway)),
    )
}

fn camera_capture(c: &mut Criterion) {
    let mut group = c.benchmark_group("camera_capture");
    group.sample_size(20);
    for (width_px, height_px) in [(640, 480), (1920, 1080)] {
        for (label, max_length_px) in [("full", 0), ("binned160", 160)] {
            let overrides = [
                format!("camera.width_px={width_px}"),
                format!("camera.height_px={height_px}"),
                format!("camera.measure_max_length_px={max_length_px}"),
                "output.frames_every=0".to_string(),
            ];
            let path = std::path::Path::new("scenarios/formation.toml");
            let camera = Scenario::load(path, &overrides)
                .map_err(|e| e.to_string())
                .and_then(|s| CameraSensor::new(&CameraConfig::of(&s)).map_err(|e| e.to_string()));
            let mut camera = match camera {
                Ok(camera) => camera,
                Err(e) => {
                    eprintln!("frame_pipeline: {e}");
                    return;
                }
            };
            let mut index = 0u64;
            group.bench_function(format!("{width_px}x{height_px}_{label}"), |b| {
                b.iter(|| {
                    index += 1;
                    let t_s = index as f64 / 30.0;
                    black_box(camera.capture(t_s, &slot_geometry(index)).ok());
                });
            });
            eprintln!(
                "{width_px}x{height_px}_{label}: {:?}",
                camera.window_counts()
            );
        }
    }
    group.finish();
}

criterion_group! {
    name = benches;
    // No HTML plots: their renderer needs a font the bench machine may not have.
    config = Criterion::default().without_plots();
    targets = frame_pipeline, camera_capture
}
criterion_main!(benches);
