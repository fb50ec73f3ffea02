//! The camera sensor stage: on camera ticks it renders the target as the follower's camera sees
//! it, measures the frame with the image pipeline, computes the ground truth beside it, and
//! turns the measurement into r* through the sensing transform (3.3)-(3.12). Measurements
//! reach the guidance `latency_frames` frames after their frame was taken and are held
//! between frames; a frame whose status is not `Ok` is a lost frame: the guidance then coasts.
//!
//! With `camera.pipeline = "window"` a frame is drawn, read back and measured only in the
//! tracking window `vision::tracking` predicts from the last measured frame and the follower's
//! attitude. The whole image is drawn at acquisition and after a lost frame (no track), and
//! when the window's measurement is not a clean `Ok` or its target pixels reach an edge of the
//! window inside the image: that frame is then drawn and measured again whole, before its
//! record is made, so the record is the whole image's. A frame that will be saved
//! (`output.frames_every`) is measured like any other, then drawn again whole for the saved
//! image when it was not, so saving frames changes no measurement. A windowed frame whose target is
//! predicted longer than `camera.measure_max_length_px` is drawn and measured binned
//! (`super::binning`: the camera of 1/k the resolution, its renderer made when first needed),
//! and its measurement carried back to the image's pixels; a binned frame that cannot stand is
//! redrawn whole at full resolution, like a windowed one.
//!
//! One job per part: `schedule` numbers frames and delivers them after their latency,
//! `drawing` exposes them (region, binning, renderer, pixel buffers), `metering` measures
//! them, `audit` holds each measurement against the truth, `setup` builds the renderer and
//! the mesh; this module wires them. The renderer draws the true geometry; the sensing
//! transform, the tracking window and the records use the follower's navigation
//! ([`CaptureGeometry::navigation`]).

mod audit;
mod backdrop;
mod drawing;
mod metering;
mod schedule;
mod setup;

pub use audit::MeasurementErrors;
pub use backdrop::{BackdropFrames, BackgroundCounts, FrameBackground};
pub use drawing::WindowCounts;
pub use setup::{SensorError, load_target_mesh, world_scene};

use super::config::CameraConfig;
use super::geometry::{CaptureGeometry, OtherAircraft};
use super::transform::scaled_relative_position;
use crate::frames::{Mat3, Vec3};
use crate::render::camera::CameraIntrinsics;
use crate::render::gpu::GpuContext;
use crate::render::image::CameraImage;
use crate::render::region::ImageRegion;
use crate::render::renderer::RenderTimings;
use crate::render::settings::Sky;
use crate::vision::{BlobMeasurement, BlobStatus, ImageMeasurement, ImageTruth, TrackingWindow};
use audit::{AuditedFrame, MeasurementAudit};
use backdrop::{BackdropAudit, BackdropFrame};
use drawing::{DrawingSetup, FrameDrawing, InFlight};
use metering::{Metering, RegionOutcome};
use schedule::{Exposure, FrameSchedule};
use std::time::{Duration, Instant};

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
    /// Where the follower's navigation put it when the frame was taken, NED, ft.
    pub follower_position_ned_ft: Vec3,
    /// The camera's orientation then as the follower knows it, (L_CB L_BE)ᵀ: NED from camera
    /// axes.
    pub ned_from_camera: Mat3,
    /// The true range ‖R‖ when the frame was taken, ft (for the apparent size).
    pub range_ft: f64,
    /// The unit direction of the measured maximal length in (yI, zI) (either sense; None
    /// when nothing was measured).
    pub length_direction: Option<[f64; 2]>,
    /// The distance of the measured centroid from the true centroid of the target's
    /// silhouette, px (None when not `Ok`, or the silhouette is not known).
    pub centroid_vs_silhouette_px: Option<f64>,
    /// What lay behind the target, by the truth (None without a world scene).
    pub background: Option<FrameBackground>,
}

/// How far a measured point may lie from the target's true reference point beyond the
/// target's true maximal length and still be of the target, px: a blob of a few pixels at
/// 200 ft, or measured on binned pixels, stays on its target.
pub const OFF_TARGET_MARGIN_PX: f64 = 8.0;

