//! How a frame is exposed: which part of the image is drawn (the tracking window, binned or
//! not, or the whole image), by which renderer, into which of the two pixel buffers, and how
//! the frames were drawn over the run ([`WindowCounts`]).

use super::CameraTimings;
use super::schedule::Exposure;
use super::setup::SensorError;
use crate::frames::Mat3;
use crate::render::camera::{AircraftPose, CameraIntrinsics, TargetPoseInCamera};
use crate::render::gpu::GpuContext;
use crate::render::image::CameraImage;
use crate::render::mesh::TargetMesh;
use crate::render::region::ImageRegion;
use crate::render::renderer::{PendingFrame, Renderer};
use crate::render::scene::CameraInWorld;
use crate::render::settings::RenderSettings;
use crate::scenario::CameraPipeline;
use crate::sensing::binning::{Binning, binned_intrinsics, binned_region};
use crate::sensing::geometry::OtherAircraft;
use crate::vision::{BlobMeasurement, TrackingWindow};

/// How the frames were drawn and measured (`camera.pipeline = "window"`), counted over the
/// run; every frame is in exactly one of the first two. A frame to be saved is measured as
/// any other and then, when it was not drawn whole, drawn again whole for the saved image
/// only, so saving frames never changes a measurement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct WindowCounts {
    /// Drawn in the tracking window (measured there, or redrawn whole).
    pub windowed: u64,
    /// Drawn whole: no track (acquisition, after a lost frame) or the `whole` pipeline.
    pub whole_untracked: u64,
    /// Of the `windowed`, drawn again whole: the window's measurement was not a clean `Ok`
    /// or reached its edge.
    pub redrawn_whole: u64,
    /// Of the `windowed`, drawn again whole after they were measured, to be saved.
    pub whole_saved: u64,
    /// Of the `windowed`, drawn and measured binned (`camera.measure_max_length_px`).
    pub binned: u64,
}

/// Where the camera truly is when `exposure` is taken: what a world scene is drawn from.
fn camera_in_world(exposure: &Exposure) -> CameraInWorld {
    let follower = &exposure.geometry.follower;
    CameraInWorld {
        ned_from_camera: follower.camera_from_ned().transpose(),
        position_ned_ft: follower.position_ned_ft,
    }
}

/// A frame in flight: drawn on the GPU, not read back yet, and its number.
pub(super) type InFlight = Option<(PendingFrame, u64)>;

/// Which of the two pixel buffers holds frame `index`.
pub(super) fn buffer_of(index: u64) -> usize {
    (index % 2) as usize
}

/// A read-back frame as it is to be measured.
pub(super) struct DrawnFrame<'a> {
    /// Its pixels.
    pub pixels: &'a CameraImage,
    /// The tracking window to measure it in (None: the whole image).
    pub window: Option<ImageRegion>,
    /// The binning it was drawn at (1: none); `window` is in its pixels.
    pub factor: u32,
    /// The intrinsics of the camera binned by `factor`.
    pub intrinsics: CameraIntrinsics,
}

/// The renderers, the pixel buffers and the tracking window that decides what to draw.
pub(super) struct FrameDrawing {
    intrinsics: CameraIntrinsics,
    renderer: Renderer,
    /// The device, for the binned cameras' renderers (made when first needed).
    gpu: GpuContext,
    mesh: TargetMesh,
    binning: Binning,
    /// The renderers of the binned cameras, by binning factor.
    binned_renderers: Vec<(u32, Renderer)>,
    /// Frames taken in [start, end) s show no target (`camera.occlusion_s`).
    occlusion_s: [f64; 2],
    pipeline: CameraPipeline,
    tracker: TrackingWindow,
    /// Frames whose index is a multiple of this are saved, so drawn whole once measured.
    saved_every: Option<u64>,
    window_counts: WindowCounts,
    /// Pixels of the even and the odd frames: one is measured while the other is drawn.
    pixels: [CameraImage; 2],
    /// The part of the image each of `pixels` holds.
    regions: [ImageRegion; 2],
    /// The tracking window each of `pixels` is measured in (None: the whole image).
    windows: [Option<ImageRegion>; 2],
    /// The binning each of `pixels` was drawn at (1: none); `regions` and `windows` are in its
    /// pixels.
    factors: [u32; 2],
    /// Other aircraft to draw in the frames begun from now on.
    others: Vec<OtherAircraft>,
    /// The other aircraft each of `pixels` was drawn with, as its camera saw them.
    drawn_others: [Vec<AircraftPose>; 2],
}

