//! Helpers shared by the `render_*` tests: one GPU context for the test binary (its tests run on
//! several threads against one device), poses and pixel masks.
#![allow(dead_code)]

use std::sync::OnceLock;

use wingman::frames::{EulerAngles, Vec3};
use wingman::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use wingman::render::{CameraImage, GpuContext, RenderSettings, Renderer, TargetMesh};
use wingman::sensing::line_of_sight_body;
use wingman::vision::{BlobMeasurement, BlobSelection, VisionConfig, VisionPipeline};

/// The shared GPU context. Panics (fails the test) with the install hint when there is no
/// adapter: a skipped GPU test would hide a broken set-up (docs/design.md, Tests).
pub fn gpu() -> &'static GpuContext {
    static GPU: OnceLock<Result<GpuContext, String>> = OnceLock::new();
    match GPU.get_or_init(|| GpuContext::new().map_err(|e| e.to_string())) {
        Ok(gpu) => gpu,
        Err(message) => panic!("{message}"),
    }
}

/// The committed seed aircraft, 8 ft span.
pub fn aircraft() -> TargetMesh {
    match TargetMesh::target_aircraft(1.0) {
        Ok(mesh) => mesh,
        Err(e) => panic!("{e}"),
    }
}

/// A pose: target reference point at `position_body_ft`, target attitude relative to the camera
/// given as 3-2-1 angles (roll, pitch, yaw, rad) of the target in camera axes.
pub fn pose(position_body_ft: [f64; 3], attitude_rad: [f64; 3]) -> TargetPoseInCamera {
    let [phi, theta, psi] = attitude_rad;
    TargetPoseInCamera {
        position_body_ft: Vec3::from(position_body_ft),
        body_from_target: EulerAngles::new(phi, theta, psi)
            .body_from_ned()
            .transpose(),
    }
}

/// Target attitudes relative to the camera (roll, pitch, yaw of the target in camera axes),
/// each at least 15° from a wing seen edge-on (asserted in [`sixty_poses`]). The first is the
/// symmetric view: pitched up 90°, the camera sees the planform with the nose up,
/// mirror-symmetric in u.
pub const POSE_ATTITUDES: [[f64; 3]; 6] = [
    [0.0, std::f64::consts::FRAC_PI_2, 0.0],
    [0.3, 0.9, 0.4],
    [-0.4, 1.1, 2.0],
    [0.2, -1.2, 2.8],
    [0.0, -1.0, 0.5],
    [0.0, 0.7, -0.5],
];

/// One of the 60 poses of the image pipeline's tests.
#[derive(Debug, Clone, Copy)]
pub struct PoseCase {
    /// Range, ft.
    pub range_ft: f64,
    /// Bearing, deg.
    pub bearing_deg: f64,
    /// Elevation, deg.
    pub elevation_deg: f64,
    /// One of [`POSE_ATTITUDES`].
    pub attitude: [f64; 3],
    /// The pose.
    pub pose: TargetPoseInCamera,
}

/// The 60-pose test set at 640x480, 60° field of view: ranges 20-250 ft, bearings and
/// elevations across the field of view where the whole 8 ft target fits in the image (shrunk
/// close in), three attitudes per position (the planform, and two of the other five in turn).
pub fn sixty_poses() -> Vec<PoseCase> {
    let positions = [20.0, 45.0, 90.0, 160.0, 250.0]
        .into_iter()
        .flat_map(|range_ft| {
            [(-18.0, 8.0), (0.0, 0.0), (20.0, -10.0), (8.0, 15.0)].map(
                |(bearing_deg, elevation_deg)| {
                    let scale = f64::min(1.0, range_ft / 60.0);
                    (range_ft, bearing_deg * scale, elevation_deg * scale)
                },
            )
        });
    let mut cases = Vec::new();
    for (k, (range_ft, bearing_deg, elevation_deg)) in positions.enumerate() {
        for i in [0, 1 + k % 5, 1 + (k + 2) % 5] {
            let attitude = POSE_ATTITUDES[i];
            let position =
                line_of_sight_body(f64::to_radians(bearing_deg), f64::to_radians(elevation_deg))
                    * range_ft;
            let p = pose([position.x, position.y, position.z], attitude);
            let wing_normal = p.body_from_target * Vec3::z();
            let off_edge_on = wing_normal.dot(&position.normalize()).abs().asin();
            assert!(
                off_edge_on > 15f64.to_radians(),
                "{attitude:?} is near edge-on"
            );
            cases.push(PoseCase {
                range_ft,
                bearing_deg,
                elevation_deg,
                attitude,
                pose: p,
            });
        }
    }
    cases
}