impl FrameRecord {
    /// Whether the measurement the frame gave the estimator is of the target, by the truth:
    /// its point lies within the true maximal length plus [`OFF_TARGET_MARGIN_PX`] of the
    /// true reference point. A blob measured while the target is behind the camera is not.
    /// `None` when the frame gave no measurement.
    pub fn on_target(&self) -> Option<bool> {
        self.r_measured?;
        let measured = self.measured?;
        Some(self.truth.is_some_and(|truth| {
            let off_px = (measured.y_i_px - truth.y_i_px).hypot(measured.z_i_px - truth.z_i_px);
            off_px <= truth.b_i_px + OFF_TARGET_MARGIN_PX
        }))
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

/// The camera in the loop.
pub struct CameraSensor {
    schedule: FrameSchedule,
    drawing: FrameDrawing,
    metering: Metering,
    audit: MeasurementAudit,
    /// What lay behind the target in each frame, in a world scene.
    backdrop: Option<BackdropAudit>,
    /// The last frame measured, its record and its blob.
    last: Option<(FrameRecord, BlobMeasurement)>,
    /// The last frame delivered to the estimator (its index) and whether it was trusted.
    settled: Option<(u64, bool)>,
    lost_frames: u64,
    /// Frames measured as a merge (`BlobStatus::Merged`), among the lost ones.
    merged_frames: u64,
    timings: CameraTimings,
    adapter: String,
}

impl std::fmt::Debug for CameraSensor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CameraSensor")
            .field("intrinsics", self.drawing.intrinsics())
            .field("adapter", &self.adapter)
            .field("frames", &self.schedule.frames())
            .field("window_counts", &self.drawing.window_counts())
            .finish_non_exhaustive()
    }
}

impl CameraSensor {
    /// Sets up GPU, renderer, mesh and image pipeline for a camera.
    pub fn new(config: &CameraConfig) -> Result<Self, SensorError> {
        Self::on_gpu(config, &GpuContext::new()?)
    }

    /// Sets up renderer, mesh and image pipeline on an open GPU device (e.g. one shared by
    /// the runs of a sweep).
    pub fn on_gpu(config: &CameraConfig, gpu: &GpuContext) -> Result<Self, SensorError> {
        let camera = config.camera;
        let mesh = load_target_mesh(config)?;
        let settings = setup::render_settings(config);
        let backdrop = match settings.background.sky {
            Sky::World(world) => Some(BackdropAudit::new(world)),
            _ => None,
        };
        let ground_down_ft = match &settings.background.sky {
            Sky::World(world) => world.ground.as_ref().map(|ground| ground.down_ft),
            _ => None,
        };
        let metering = Metering::new(camera, ground_down_ft)?;
        let tracker = TrackingWindow::new(
            settings.intrinsics,
            1.0 / camera.rate_hz,
            metering.region_clearance_px(),
        );
        let drawing_setup = DrawingSetup {
            settings,
            measure_max_length_px: camera.measure_max_length_px,
            occlusion_s: camera.occlusion_s,
            pipeline: camera.pipeline,
            tracker,
            frames_every: config.frames_every,
        };
        Ok(Self {
            schedule: FrameSchedule::new(
                camera.period_ticks(config.dt_s),
                u64::from(camera.latency_frames),
            ),
            drawing: FrameDrawing::new(gpu, mesh, drawing_setup)?,
            metering,
            audit: MeasurementAudit::default(),
            backdrop,
            last: None,
            settled: None,
            lost_frames: 0,
            merged_frames: 0,
            timings: CameraTimings::default(),
            adapter: gpu.description(),
        })
    }

    /// Draws `others` with the target in the frames taken from now on (none by default).
    pub fn set_other_aircraft(&mut self, others: &[OtherAircraft]) {
        self.drawing.set_other_aircraft(others);
    }

