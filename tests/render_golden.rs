//! Fixed poses render like the committed golden images in `tests/golden/` (4 samples a pixel):
//! the target on the screen-fixed skies, and on the world scene (sky by elevation, horizon,
//! textured ground, clouds, the sun's shading and glare) seen from fixed camera poses.
//!
//! Tolerance (grey levels, Rec. 601 luma): mean absolute difference < 1 and fewer than 0.5 % of
//! pixels differing by more than 32. On the machine that made the goldens the difference is 0;
//! the slack absorbs another rasteriser's sub-pixel snapping (a few edge pixels flip) and
//! float rounding in shading and noise (±1 level).
//!
//! Regenerate after an intended change (then look at the PNGs before committing them):
//! `WINGMAN_UPDATE_GOLDEN=1 cargo test --release --test behaviour render_golden::`

use std::path::{Path, PathBuf};

use crate::render_support::*;
use wingman::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use wingman::render::{
    Background, CameraImage, CameraInWorld, PixelNoise, RenderSettings, Renderer, Sky,
};

fn golden_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(name)
}

fn render(settings: RenderSettings, p: &TargetPoseInCamera) -> CameraImage {
    render_from(settings, p, &CameraInWorld::default())
}

fn render_from(
    settings: RenderSettings,
    p: &TargetPoseInCamera,
    camera: &CameraInWorld,
) -> CameraImage {
    let mut renderer = match Renderer::new(gpu(), settings, &aircraft()) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    };
    renderer.set_camera_in_world(camera);
    match renderer.render(p, 5) {
        Ok(f) => f.clone(),
        Err(e) => panic!("{e}"),
    }
}

fn assert_matches_golden(frame: &CameraImage, name: &str) {
    let path = golden_path(name);
    if std::env::var_os("WINGMAN_UPDATE_GOLDEN").is_some() {
        frame.save_png(&path).expect("golden written");
        eprintln!("wrote {}", path.display());
        return;
    }
    let expected = match CameraImage::read_png(&path) {
        Ok(img) => img,
        Err(e) => panic!(
            "cannot read golden {}: {e}; create it with \
             WINGMAN_UPDATE_GOLDEN=1 cargo test --release --test behaviour render_golden::",
            path.display()
        ),
    };
    let actual_path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let keep = || {
        let _ = frame.save_png(&actual_path);
        actual_path.display().to_string()
    };
    assert_eq!(
        (expected.width_px, expected.height_px),
        (frame.width_px, frame.height_px),
        "golden {} has another size (rendered frame: {})",
        path.display(),
        keep()
    );
    let diffs: Vec<u32> = frame
        .grey_levels()
        .iter()
        .zip(expected.grey_levels())
        .map(|(a, b)| u32::from(a.abs_diff(b)))
        .collect();
    let n = diffs.len() as f64;
    let mean = diffs.iter().map(|&d| f64::from(d)).sum::<f64>() / n;
    let big = diffs.iter().filter(|&&d| d > 32).count() as f64 / n;
    assert!(
        mean < 1.0 && big < 0.005,
        "{name}: mean abs diff {mean:.3} grey levels, {:.2} % pixels off by > 32 (rendered frame: {})",
        100.0 * big,
        keep()
    );
}

#[test]
fn three_quarter_view_on_uniform_sky() {
    let mut settings = RenderSettings::new(CameraIntrinsics::from_hfov(160, 120, 40.0));
    settings.msaa_samples = 4;
    let frame = render(settings, &pose([20.0, 1.0, 0.5], [0.3, -0.6, 0.9]));
    assert_matches_golden(&frame, "three_quarter_160x120.png");
}

#[test]
fn banked_view_on_noisy_gradient_sky() {
    let mut settings = RenderSettings::new(CameraIntrinsics::from_hfov(160, 120, 40.0));
    settings.msaa_samples = 4;
    settings.background = Background {
        sky: Sky::VerticalGradient {
            top_rgb: [120, 160, 215],
            bottom_rgb: [215, 220, 225],
        },
        noise: Some(PixelNoise {
            std_grey_levels: 4.0,
            seed: 2024,
        }),
    };
    let frame = render(settings, &pose([22.0, -1.0, -1.0], [-0.7, 0.15, 2.6]));
    assert_matches_golden(&frame, "banked_noisy_gradient_160x120.png");
}

/// The world scene at 160x120 with a 60° field of view, 4 samples a pixel.
fn scene_settings(cloud_coverage: f64, sun_deg: [f64; 2], glare: f64) -> RenderSettings {
    let mut settings = RenderSettings::new(CameraIntrinsics::from_hfov(160, 120, 60.0));
    settings.msaa_samples = 4;
    settings.background.sky = Sky::World(world_scene(cloud_coverage, sun_deg, glare, 11));
    settings
}

/// Level flight 300 ft above the fields, pitched 8° down and banked: the horizon crosses the
/// image and the target, roads and fields below it, the sky brightening towards the horizon.
#[test]
fn scene_horizon_and_ground() {
    let settings = scene_settings(0.0, [200.0, 30.0], 0.0);
    let camera = world_camera([10.0, -8.0, 30.0]);
    let frame = render_from(
        settings,
        &pose([30.0, 0.0, -4.4], [0.2, -0.5, 0.6]),
        &camera,
    );
    assert_matches_golden(&frame, "scene_horizon_ground_160x120.png");
}

/// Looking 30° up at a sheet of clouds covering half the sky, the target against them.
#[test]
fn scene_clouds_overhead() {
    let settings = scene_settings(0.5, [200.0, 30.0], 0.0);
    let camera = world_camera([0.0, 30.0, 0.0]);
    let frame = render_from(settings, &pose([30.0, 3.0, 0.0], [0.0, 0.2, 0.4]), &camera);
    assert_matches_golden(&frame, "scene_clouds_160x120.png");
}

/// Towards the sun 10° above the horizon with glare: the sun's disc and its veil, and the
/// target lit from ahead by the sun (its faces shaded by their angle to the sun).
#[test]
fn scene_sun_shading_and_glare() {
    let settings = scene_settings(0.0, [0.0, 10.0], 0.6);
    let camera = world_camera([0.0, 4.0, 6.0]);
    let frame = render_from(settings, &pose([30.0, 3.0, 1.0], [0.3, -0.6, 0.9]), &camera);
    assert_matches_golden(&frame, "scene_sun_glare_160x120.png");
}
