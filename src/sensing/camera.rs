//! The camera sensor stage: on camera ticks it renders the target as the follower's camera sees
//! it, measures the frame with the image pipeline, computes the ground truth beside it, and
//! turns the measurement into r* through the sensing transform (3.3)-(3.12). Measurements
//! reach the guidance `latency_frames` frames after their frame was taken and are held
//! between frames; a frame whose status is not `Ok` is a lost frame: the guidance then coasts.
//!
//! With `camera.pipeline = "window"` (issue 13) a frame is drawn, read back and measured only
//! in the tracking window `vision::tracking` predicts from the last measured frame and the
//! follower's attitude. The whole image is drawn at acquisition and after a lost frame (no
//! track), for a frame that will be saved (`output.frames_every`: saved frames are whole
//! images), and when the window's measurement is not a clean `Ok` or its target pixels reach
//! an edge of the window inside the image: that frame is then drawn and measured again whole,
//! before its record is made, so the record is the whole image's. A windowed frame whose
//! target is predicted longer than `camera.measure_max_length_px` is drawn and measured binned
//! (`super::binning`: the camera of 1/k the resolution, its renderer made when first needed),
//! and its measurement carried back to the image's pixels; a binned frame that cannot stand is
//! redrawn whole at full resolution, like a windowed one.