    /// Whether a frame is taken at this tick.
    pub fn is_frame_tick(&self, tick: u64) -> bool {
        self.schedule.is_frame_tick(tick)
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
        let index = self.schedule.next_index();
        let camera_from_ned = geometry.camera_from_ned();
        let (region, window, factor) = self.drawing.plan(index, &camera_from_ned);
        let exposure = self.schedule.expose(t_s, geometry);
        let pending = self.drawing.begin(&exposure, &region, window, factor)?;
        let mut in_flight = Some((pending, exposure.index));
        if self.schedule.overlaps() {
            if let Some(previous) = self.schedule.replace_unmeasured(None) {
                self.measure(&previous, &mut in_flight)?;
            }
            self.drawing.finish(&mut in_flight, &mut self.timings)?;
            self.schedule.replace_unmeasured(Some(exposure));
        } else {
            self.drawing.finish(&mut in_flight, &mut self.timings)?;
            self.measure(&exposure, &mut in_flight)?;
        }
        Ok(self.schedule.deliver(exposure.index))
    }

    /// Takes and measures one frame of the whole image at once, whatever the latency and the
    /// pipeline (`wingman render`).
    pub fn capture_now(
        &mut self,
        t_s: f64,
        geometry: &CaptureGeometry,
    ) -> Result<FrameRecord, SensorError> {
        let whole = ImageRegion::whole(self.drawing.intrinsics());
        let exposure = self.schedule.expose(t_s, geometry);
        let pending = self.drawing.begin(&exposure, &whole, None, 1)?;
        let mut in_flight = Some((pending, exposure.index));
        self.drawing.finish(&mut in_flight, &mut self.timings)?;
        self.measure(&exposure, &mut in_flight)
    }

    /// Measures a read-back frame (drawing and measuring it again whole when its region's
    /// measurement cannot stand; the frame in flight is read back first, as the renderer
    /// draws one frame at a time), computes its truth and r*, and queues its record.
    fn measure(
        &mut self,
        exposure: &Exposure,
        in_flight: &mut InFlight,
    ) -> Result<FrameRecord, SensorError> {
        self.metering.orient(
            exposure.geometry.camera_from_ned(),
            exposure.geometry.navigation.position_ned_ft,
            exposure.geometry.expected,
        );
        let selection = self.metering.selection(self.drawing.intrinsics());
        let frame = self.drawing.frame(exposure.index)?;
        let blob = match self
            .metering
            .measure(&frame, selection, &mut self.timings)?
        {
            RegionOutcome::Measured(blob) => blob,
            RegionOutcome::NeedsWholeImage => {
                self.drawing
                    .redraw_whole(exposure, in_flight, &mut self.timings)?;
                let frame = self.drawing.frame(exposure.index)?;
                self.metering
                    .measure_whole(&frame, selection, &mut self.timings)?
            }
        };
        let camera_from_ned = exposure.geometry.camera_from_ned();
        self.drawing
            .observe(exposure.index, &blob, &camera_from_ned);
        self.drawing
            .redraw_to_save(exposure, in_flight, &mut self.timings)?;
        Ok(self.record(exposure, blob))
    }

    /// Computes the truth and r* of a measured frame and queues its record.
    fn record(&mut self, exposure: &Exposure, blob: BlobMeasurement) -> FrameRecord {
        let truth_started = Instant::now();
        let geometry = &exposure.geometry;
        let camera_from_ned = geometry.camera_from_ned();
        let intrinsics = *self.drawing.intrinsics();
        let pose = geometry.pose();
        let measured = self.metering.image_measurement(&blob, &intrinsics);
        let ok = blob.status == BlobStatus::Ok;
        let audited = AuditedFrame {
            pose: &pose,
            blob: &blob,
            measured,
            ok,
        };
        let truth = self.audit.audit(&audited, self.drawing.mesh(), &intrinsics);
        let background = match (&mut self.backdrop, &truth) {
            (Some(backdrop), Some(truth)) => {
                let frame = BackdropFrame {
                    index: exposure.index,
                    truth,
                    follower: &geometry.follower,
                    ok,
                    silhouette_sq_px2: self.audit.last_silhouette_sq_px2(),
                };
                Some(backdrop.count(&frame, &intrinsics))
            }
            _ => None,
        };
        let r_measured = match (ok, measured) {
            (true, Some(m)) => Some(scaled_relative_position(
                &m,
                intrinsics.focal_px,
                &camera_from_ned,
            )),
            _ => None,
        };
        self.timings.truth += truth_started.elapsed();

        self.metering.remember(&blob);
        if !ok {
            self.lost_frames += 1;
        }
        if blob.status == BlobStatus::Merged {
            self.merged_frames += 1;
        }
        let record = FrameRecord {
            index: exposure.index,
            t_s: exposure.t_s,
            status: blob.status,
            measured,
            truth,
            r_measured,
            follower_position_ned_ft: geometry.navigation.position_ned_ft,
            ned_from_camera: camera_from_ned.transpose(),
            range_ft: geometry.relative_ned_ft.norm(),
            length_direction: blob.length_direction(),
            centroid_vs_silhouette_px: self.audit.last_silhouette_sq_px2().map(f64::sqrt),
            background,
        };
        self.last = Some((record, blob));
        self.schedule.queue(record);
        record
    }

