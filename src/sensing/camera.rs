//! The camera sensor stage: on camera ticks it renders the target as the follower's camera sees
//! it, measures the frame with the image pipeline, computes the ground truth beside it, and
//! turns the measurement into r* through the sensing transform (3.3)-(3.12). Measurements
//! reach the guidance `latency_frames` frames after their frame was taken and are held
//! between frames; a frame whose status is not `Ok` is a lost frame: the guidance then coasts.

use super::transform::scaled_relative_position;
use crate::frames::{EulerAngles, Mat3, Vec3};
use crate::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use crate::render::gpu::{GpuContext, GpuError};
use crate::render::image::CameraImage;
use crate::render::mesh::{MeshError, TargetMesh};
use crate::render::renderer::{PendingFrame, RenderError, RenderTimings, Renderer};
use crate::render::settings::{Background, PixelNoise, RenderSettings, Sky, TargetShading};
use crate::scenario::{BearingPoint, BlobChoice, CameraSection, DEFAULT_MESH, Scenario, SkyKind};
use crate::vision::silhouette::SilhouetteCentroid;
use crate::vision::{
    BlobMeasurement, BlobSelection, BlobStatus, ImageMeasurement, ImageSizeError, ImageTruth,
    TruthProjector, VisionConfig, VisionConfigError, VisionPipeline,
};
use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

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
}

/// Where the follower and target are when a frame is taken.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CaptureGeometry {
    /// R_T - R_F, NED, ft.
    pub relative_ned_ft: Vec3,
    /// R_F, NED, ft (the follower's own navigation state, known to it).
    pub follower_position_ned_ft: Vec3,
    /// Follower attitude.
    pub follower_attitude: EulerAngles,
    /// The camera's mounting on the body, L_CB (identity: camera = body).
    pub camera_from_body: Mat3,
    /// Target attitude.
    pub target_attitude: EulerAngles,
}

impl CaptureGeometry {
    /// L_CB L_BE: NED to camera axes.
    pub fn camera_from_ned(&self) -> Mat3 {
        self.camera_from_body * self.follower_attitude.body_from_ned()
    }

    /// The target's pose in camera axes.
    pub fn pose(&self) -> TargetPoseInCamera {
        let camera_from_ned = self.camera_from_ned();
        TargetPoseInCamera {
            position_body_ft: camera_from_ned * self.relative_ned_ft,
            body_from_target: camera_from_ned * self.target_attitude.body_from_ned().transpose(),
        }
    }
}

/// One frame's measurement beside its truth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameRecord {
    /// Frame number (0-based).
    pub index: u64,
    /// Time the frame was taken, s.
    pub t_s: f64,
    /// Vision status.
    pub status: BlobStatus,
    /// Measured (yI, zI, bI), px (None when nothing was found).
    pub measured: Option<ImageMeasurement>,
    /// True (yI, zI) of the target's reference point and true maximal length of the projected
    /// mesh, px (None when part of the target is behind the camera).
    pub truth: Option<ImageMeasurement>,
    /// r* from this frame (None when lost).
    pub r_measured: Option<Vec3>,
    /// Where the follower was when the frame was taken, NED, ft.
    pub follower_position_ned_ft: Vec3,
    /// The camera's orientation then, (L_CB L_BE)ᵀ: NED from camera axes.
    pub ned_from_camera: Mat3,
    /// The true range ‖R‖ when the frame was taken, ft (for the apparent size).
    pub range_ft: f64,
}

/// A frame taken: when, and the geometry it was taken in.
#[derive(Debug, Clone, Copy)]
struct Exposure {
    index: u64,
    t_s: f64,
    geometry: CaptureGeometry,
}

/// Which of the two pixel buffers holds frame `index`.
fn buffer_of(index: u64) -> usize {
    (index % 2) as usize
}

/// Wall-clock time spent in each stage of the camera, summed over the run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CameraTimings {
    /// Building the command buffer and submitting it.
    pub render: Duration,
    /// Waiting for the GPU and copying the frame back (pixel noise included).
    pub readback: Duration,
    /// Image pipeline.
    pub vision: Duration,
    /// Ground truth and sensing transform.
    pub truth: Duration,
}

impl CameraTimings {
    fn add_render(&mut self, t: RenderTimings) {
        self.render += Duration::from_secs_f64(t.submit_s);
        self.readback += Duration::from_secs_f64(t.readback_s + t.noise_s);
    }
}

