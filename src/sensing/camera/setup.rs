//! The camera's set-up from its configuration: the renderer's settings, the intrinsics, the
//! target mesh, and what can go wrong.

use crate::render::camera::CameraIntrinsics;
use crate::render::gpu::GpuError;
use crate::render::mesh::{MeshError, TargetMesh};
use crate::render::renderer::RenderError;
use crate::render::scene::{Clouds, Ground, Sun, WorldScene};
use crate::render::settings::{Background, PixelNoise, RenderSettings, Sky, TargetShading};
use crate::scenario::{CameraSection, DEFAULT_MESH, SceneKind, SceneSection, SkyKind};
use crate::sensing::config::CameraConfig;
use crate::vision::{ImageSizeError, VisionConfigError};
use std::path::{Path, PathBuf};

/// Why the camera could not be set up or a frame not taken.
#[derive(Debug, thiserror::Error)]
pub enum SensorError {
    /// No GPU adapter or device (the message says what to install).
    #[error("{0}")]
    Gpu(#[from] GpuError),
    /// The target mesh could not be loaded.
    #[error("camera.mesh: {0}")]
    Mesh(#[from] MeshError),
    /// The target mesh has no extent to scale to the target's size.
    #[error("camera.mesh: {}: the mesh has no extent", .0.display())]
    MeshWithoutExtent(PathBuf),
    /// The renderer rejected its settings, or a frame failed.
    #[error("camera: {0}")]
    Render(#[from] RenderError),
    /// The image pipeline rejected its settings.
    #[error("camera: {0}")]
    VisionSettings(#[from] VisionConfigError),
    /// A read-back frame did not fit its stated size.
    #[error("camera: {0}")]
    Frame(#[from] ImageSizeError),
    /// A binning factor that does not divide the image (cannot happen: `Binning` offers
    /// only factors that do).
    #[error("camera: binning by {0} does not divide the image")]
    Binning(u32),
}

/// The renderer's settings for a camera's configuration.
pub(super) fn render_settings(config: &CameraConfig) -> RenderSettings {
    let camera = config.camera;
    let sky = match (config.scene.kind, camera.sky) {
        (SceneKind::World, _) => Sky::World(world_scene(config.scene, config.start_down_ft)),
        (SceneKind::Sky, SkyKind::Uniform) => Sky::Uniform {
            rgb: camera.sky_rgb,
        },
        (SceneKind::Sky, SkyKind::Gradient) => Sky::VerticalGradient {
            top_rgb: camera.sky_top_rgb,
            bottom_rgb: camera.sky_bottom_rgb,
        },
    };
    let noise = (camera.noise_std_grey > 0.0).then_some(PixelNoise {
        std_grey_levels: camera.noise_std_grey,
        seed: config.seed,
    });
    RenderSettings {
        intrinsics: intrinsics(camera),
        msaa_samples: camera.msaa_samples,
        target_window: true,
        background: Background { sky, noise },
        shading: TargetShading::default(),
    }
}

/// The world of a `[scene]` section whose heights refer to a start at NED down
/// `start_down_ft`.
pub fn world_scene(scene: &SceneSection, start_down_ft: f64) -> WorldScene {
    WorldScene {
        zenith_rgb: scene.zenith_rgb,
        horizon_rgb: scene.horizon_rgb,
        ground: scene.ground.then_some(Ground {
            down_ft: start_down_ft + scene.ground_below_start_ft,
            field_ft: scene.field_ft,
            road_every_fields: scene.road_every_fields,
            road_width_ft: scene.road_width_ft,
        }),
        clouds: (scene.cloud_coverage > 0.0).then_some(Clouds {
            down_ft: start_down_ft - scene.cloud_above_start_ft,
            cell_ft: scene.cloud_size_ft,
            coverage: scene.cloud_coverage,
        }),
        sun: Sun::at(
            scene.sun_azimuth_deg,
            scene.sun_elevation_deg,
            scene.sun_glare,
        ),
        visibility_ft: scene.visibility_ft,
        seed: scene.seed,
    }
}

/// The pinhole intrinsics of a `[camera]` section.
fn intrinsics(camera: &CameraSection) -> CameraIntrinsics {
    CameraIntrinsics {
        width_px: camera.width_px,
        height_px: camera.height_px,
        focal_px: camera.focal_length_px(),
    }
}

/// Loads the camera's target mesh (`camera.mesh`), scaled so that its maximal dimension is
/// the target's size.
pub fn load_target_mesh(config: &CameraConfig) -> Result<TargetMesh, SensorError> {
    let path = Path::new(&config.camera.mesh);
    // The default mesh where no file of that name is found: the copy built into the program.
    let unscaled = if config.camera.mesh == DEFAULT_MESH && !path.exists() {
        TargetMesh::target_aircraft(1.0)?
    } else {
        TargetMesh::load_obj(path, 1.0)?
    };
    let span = unscaled.max_dimension_ft();
    if !(span.is_finite() && span > 0.0) {
        return Err(SensorError::MeshWithoutExtent(path.to_path_buf()));
    }
    Ok(unscaled.scaled(config.target_size_ft / span))
}