    /// The last frame measured, its record and its measurement, when it was drawn whole
    /// (frames to be saved always are, once measured; a frame drawn in its tracking window
    /// only is `None` here: see [`Self::last_record`]).
    pub fn last_frame(&self) -> Option<(&CameraImage, &FrameRecord, &BlobMeasurement)> {
        let (record, blob) = self.last.as_ref()?;
        let image = self.drawing.whole_image(record.index)?;
        Some((image, record, blob))
    }

    /// The ground truth of the last frame taken (None when part of the target was behind
    /// the camera).
    pub fn last_truth(&self) -> Option<ImageTruth> {
        self.audit.last_truth()
    }

    /// The record of the last frame measured (the newest: with a latency of two frames or
    /// more, not yet the guidance's).
    pub fn last_record(&self) -> Option<FrameRecord> {
        self.last.map(|(record, _)| record)
    }

    /// The record the guidance holds now: the latest frame at least `latency_frames` frames
    /// old.
    pub fn held_record(&self) -> Option<FrameRecord> {
        self.schedule.held()
    }

    /// The frame `index` reached the estimator, which took it (`trusted`) or not (a frame not
    /// `Ok`, or one the filter's gates kept out).
    pub fn settle(&mut self, index: u64, trusted: bool) {
        self.settled = Some((index, trusted));
        if let Some(backdrop) = &mut self.backdrop {
            backdrop.settle(index, trusted);
        }
    }

    /// Whether the frame the guidance holds was trusted (`None` before one is held).
    pub fn held_trusted(&self) -> Option<bool> {
        let held = self.held_record()?;
        self.settled
            .and_then(|(index, trusted)| (index == held.index).then_some(trusted))
    }

    /// The intrinsics of this camera.
    pub fn intrinsics(&self) -> &CameraIntrinsics {
        self.drawing.intrinsics()
    }

    /// Frames taken.
    pub fn frames(&self) -> u64 {
        self.schedule.frames()
    }

    /// Frames whose status was not `Ok`.
    pub fn lost_frames(&self) -> u64 {
        self.lost_frames
    }

    /// Frames measured as a merge (`camera.merges = "bearing"`), among the lost ones.
    pub fn merged_frames(&self) -> u64 {
        self.merged_frames
    }

    /// Measurement errors against truth.
    pub fn errors(&self) -> MeasurementErrors {
        self.audit.errors()
    }

    /// Time spent per stage.
    pub fn timings(&self) -> CameraTimings {
        self.timings
    }

    /// The frames by what lay behind the target (by the truth), in a world scene (None under
    /// a screen-fixed sky).
    pub fn background(&self) -> Option<BackgroundCounts> {
        self.backdrop.as_ref().map(BackdropAudit::counts)
    }

    /// How the frames were drawn: in the tracking window or whole, and why.
    pub fn window_counts(&self) -> WindowCounts {
        self.drawing.window_counts()
    }

    /// The adapter, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) (Cpu, Vulkan)".
    pub fn adapter(&self) -> &str {
        &self.adapter
    }
}