/// The image pipeline as the camera scenarios configure it: thin, partly covered pixels kept
/// in the mask and one-pixel gaps bridged.
pub fn scenario_vision_config() -> VisionConfig {
    let mut config = VisionConfig {
        link_radius_px: 2,
        ..VisionConfig::default()
    };
    config.segmentation.mask_coverage = 0.2;
    config
}

/// The seed aircraft drawn by a 640x480 camera of 60° field of view with 4 samples per pixel
/// and measured by the scenarios' image pipeline: the rig of the tests that compare the
/// measurement with the geometry.
pub struct MeasuringRig {
    /// The camera.
    pub cam: CameraIntrinsics,
    /// The aircraft it draws.
    pub mesh: TargetMesh,
    renderer: Renderer,
    vision: VisionPipeline,
}

impl MeasuringRig {
    /// The rig on the shared GPU context.
    pub fn new() -> Self {
        let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
        let mut settings = RenderSettings::new(cam);
        settings.msaa_samples = 4;
        let mesh = aircraft();
        let renderer = Renderer::new(gpu(), settings, &mesh).unwrap_or_else(|e| panic!("{e}"));
        let vision =
            VisionPipeline::new(scenario_vision_config()).unwrap_or_else(|e| panic!("{e}"));
        Self {
            cam,
            mesh,
            renderer,
            vision,
        }
    }

    /// The aircraft at `pose` drawn and its largest blob measured.
    pub fn measure(&mut self, pose: &TargetPoseInCamera) -> BlobMeasurement {
        let frame = self
            .renderer
            .render(pose, 0)
            .unwrap_or_else(|e| panic!("{e}"));
        measure_largest(&mut self.vision, frame)
    }
}

/// The largest blob of the whole `frame`, measured by `vision`.
pub fn measure_largest(vision: &mut VisionPipeline, frame: &CameraImage) -> BlobMeasurement {
    vision
        .measure(
            &frame.rgba,
            frame.width_px,
            frame.height_px,
            BlobSelection::Largest,
        )
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Grey levels of `frame` below `threshold`: the target's silhouette.
pub fn dark_mask(frame: &CameraImage, threshold: u8) -> Vec<bool> {
    frame.grey_levels().iter().map(|&g| g < threshold).collect()
}

/// (u_min, v_min, u_max, v_max) of the set pixels as a continuous box: pixel i spans [i, i+1).
pub fn mask_bbox(mask: &[bool], width_px: u32) -> Option<(f64, f64, f64, f64)> {
    let w = width_px as usize;
    let mut b: Option<(f64, f64, f64, f64)> = None;
    for (k, _) in mask.iter().enumerate().filter(|(_, m)| **m) {
        let (u, v) = ((k % w) as f64, (k / w) as f64);
        b = Some(match b {
            None => (u, v, u + 1.0, v + 1.0),
            Some((a, c, d, e)) => (a.min(u), c.min(v), d.max(u + 1.0), e.max(v + 1.0)),
        });
    }
    b
}

/// Centroid (u, v) of the set pixels' centres, px.
pub fn mask_centroid(mask: &[bool], width_px: u32) -> Option<(f64, f64)> {
    let w = width_px as usize;
    let (mut n, mut su, mut sv) = (0.0, 0.0, 0.0);
    for (k, _) in mask.iter().enumerate().filter(|(_, m)| **m) {
        n += 1.0;
        su += (k % w) as f64 + 0.5;
        sv += (k / w) as f64 + 0.5;
    }
    (n > 0.0).then(|| (su / n, sv / n))
}

/// Pixel positions (u, v) of the mesh's vertices at `pose`, from
/// [`CameraIntrinsics::image_from_body`] (`None` for a vertex behind the camera).
pub fn projected_vertices(
    cam: &CameraIntrinsics,
    mesh: &TargetMesh,
    pose: &TargetPoseInCamera,
) -> Vec<Option<(f64, f64)>> {
    mesh.vertices_ft
        .iter()
        .map(|p| {
            let (y, z) = cam.image_from_body(&pose.body_from_target_point(p))?;
            Some(cam.pixel_from_image(y, z))
        })
        .collect()
}

/// How a pixel centre relates to the projected silhouette, with a margin `eps_px` for the
/// rasteriser's sub-pixel snapping.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coverage {
    /// Inside some triangle by more than the margin.
    Inside,
    /// Outside every triangle by more than the margin.
    Outside,
    /// Within the margin of an edge.
    Edge,
}