/// Accumulated measurement-error statistics over `Ok` frames.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MeasurementErrors {
    /// Frames with both a measurement and its truth.
    pub count: u64,
    /// Σ of squared centroid distance, px².
    pub centroid_sq_px2: f64,
    /// Σ of squared maximal-length error, px².
    pub length_sq_px2: f64,
    /// Frames with both a measured centroid and the silhouette's true one.
    pub silhouette_count: u64,
    /// Σ of squared distance between the measured and the silhouette's true centroid, px².
    pub silhouette_centroid_sq_px2: f64,
}

impl MeasurementErrors {
    /// RMS centroid error, px (None before any frame).
    pub fn centroid_rms_px(&self) -> Option<f64> {
        (self.count > 0).then(|| (self.centroid_sq_px2 / self.count as f64).sqrt())
    }

    /// RMS distance between the measured centroid and the silhouette's true centroid, px
    /// (None before any frame).
    pub fn silhouette_centroid_rms_px(&self) -> Option<f64> {
        (self.silhouette_count > 0)
            .then(|| (self.silhouette_centroid_sq_px2 / self.silhouette_count as f64).sqrt())
    }

    /// RMS maximal-length error, px (None before any frame).
    pub fn length_rms_px(&self) -> Option<f64> {
        (self.count > 0).then(|| (self.length_sq_px2 / self.count as f64).sqrt())
    }
}

/// The camera in the loop.
pub struct CameraSensor {
    intrinsics: CameraIntrinsics,
    renderer: Renderer,
    vision: VisionPipeline,
    truth: TruthProjector,
    silhouette: SilhouetteCentroid,
    mesh_vertices_ft: Vec<Vec3>,
    mesh_triangles: Vec<[u32; 3]>,
    selection: BlobChoice,
    bearing_point: BearingPoint,
    period_ticks: u64,
    latency_frames: u64,
    pending: VecDeque<FrameRecord>,
    held: Option<FrameRecord>,
    last_frame: Option<FrameRecord>,
    last_measurement: Option<BlobMeasurement>,
    last_truth: Option<ImageTruth>,
    previous_centroid_px: Option<(f64, f64)>,
    /// Pixels of the even and the odd frames: one is measured while the other is drawn.
    pixels: [CameraImage; 2],
    /// The frame read back but not measured yet (latency of a frame or more).
    unmeasured: Option<Exposure>,
    frames: u64,
    lost_frames: u64,
    errors: MeasurementErrors,
    timings: CameraTimings,
    adapter: String,
}

impl std::fmt::Debug for CameraSensor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CameraSensor")
            .field("intrinsics", &self.intrinsics)
            .field("adapter", &self.adapter)
            .field("frames", &self.frames)
            .finish_non_exhaustive()
    }
}

/// The renderer's settings for a `[camera]` section.
pub fn render_settings(camera: &CameraSection, seed: u64) -> RenderSettings {
    let sky = match camera.sky {
        SkyKind::Uniform => Sky::Uniform {
            rgb: camera.sky_rgb,
        },
        SkyKind::Gradient => Sky::VerticalGradient {
            top_rgb: camera.sky_top_rgb,
            bottom_rgb: camera.sky_bottom_rgb,
        },
    };
    let noise = (camera.noise_std_grey > 0.0).then_some(PixelNoise {
        std_grey_levels: camera.noise_std_grey,
        seed,
    });
    RenderSettings {
        intrinsics: intrinsics(camera),
        msaa_samples: camera.msaa_samples,
        multisample_window: true,
        background: Background { sky, noise },
        shading: TargetShading::default(),
    }
}

/// The pinhole intrinsics of a `[camera]` section.
pub fn intrinsics(camera: &CameraSection) -> CameraIntrinsics {
    CameraIntrinsics {
        width_px: camera.width_px,
        height_px: camera.height_px,
        focal_px: camera.focal_length_px(),
    }
}

/// Loads the scenario's target mesh, scaled so that its maximal dimension is `target.size_ft`.
pub fn load_target_mesh(scenario: &Scenario) -> Result<TargetMesh, SensorError> {
    let path = Path::new(&scenario.camera.mesh);
    // The default mesh where no file of that name is found: the copy built into the program.
    let unscaled = if scenario.camera.mesh == DEFAULT_MESH && !path.exists() {
        TargetMesh::target_aircraft(1.0)?
    } else {
        TargetMesh::load_obj(path, 1.0)?
    };
    let span = unscaled.max_dimension_ft();
    if !(span.is_finite() && span > 0.0) {
        return Err(SensorError::MeshWithoutExtent(path.to_path_buf()));
    }
    Ok(unscaled.scaled(scenario.target.size_ft / span))
}