use super::binning::{
    Binning, binned_intrinsics, binned_region, binned_selection, unbinned_measurement,
};
use super::transform::scaled_relative_position;
use crate::frames::{EulerAngles, Mat3, Vec3};
use crate::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use crate::render::gpu::{GpuContext, GpuError};
use crate::render::image::CameraImage;
use crate::render::mesh::{MeshError, TargetMesh};
use crate::render::region::ImageRegion;
use crate::render::renderer::{PendingFrame, RenderError, RenderTimings, Renderer};
use crate::render::settings::{Background, PixelNoise, RenderSettings, Sky, TargetShading};
use crate::scenario::{
    BearingPoint, BlobChoice, CameraPipeline, CameraSection, DEFAULT_MESH, Scenario, SkyKind,
};
use crate::vision::silhouette::SilhouetteCentroid;
use crate::vision::{
    BlobMeasurement, BlobSelection, BlobStatus, ImageMeasurement, ImageSizeError, ImageTruth,
    TrackingWindow, TruthProjector, VisionConfig, VisionConfigError, VisionPipeline,
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
    /// A binning factor that does not divide the image (cannot happen: `Binning` offers
    /// only factors that do).
    #[error("camera: binning by {0} does not divide the image")]
    Binning(u32),
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

/// Copies the pixels of `window` out of `rgba`, the pixels of `drawn` (which contains it),
/// into `out`.
fn cut_window(rgba: &[u8], drawn: &ImageRegion, window: &ImageRegion, out: &mut Vec<u8>) {
    out.clear();
    let stride = 4 * drawn.width_px as usize;
    let first = 4 * (window.u0_px - drawn.u0_px) as usize;
    let row_bytes = 4 * window.width_px as usize;
    for v in window.v0_px..window.v_end_px() {
        let start = (v - drawn.v0_px) as usize * stride + first;
        out.extend_from_slice(&rgba[start..start + row_bytes]);
    }
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

/// How the frames were drawn and measured (`camera.pipeline = "window"`), counted over the
/// run; every frame is in exactly one of the first three. Frames are measured in their
/// tracking window when there is one, those drawn whole to be saved included.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct WindowCounts {
    /// Drawn in the tracking window (measured there, or redrawn whole).
    pub windowed: u64,
    /// Drawn whole: no track (acquisition, after a lost frame) or the `whole` pipeline.
    pub whole_untracked: u64,
    /// Drawn whole to be saved.
    pub whole_saved: u64,
    /// Of the `windowed`, drawn again whole: the window's measurement was not a clean `Ok`
    /// or reached its edge.
    pub redrawn_whole: u64,
    /// Of the `windowed`, drawn and measured binned (`camera.measure_max_length_px`).
    pub binned: u64,
}

/// A frame taken in a region: whether its measurement stands or the frame must be measured
/// whole.
#[derive(Debug, Clone, Copy)]
enum RegionOutcome {
    /// The measurement (of the whole image, or of a region, in image coordinates).
    Measured(BlobMeasurement),
    /// The region's measurement cannot stand for the whole image's.
    NeedsWholeImage,
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
    /// The device, for the binned cameras' renderers (made when first needed).
    gpu: GpuContext,
    binning: Binning,
    /// The renderers of the binned cameras, by binning factor.
    binned_renderers: Vec<(u32, Renderer)>,
    vision: VisionPipeline,
    truth: TruthProjector,
    silhouette: SilhouetteCentroid,
    mesh: TargetMesh,
    selection: BlobChoice,
    bearing_point: BearingPoint,
    /// Frames taken in [start, end) s show no target (`camera.occlusion_s`).
    occlusion_s: [f64; 2],
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
    /// The part of the image each of `pixels` holds.
    regions: [ImageRegion; 2],
    /// The tracking window each of `pixels` is measured in (None: the whole image).
    windows: [Option<ImageRegion>; 2],
    /// The binning each of `pixels` was drawn at (1: none); `regions` and `windows` are in its
    /// pixels.
    factors: [u32; 2],
    /// A window's pixels cut from a whole frame (a frame drawn whole to be saved).
    window_pixels: Vec<u8>,
    pipeline: CameraPipeline,
    tracker: TrackingWindow,
    /// Frames whose index is a multiple of this are saved, so drawn whole.
    saved_every: Option<u64>,
    window_counts: WindowCounts,
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
            .field("pipeline", &self.pipeline)
            .field("window_counts", &self.window_counts)
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
        target_window: true,
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
        Self::on_gpu(scenario, &GpuContext::new()?)
    }

    /// Sets up renderer, mesh and image pipeline on an open GPU device (e.g. one shared by
    /// the runs of a sweep).
    pub fn on_gpu(scenario: &Scenario, gpu: &GpuContext) -> Result<Self, SensorError> {
        let camera = &scenario.camera;
        let mesh = load_target_mesh(scenario)?;
        let adapter = gpu.description();
        let settings = render_settings(camera, scenario.run.seed);
        let renderer = Renderer::new(gpu, settings, &mesh)?;
        let binning = Binning::new(&settings.intrinsics, camera.measure_max_length_px);
        let mut vision_config = VisionConfig {
            min_pixel_count: camera.min_pixel_count as usize,
            ..VisionConfig::default()
        };
        vision_config.segmentation.mask_coverage = camera.mask_coverage;
        vision_config.link_radius_px = camera.link_radius_px as usize;
        let vision = VisionPipeline::new(vision_config)?;
        let frame_period_s = 1.0 / camera.rate_hz;
        let tracker = TrackingWindow::new(
            settings.intrinsics,
            frame_period_s,
            vision.region_clearance_px(),
        );
        let whole = ImageRegion::whole(&settings.intrinsics);
        let saved_every = scenario.output.frames_every;
        Ok(Self {
            regions: [whole, whole],
            windows: [None, None],
            factors: [1, 1],
            gpu: gpu.clone(),
            binning,
            binned_renderers: Vec::new(),
            window_pixels: Vec::new(),
            pipeline: camera.pipeline,
            tracker,
            saved_every: (saved_every > 0).then_some(u64::from(saved_every)),
            window_counts: WindowCounts::default(),
            intrinsics: settings.intrinsics,
            renderer,
            vision,
            truth: TruthProjector::new(),
            silhouette: SilhouetteCentroid::default(),
            mesh,
            selection: camera.selection,
            bearing_point: camera.bearing_point,
            occlusion_s: camera.occlusion_s,
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
        let (region, window, factor) = self.regions_of(self.frames, geometry);
        let (exposure, pending) = self.expose(t_s, geometry, &region, factor)?;
        self.windows[buffer_of(exposure.index)] = window;
        let mut in_flight = Some((pending, exposure.index));
        if self.latency_frames == 0 {
            self.finish_in_flight(&mut in_flight)?;
            self.measure(&exposure, &mut in_flight)?;
        } else {
            if let Some(previous) = self.unmeasured.take() {
                self.measure(&previous, &mut in_flight)?;
            }
            self.finish_in_flight(&mut in_flight)?;
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

    /// Takes and measures one frame of the whole image at once, whatever the latency and the
    /// pipeline (`wingman render`).
    pub fn capture_now(
        &mut self,
        t_s: f64,
        geometry: &CaptureGeometry,
    ) -> Result<FrameRecord, SensorError> {
        let whole = ImageRegion::whole(&self.intrinsics);
        let (exposure, pending) = self.expose(t_s, geometry, &whole, 1)?;
        self.windows[buffer_of(exposure.index)] = None;
        let mut in_flight = Some((pending, exposure.index));
        self.finish_in_flight(&mut in_flight)?;
        self.measure(&exposure, &mut in_flight)
    }

    /// The part of the image to draw for frame `index`, taken in `geometry`, the tracking
    /// window to measure it in (see the module documentation), both in the pixels of the
    /// binning factor returned with them (1: the image's), counted in [`WindowCounts`]. A
    /// frame to be saved is drawn whole and measured in its window all the same.
    fn regions_of(
        &mut self,
        index: u64,
        geometry: &CaptureGeometry,
    ) -> (ImageRegion, Option<ImageRegion>, u32) {
        let whole = ImageRegion::whole(&self.intrinsics);
        let window = match self.pipeline {
            CameraPipeline::Window => self.tracker.predict(index, &geometry.camera_from_ned()),
            CameraPipeline::Whole => None,
        };
        if self.saved_every.is_some_and(|n| index.is_multiple_of(n)) {
            self.window_counts.whole_saved += 1;
            return (whole, window, 1);
        }
        let Some(region) = window else {
            self.window_counts.whole_untracked += 1;
            return (whole, None, 1);
        };
        self.window_counts.windowed += 1;
        let factor = self
            .tracker
            .predicted_length_px()
            .map_or(1, |length| self.binning.factor_for(length));
        if factor == 1 {
            return (region, window, 1);
        }
        self.window_counts.binned += 1;
        let binned = binned_region(&region, factor);
        (binned, Some(binned), factor)
    }

    /// Numbers the next frame and starts drawing `region` of it (in the pixels of binning
    /// `factor`).
    fn expose(
        &mut self,
        t_s: f64,
        geometry: &CaptureGeometry,
        region: &ImageRegion,
        factor: u32,
    ) -> Result<(Exposure, PendingFrame), SensorError> {
        let exposure = Exposure {
            index: self.frames,
            t_s,
            geometry: *geometry,
        };
        self.frames += 1;
        self.factors[buffer_of(exposure.index)] = factor;
        let pose = self.drawn_pose(&exposure);
        let pending = self.renderer_for(factor)?.begin_frame_in(&pose, region)?;
        Ok((exposure, pending))
    }

    /// The renderer of binning `factor` (the image's for 1), made when first asked for.
    fn renderer_for(&mut self, factor: u32) -> Result<&mut Renderer, SensorError> {
        if factor == 1 {
            return Ok(&mut self.renderer);
        }
        let found = self.binned_renderers.iter().position(|(k, _)| *k == factor);
        let slot = match found {
            Some(slot) => slot,
            None => {
                let renderer = self.binned_renderer(factor)?;
                self.binned_renderers.push((factor, renderer));
                self.binned_renderers.len() - 1
            }
        };
        Ok(&mut self.binned_renderers[slot].1)
    }

    /// The renderer of the camera of 1/`factor` the resolution on the same optics: pixel
    /// noise σ/k, the mean of k² independent draws (`sensing::binning`).
    fn binned_renderer(&self, factor: u32) -> Result<Renderer, SensorError> {
        let mut settings = *self.renderer.settings();
        settings.intrinsics = self.intrinsics_of(factor)?;
        if let Some(noise) = settings.background.noise.as_mut() {
            noise.std_grey_levels /= f64::from(factor);
        }
        Ok(Renderer::new(&self.gpu, settings, &self.mesh)?)
    }

    /// The intrinsics of the camera binned by `factor` (the image's for 1).
    fn intrinsics_of(&self, factor: u32) -> Result<CameraIntrinsics, SensorError> {
        binned_intrinsics(&self.intrinsics, factor).ok_or(SensorError::Binning(factor))
    }

    /// The target's pose as a frame draws it: where it is, or nowhere while the occlusion
    /// hides it.
    fn drawn_pose(&self, exposure: &Exposure) -> TargetPoseInCamera {
        let [hide_s, show_s] = self.occlusion_s;
        if (hide_s..show_s).contains(&exposure.t_s) {
            TargetPoseInCamera::hidden()
        } else {
            exposure.geometry.pose()
        }
    }

    /// Reads the frame in flight, if any, back into its buffer.
    fn finish_in_flight(
        &mut self,
        in_flight: &mut Option<(PendingFrame, u64)>,
    ) -> Result<(), SensorError> {
        let Some((pending, index)) = in_flight.take() else {
            return Ok(());
        };
        let buffer = buffer_of(index);
        self.regions[buffer] = pending.region();
        let mut pixels = std::mem::take(&mut self.pixels[buffer]);
        let renderer = self.renderer_for(self.factors[buffer])?;
        let finished = renderer.finish_frame(pending, index, &mut pixels);
        let timings = renderer.last_timings();
        self.pixels[buffer] = pixels;
        finished?;
        self.timings.add_render(timings);
        Ok(())
    }

    /// Measures a read-back frame (drawing and measuring it again whole when its region's
    /// measurement cannot stand; the frame in flight is read back first, as the renderer
    /// draws one frame at a time), computes its truth and r*, and queues its record.
    fn measure(
        &mut self,
        exposure: &Exposure,
        in_flight: &mut Option<(PendingFrame, u64)>,
    ) -> Result<FrameRecord, SensorError> {
        let selection = match (self.selection, self.previous_centroid_px) {
            (BlobChoice::Nearest, Some((u_px, v_px))) => BlobSelection::NearestTo { u_px, v_px },
            _ => BlobSelection::Largest,
        };
        let blob = match self.measure_pixels(exposure.index, selection)? {
            RegionOutcome::Measured(blob) => blob,
            RegionOutcome::NeedsWholeImage => {
                self.finish_in_flight(in_flight)?;
                self.window_counts.redrawn_whole += 1;
                let whole = ImageRegion::whole(&self.intrinsics);
                let pose = self.drawn_pose(exposure);
                let buffer = buffer_of(exposure.index);
                self.factors[buffer] = 1;
                let redrawn = self.renderer.begin_frame_in(&pose, &whole)?;
                self.finish_in_flight(&mut Some((redrawn, exposure.index)))?;
                self.windows[buffer] = None;
                self.measure_whole(exposure.index, selection)?
            }
        };
        let camera_from_ned = exposure.geometry.camera_from_ned();
        self.tracker
            .observe(exposure.index, &blob, &camera_from_ned);
        Ok(self.record(exposure, blob))
    }

    /// Measures the pixels of frame `index` as read back: in its tracking window (binned or
    /// not), or the whole image; the measurement is in the image's pixels. A window's
    /// measurement that cannot stand is replaced by the whole image's when the frame was drawn
    /// whole, and asks for the frame to be drawn whole otherwise.
    fn measure_pixels(
        &mut self,
        index: u64,
        selection: BlobSelection,
    ) -> Result<RegionOutcome, SensorError> {
        let buffer = buffer_of(index);
        let factor = self.factors[buffer];
        let intrinsics = self.intrinsics_of(factor)?;
        let (drawn, frame) = (self.regions[buffer], &self.pixels[buffer]);
        let Some(window) = self.windows[buffer] else {
            return Ok(RegionOutcome::Measured(
                self.measure_whole(index, selection)?,
            ));
        };
        let vision_started = Instant::now();
        let pixels = if drawn == window {
            &frame.rgba
        } else {
            cut_window(&frame.rgba, &drawn, &window, &mut self.window_pixels);
            &self.window_pixels
        };
        let measured = self.vision.measure_region(
            pixels,
            &window,
            &intrinsics,
            binned_selection(selection, factor),
        )?;
        self.timings.vision += vision_started.elapsed();
        if !measured.reaches_inner_edge && measured.blob.status == BlobStatus::Ok {
            Ok(RegionOutcome::Measured(unbinned_measurement(
                &measured.blob,
                factor,
            )))
        } else if factor == 1 && drawn.is_whole(&self.intrinsics) {
            Ok(RegionOutcome::Measured(
                self.measure_whole(index, selection)?,
            ))
        } else {
            Ok(RegionOutcome::NeedsWholeImage)
        }
    }

    /// Measures the pixels of frame `index`, a whole image.
    fn measure_whole(
        &mut self,
        index: u64,
        selection: BlobSelection,
    ) -> Result<BlobMeasurement, SensorError> {
        let vision_started = Instant::now();
        let frame = &self.pixels[buffer_of(index)];
        let blob = self
            .vision
            .measure(&frame.rgba, frame.width_px, frame.height_px, selection)?;
        self.timings.vision += vision_started.elapsed();
        Ok(blob)
    }

    /// Computes the truth and r* of a measured frame and queues its record.
    fn record(&mut self, exposure: &Exposure, blob: BlobMeasurement) -> FrameRecord {
        let truth_started = Instant::now();
        let geometry = &exposure.geometry;
        let pose = geometry.pose();
        self.last_truth = self
            .truth
            .image_truth(&self.mesh.vertices_ft, &pose, &self.intrinsics);
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
        record
    }

    /// The last frame measured, its record and its measurement, when it was drawn whole
    /// (frames to be saved always are; a frame drawn in its tracking window only is `None`
    /// here: see [`Self::last_record`]).
    pub fn last_frame(&self) -> Option<(&CameraImage, &FrameRecord, &BlobMeasurement)> {
        match (&self.last_frame, &self.last_measurement) {
            (Some(record), Some(blob))
                if self.factors[buffer_of(record.index)] == 1
                    && self.regions[buffer_of(record.index)].is_whole(&self.intrinsics) =>
            {
                Some((&self.pixels[buffer_of(record.index)], record, blob))
            }
            _ => None,
        }
    }

    /// Adds a measured frame's distance from the silhouette's true centroid to the errors.
    fn record_silhouette_error(&mut self, blob: &BlobMeasurement, pose: &TargetPoseInCamera) {
        let truth = self.silhouette.centroid(
            &self.mesh.vertices_ft,
            &self.mesh.triangles,
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

    /// How the frames were drawn: in the tracking window or whole, and why.
    pub fn window_counts(&self) -> WindowCounts {
        self.window_counts
    }

    /// The adapter, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) (Cpu, Vulkan)".
    pub fn adapter(&self) -> &str {
        &self.adapter
    }
}