/// What [`FrameDrawing`] is made of, besides its device and mesh.
pub(super) struct DrawingSetup {
    /// The image's renderer settings.
    pub settings: RenderSettings,
    /// `camera.measure_max_length_px`.
    pub measure_max_length_px: f64,
    /// `camera.occlusion_s`.
    pub occlusion_s: [f64; 2],
    /// `camera.pipeline`.
    pub pipeline: CameraPipeline,
    /// The tracking window.
    pub tracker: TrackingWindow,
    /// `output.frames_every` (0: none saved).
    pub frames_every: u32,
}

impl FrameDrawing {
    /// The image's renderer on `gpu` for `mesh`, and the rest of `setup`.
    pub fn new(
        gpu: &GpuContext,
        mesh: TargetMesh,
        setup: DrawingSetup,
    ) -> Result<Self, SensorError> {
        let intrinsics = setup.settings.intrinsics;
        let whole = ImageRegion::whole(&intrinsics);
        let saved_every = setup.frames_every;
        Ok(Self {
            intrinsics,
            renderer: Renderer::new(gpu, setup.settings, &mesh)?,
            gpu: gpu.clone(),
            mesh,
            binning: Binning::new(&intrinsics, setup.measure_max_length_px),
            binned_renderers: Vec::new(),
            occlusion_s: setup.occlusion_s,
            pipeline: setup.pipeline,
            tracker: setup.tracker,
            saved_every: (saved_every > 0).then_some(u64::from(saved_every)),
            window_counts: WindowCounts::default(),
            pixels: [CameraImage::default(), CameraImage::default()],
            regions: [whole, whole],
            windows: [None, None],
            factors: [1, 1],
            others: Vec::new(),
            drawn_others: [Vec::new(), Vec::new()],
        })
    }

    /// The image's intrinsics.
    pub fn intrinsics(&self) -> &CameraIntrinsics {
        &self.intrinsics
    }

    /// The target mesh.
    pub fn mesh(&self) -> &TargetMesh {
        &self.mesh
    }

    /// Draws `others` with the target in the frames begun from now on.
    pub fn set_other_aircraft(&mut self, others: &[OtherAircraft]) {
        self.others = others.to_vec();
    }

    /// How the frames were drawn so far.
    pub fn window_counts(&self) -> WindowCounts {
        self.window_counts
    }