impl CameraSensor {
    /// Sets up GPU, renderer, mesh and image pipeline for a camera scenario.
    pub fn new(scenario: &Scenario) -> Result<Self, SensorError> {
        let camera = &scenario.camera;
        let mesh = load_target_mesh(scenario)?;
        let gpu = GpuContext::new()?;
        let adapter = gpu.description();
        let settings = render_settings(camera, scenario.run.seed);
        let renderer = Renderer::new(&gpu, settings, &mesh)?;
        let mut vision_config = VisionConfig {
            min_pixel_count: camera.min_pixel_count as usize,
            ..VisionConfig::default()
        };
        vision_config.segmentation.mask_coverage = camera.mask_coverage;
        vision_config.link_radius_px = camera.link_radius_px as usize;
        let vision = VisionPipeline::new(vision_config)?;
        Ok(Self {
            intrinsics: settings.intrinsics,
            renderer,
            vision,
            truth: TruthProjector::new(),
            silhouette: SilhouetteCentroid::default(),
            mesh_vertices_ft: mesh.vertices_ft.clone(),
            mesh_triangles: mesh.triangles.clone(),
            selection: camera.selection,
            bearing_point: camera.bearing_point,
            period_ticks: camera.period_ticks(scenario.run.dt_s),
            latency_frames: u64::from(camera.latency_frames),
            pending: VecDeque::new(),
            held: None,
            last_frame: None,
            last_measurement: None,
            last_truth: None,
            previous_centroid_px: None,
            pixels: [CameraImage::default(), CameraImage::default()],
            unmeasured: None,
            frames: 0,
            lost_frames: 0,
            errors: MeasurementErrors::default(),
            timings: CameraTimings::default(),
            adapter,
        })
    }

    /// Whether a frame is taken at this tick.
    pub fn is_frame_tick(&self, tick: u64) -> bool {
        tick.is_multiple_of(self.period_ticks)
    }

    /// Takes a frame and returns the record the guidance holds from now on (the frame taken
    /// `latency_frames` frames ago; None before the first one arrives).
    ///
    /// With a latency of a frame or more the measurement of a frame is not needed before the
    /// next frame is taken, so the two are overlapped: this frame is submitted, the previous
    /// one is measured while the renderer draws this one, then this one is read back. The
    /// records, and when they reach the guidance, are those of measuring each frame at once.
    pub fn capture(
        &mut self,
        t_s: f64,
        geometry: &CaptureGeometry,
    ) -> Result<Option<FrameRecord>, SensorError> {
        let (exposure, pending) = self.expose(t_s, geometry)?;
        if self.latency_frames == 0 {
            self.finish(pending, exposure.index)?;
            self.measure(&exposure)?;
        } else {
            if let Some(previous) = self.unmeasured.take() {
                self.measure(&previous)?;
            }
            self.finish(pending, exposure.index)?;
            self.unmeasured = Some(exposure);
        }
        while self
            .pending
            .front()
            .is_some_and(|r| r.index + self.latency_frames <= exposure.index)
        {
            self.held = self.pending.pop_front();
        }
        Ok(self.held)
    }

    /// Takes and measures one frame at once, whatever the latency (`wingman render`).
    pub fn capture_now(
        &mut self,
        t_s: f64,
        geometry: &CaptureGeometry,
    ) -> Result<FrameRecord, SensorError> {
        let (exposure, pending) = self.expose(t_s, geometry)?;
        self.finish(pending, exposure.index)?;
        self.measure(&exposure)
    }

    /// Numbers the next frame and starts drawing it.
    fn expose(
        &mut self,
        t_s: f64,
        geometry: &CaptureGeometry,
    ) -> Result<(Exposure, PendingFrame), SensorError> {
        let exposure = Exposure {
            index: self.frames,
            t_s,
            geometry: *geometry,
        };
        self.frames += 1;
        let pending = self.renderer.begin_frame(&geometry.pose())?;
        Ok((exposure, pending))
    }

    /// Reads frame `index` back into its buffer.
    fn finish(&mut self, pending: PendingFrame, index: u64) -> Result<(), SensorError> {
        self.renderer
            .finish_frame(pending, index, &mut self.pixels[buffer_of(index)])?;
        self.timings.add_render(self.renderer.last_timings());
        Ok(())
    }