/// CPU rasterisation of the projected mesh at pixel centres (all vertices must be in front).
pub fn cpu_coverage(
    cam: &CameraIntrinsics,
    mesh: &TargetMesh,
    pose: &TargetPoseInCamera,
    eps_px: f64,
) -> Vec<Coverage> {
    let (w, h) = (cam.width_px as usize, cam.height_px as usize);
    let uv: Vec<(f64, f64)> = projected_vertices(cam, mesh, pose)
        .into_iter()
        .map(|p| p.expect("every vertex in front of the camera"))
        .collect();
    let mut out = vec![Coverage::Outside; w * h];
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| uv[i as usize]);
        let area2 = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
        if area2.abs() < 1e-12 {
            continue;
        }
        let s = area2.signum();
        // Signed distance of p to edge p0->p1, positive inside.
        let dist = |p0: (f64, f64), p1: (f64, f64), p: (f64, f64)| {
            let (ex, ey) = (p1.0 - p0.0, p1.1 - p0.1);
            s * (ex * (p.1 - p0.1) - ey * (p.0 - p0.0)) / (ex * ex + ey * ey).sqrt()
        };
        let u0 = (a.0.min(b.0).min(c.0) - 1.0).floor().max(0.0) as usize;
        let u1 = (a.0.max(b.0).max(c.0) + 1.0).ceil().min(w as f64) as usize;
        let v0 = (a.1.min(b.1).min(c.1) - 1.0).floor().max(0.0) as usize;
        let v1 = (a.1.max(b.1).max(c.1) + 1.0).ceil().min(h as f64) as usize;
        for v in v0..v1 {
            for u in u0..u1 {
                let p = (u as f64 + 0.5, v as f64 + 0.5);
                let d = dist(a, b, p).min(dist(b, c, p)).min(dist(c, a, p));
                let k = v * w + u;
                if d > eps_px {
                    out[k] = Coverage::Inside;
                } else if d >= -eps_px && out[k] == Coverage::Outside {
                    out[k] = Coverage::Edge;
                }
            }
        }
    }
    out
}

/// The world scene of the scene tests: ground 300 ft below the origin (fields of 400 ft, a
/// road every 4), clouds 600 ft above it covering `cloud_coverage` (none at 0), the sun at
/// `sun_deg` = [azimuth, elevation] with `glare`, seed `seed`.
pub fn world_scene(
    cloud_coverage: f64,
    sun_deg: [f64; 2],
    glare: f64,
    seed: u32,
) -> wingman::render::WorldScene {
    use wingman::render::{Clouds, Ground, Sun, WorldScene};
    WorldScene {
        zenith_rgb: [70, 110, 190],
        horizon_rgb: [200, 212, 228],
        ground: Some(Ground {
            down_ft: 300.0,
            field_ft: 400.0,
            road_every_fields: 4,
            road_width_ft: 30.0,
        }),
        clouds: (cloud_coverage > 0.0).then_some(Clouds {
            down_ft: -600.0,
            cell_ft: 500.0,
            coverage: cloud_coverage,
        }),
        sun: Sun::at(sun_deg[0], sun_deg[1], glare),
        visibility_ft: 8000.0,
        seed,
    }
}

/// A camera at the origin turned by 3-2-1 angles `attitude_deg` (roll, pitch, yaw, deg) from
/// NED.
pub fn world_camera(attitude_deg: [f64; 3]) -> wingman::render::CameraInWorld {
    let [phi, theta, psi] = attitude_deg.map(f64::to_radians);
    wingman::render::CameraInWorld {
        ned_from_camera: EulerAngles::new(phi, theta, psi)
            .body_from_ned()
            .transpose(),
        position_ned_ft: Vec3::zeros(),
    }
}