    /// The part of the image to draw for frame `index`, whose camera the follower believes
    /// turned by `camera_from_ned`, the tracking window to measure it in (see the
    /// `sensing::camera` documentation), both in the pixels of the binning factor returned
    /// with them (1: the image's), counted in [`WindowCounts`].
    pub fn plan(
        &mut self,
        index: u64,
        camera_from_ned: &Mat3,
    ) -> (ImageRegion, Option<ImageRegion>, u32) {
        let whole = ImageRegion::whole(&self.intrinsics);
        let window = match self.pipeline {
            CameraPipeline::Window => self.tracker.predict(index, camera_from_ned),
            CameraPipeline::Whole => None,
        };
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

    /// Starts drawing `region` of a frame (in the pixels of binning `factor`), to be
    /// measured in `window`.
    pub fn begin(
        &mut self,
        exposure: &Exposure,
        region: &ImageRegion,
        window: Option<ImageRegion>,
        factor: u32,
    ) -> Result<PendingFrame, SensorError> {
        let buffer = buffer_of(exposure.index);
        self.factors[buffer] = factor;
        let pose = self.drawn_pose(exposure);
        let mesh_size_ft = self.mesh.max_dimension_ft();
        let others: Vec<AircraftPose> = (self.others.iter())
            .map(|o| o.pose_from(&exposure.geometry.follower, mesh_size_ft))
            .collect();
        let renderer = self.renderer_for(factor)?;
        renderer.set_camera_in_world(&camera_in_world(exposure));
        renderer.set_other_aircraft(&others);
        let pending = renderer.begin_frame_in(&pose, region)?;
        self.drawn_others[buffer] = others;
        self.windows[buffer] = window;
        Ok(pending)
    }

    /// Draws a frame again, whole, to be measured whole (the frame in flight is read back
    /// first, as the renderer draws one frame at a time).
    pub fn redraw_whole(
        &mut self,
        exposure: &Exposure,
        in_flight: &mut InFlight,
        timings: &mut CameraTimings,
    ) -> Result<(), SensorError> {
        self.window_counts.redrawn_whole += 1;
        self.draw_whole_again(exposure, in_flight, timings)
    }

    /// Draws a measured frame again, whole, when it is to be saved and was not drawn whole:
    /// the saved image is the whole image, its measurement the one already made.
    pub fn redraw_to_save(
        &mut self,
        exposure: &Exposure,
        in_flight: &mut InFlight,
        timings: &mut CameraTimings,
    ) -> Result<(), SensorError> {
        let saved = self
            .saved_every
            .is_some_and(|n| exposure.index.is_multiple_of(n));
        if !saved || self.is_whole(exposure.index) {
            return Ok(());
        }
        self.window_counts.whole_saved += 1;
        self.draw_whole_again(exposure, in_flight, timings)
    }

    /// Draws frame `exposure` whole at the image's resolution into its buffer, the frame in
    /// flight read back first.
    fn draw_whole_again(
        &mut self,
        exposure: &Exposure,
        in_flight: &mut InFlight,
        timings: &mut CameraTimings,
    ) -> Result<(), SensorError> {
        self.finish(in_flight, timings)?;
        let whole = ImageRegion::whole(&self.intrinsics);
        let pose = self.drawn_pose(exposure);
        let buffer = buffer_of(exposure.index);
        self.factors[buffer] = 1;
        self.renderer
            .set_camera_in_world(&camera_in_world(exposure));
        self.renderer.set_other_aircraft(&self.drawn_others[buffer]);
        let redrawn = self.renderer.begin_frame_in(&pose, &whole)?;
        self.finish(&mut Some((redrawn, exposure.index)), timings)?;
        self.windows[buffer] = None;
        Ok(())
    }

    /// Reads the frame in flight, if any, back into its buffer.
    pub fn finish(
        &mut self,
        in_flight: &mut InFlight,
        timings: &mut CameraTimings,
    ) -> Result<(), SensorError> {
        let Some((pending, index)) = in_flight.take() else {
            return Ok(());
        };
        let buffer = buffer_of(index);
        self.regions[buffer] = pending.region();
        let mut pixels = std::mem::take(&mut self.pixels[buffer]);
        let renderer = self.renderer_for(self.factors[buffer])?;
        let finished = renderer.finish_frame(pending, index, &mut pixels);
        let render_timings = renderer.last_timings();
        self.pixels[buffer] = pixels;
        finished?;
        timings.add_render(render_timings);
        Ok(())
    }

    /// The read-back frame `index`, as it is to be measured.
    pub fn frame(&self, index: u64) -> Result<DrawnFrame<'_>, SensorError> {
        let buffer = buffer_of(index);
        let factor = self.factors[buffer];
        Ok(DrawnFrame {
            pixels: &self.pixels[buffer],
            window: self.windows[buffer],
            factor,
            intrinsics: self.intrinsics_of(factor)?,
        })
    }

    /// The pixels of frame `index` when it was drawn whole at the image's resolution.
    pub fn whole_image(&self, index: u64) -> Option<&CameraImage> {
        self.is_whole(index).then(|| &self.pixels[buffer_of(index)])
    }

    /// Tells the tracking window where frame `index` measured the target, its camera believed
    /// turned by `camera_from_ned`.
    pub fn observe(&mut self, index: u64, blob: &BlobMeasurement, camera_from_ned: &Mat3) {
        self.tracker.observe(index, blob, camera_from_ned);
    }

    fn is_whole(&self, index: u64) -> bool {
        let buffer = buffer_of(index);
        self.factors[buffer] == 1 && self.regions[buffer].is_whole(&self.intrinsics)
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

    /// The target's pose as a frame draws it: where it truly is, or nowhere while the
    /// occlusion hides it.
    fn drawn_pose(&self, exposure: &Exposure) -> TargetPoseInCamera {
        let [hide_s, show_s] = self.occlusion_s;
        if (hide_s..show_s).contains(&exposure.t_s) {
            TargetPoseInCamera::hidden()
        } else {
            exposure.geometry.pose()
        }
    }
}