    /// Measures a read-back frame, computes its truth and r*, and queues its record.
    fn measure(&mut self, exposure: &Exposure) -> Result<FrameRecord, SensorError> {
        let vision_started = Instant::now();
        let selection = match (self.selection, self.previous_centroid_px) {
            (BlobChoice::Nearest, Some((u_px, v_px))) => BlobSelection::NearestTo { u_px, v_px },
            _ => BlobSelection::Largest,
        };
        let frame = &self.pixels[buffer_of(exposure.index)];
        let blob = self
            .vision
            .measure(&frame.rgba, frame.width_px, frame.height_px, selection)?;
        self.timings.vision += vision_started.elapsed();

        let truth_started = Instant::now();
        let geometry = &exposure.geometry;
        let pose = geometry.pose();
        self.last_truth = self
            .truth
            .image_truth(&self.mesh_vertices_ft, &pose, &self.intrinsics);
        let truth = self.last_truth.map(|t: ImageTruth| t.image_measurement());
        let measured = blob.image_measurement_at(&self.intrinsics, self.bearing_point);
        let ok = blob.status == BlobStatus::Ok;
        let r_measured = match (ok, measured) {
            (true, Some(m)) => Some(scaled_relative_position(
                &m,
                self.intrinsics.focal_px,
                &geometry.camera_from_ned(),
            )),
            _ => None,
        };
        if let (true, Some(m), Some(t)) = (ok, measured, truth) {
            self.errors.count += 1;
            self.errors.centroid_sq_px2 +=
                (m.y_i_px - t.y_i_px).powi(2) + (m.z_i_px - t.z_i_px).powi(2);
            self.errors.length_sq_px2 += (m.b_i_px - t.b_i_px).powi(2);
        }
        if ok {
            self.record_silhouette_error(&blob, &pose);
        }
        self.timings.truth += truth_started.elapsed();

        self.previous_centroid_px = ok.then_some((blob.centroid_u_px, blob.centroid_v_px));
        if !ok {
            self.lost_frames += 1;
        }
        let record = FrameRecord {
            index: exposure.index,
            t_s: exposure.t_s,
            status: blob.status,
            measured,
            truth,
            r_measured,
            follower_position_ned_ft: geometry.follower_position_ned_ft,
            ned_from_camera: geometry.camera_from_ned().transpose(),
            range_ft: geometry.relative_ned_ft.norm(),
        };
        self.last_frame = Some(record);
        self.last_measurement = Some(blob);
        self.pending.push_back(record);
        Ok(record)
    }

    /// The last frame taken and its measurement record.
    pub fn last_frame(&self) -> Option<(&CameraImage, &FrameRecord, &BlobMeasurement)> {
        match (&self.last_frame, &self.last_measurement) {
            (Some(record), Some(blob)) => {
                Some((&self.pixels[buffer_of(record.index)], record, blob))
            }
            _ => None,
        }
    }

    /// Adds a measured frame's distance from the silhouette's true centroid to the errors.
    fn record_silhouette_error(&mut self, blob: &BlobMeasurement, pose: &TargetPoseInCamera) {
        let truth = self.silhouette.centroid(
            &self.mesh_vertices_ft,
            &self.mesh_triangles,
            pose,
            &self.intrinsics,
        );
        if let Some((y_true, z_true)) = truth {
            let (y, z) = self
                .intrinsics
                .image_from_pixel(blob.centroid_u_px, blob.centroid_v_px);
            self.errors.silhouette_count += 1;
            self.errors.silhouette_centroid_sq_px2 += (y - y_true).powi(2) + (z - z_true).powi(2);
        }
    }

    /// The ground truth of the last frame taken (None when part of the target was behind
    /// the camera).
    pub fn last_truth(&self) -> Option<ImageTruth> {
        self.last_truth
    }

    /// The record of the last frame taken.
    pub fn last_record(&self) -> Option<FrameRecord> {
        self.last_frame
    }

    /// The intrinsics of this camera.
    pub fn intrinsics(&self) -> &CameraIntrinsics {
        &self.intrinsics
    }

    /// Frames taken.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// Frames whose status was not `Ok`.
    pub fn lost_frames(&self) -> u64 {
        self.lost_frames
    }

    /// Measurement errors against truth.
    pub fn errors(&self) -> MeasurementErrors {
        self.errors
    }

    /// Time spent per stage.
    pub fn timings(&self) -> CameraTimings {
        self.timings
    }

    /// The adapter, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) (Cpu, Vulkan)".
    pub fn adapter(&self) -> &str {
        &self.adapter
    }
}
