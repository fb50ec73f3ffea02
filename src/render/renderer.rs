//! Off-screen renderer: draws the target mesh, as the follower's camera sees it, into an RGBA8
//! texture (optionally 4x multisampled and resolved) and reads it back into a [`CameraImage`]
//! (`render::readback`). Pixel noise is then added on the CPU ([`crate::render::noise`]).
//!
//! A frame may be drawn and read back in an [`ImageRegion`] only, so that the camera's cost
//! follows the target, not the image size: the region's sky is copied from a sky texture drawn
//! once (a world scene, which follows the camera's pose, is drawn in the region alone), the
//! target's window (`render::window`, planned from the pose as for a whole frame) is
//! drawn and copied over it where they overlap, and only the region is copied into the staging
//! buffer, mapped and unpadded. Nothing else of the image is touched, and the region holds the
//! bytes the whole frame holds there.
//!
//! A whole frame under a screen-fixed sky is composed the same way on the CPU: the sky
//! texture's pixels, read back once, with the target's window read back and pasted over them;
//! so a whole frame costs a window's drawing and readback plus one copy of the image in memory.

use std::time::Instant;

use crate::frames::Vec3;
use crate::render::camera::{AircraftPose, TargetPoseInCamera};
use crate::render::gpu::GpuContext;
use crate::render::image::CameraImage;
use crate::render::mesh::TargetMesh;
use crate::render::noise::NoiseGenerator;
use crate::render::passes::Passes;
use crate::render::projection::PixelWindow;
pub use crate::render::readback::ReadbackError;
use crate::render::readback::{MapReport, Staging};
use crate::render::region::ImageRegion;
use crate::render::scene::CameraInWorld;
use crate::render::settings::{RenderSettings, Sky};
use crate::render::targets::{RenderTargets, WindowTargetsCache, copy_window, sky_texture};
use crate::render::uniforms::{UniformSlots, uniform_layout};
use crate::render::vertices::{TargetVertex, flat_shaded_vertices};
use crate::render::window::{FramePlan, WindowCopy, plan_frame_with_others};

/// Why a renderer could not be built or a frame not rendered.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// A setting is out of range.
    #[error("render settings: {0}")]
    InvalidSettings(String),
    /// The mesh has no triangles or refers to missing vertices.
    #[error("target mesh: {0}")]
    InvalidMesh(String),
    /// The pose holds NaN or infinite numbers.
    #[error("target pose in camera is not finite: {0:?}")]
    NonFinitePose(TargetPoseInCamera),
    /// wgpu rejected the creation of a GPU resource (validation or out of memory).
    #[error("GPU rejected the renderer's resources: {0}")]
    Gpu(#[source] wgpu::Error),
    /// The frame could not be read back from the GPU.
    #[error("frame readback failed: {0}")]
    Readback(#[from] ReadbackError),
}

/// A frame submitted by [`Renderer::begin_frame`] and not yet read back.
#[derive(Debug)]
pub struct PendingFrame {
    submission: wgpu::SubmissionIndex,
    /// The part of the image drawn and read back.
    region: ImageRegion,
    /// Reports the staging buffer's mapping.
    mapped: MapReport,
    /// A whole frame over a screen-fixed sky: the part of the target's window inside the
    /// image, the only pixels read back; the rest is the sky's, filled in on the CPU.
    window_part: Option<ImageRegion>,
}

impl PendingFrame {
    /// The part of the image this frame draws and reads back.
    pub fn region(&self) -> ImageRegion {
        self.region
    }
}

/// What a frame whose commands are encoded, not yet submitted, will read back.
struct EncodedFrame {
    /// The part of the image drawn.
    region: ImageRegion,
    /// The part of the image copied into the staging buffer.
    read: ImageRegion,
    /// As [`PendingFrame::window_part`].
    window_part: Option<ImageRegion>,
}

/// Wall-clock times of the last frame, s.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RenderTimings {
    /// Uniform upload, command encoding and submission.
    pub submit_s: f64,
    /// Waiting for the GPU to draw and copy (on lavapipe the drawing happens here), mapping
    /// the staging buffer and unpadding rows into the frame.
    pub readback_s: f64,
    /// Adding pixel noise on the CPU (0 without noise).
    pub noise_s: f64,
}

/// Renders the target into frames of a fixed size.
#[derive(Debug)]
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    settings: RenderSettings,
    /// The pipelines, the uploaded mesh and the clear colour.
    passes: Passes,
    uniform_slots: UniformSlots,
    /// The mesh's vertices, target axes, ft (plan the target's window).
    vertices_ft: Vec<Vec3>,
    /// Window framebuffers by size, made when first needed.
    windows: WindowTargetsCache,
    /// The whole image's framebuffers; its resolve texture is the image read back.
    image: RenderTargets,
    /// The sky alone over the whole image, drawn once (see `targets::sky_texture`).
    sky: wgpu::Texture,
    /// The sky texture's pixels, read back once (screen-fixed skies; None for a world scene).
    sky_pixels: Option<CameraImage>,
    /// The target window's pixels of the last whole frame composed on the CPU.
    window_pixels: CameraImage,
    staging: Staging,
    noise: Option<NoiseGenerator>,
    /// The frame [`Renderer::render`] reads back into and returns.
    frame: CameraImage,
    timings: RenderTimings,
    /// Where the camera is in a world scene (unused under a screen-fixed sky).
    camera_in_world: CameraInWorld,
    /// Other aircraft drawn with the target in the frames begun from now on.
    others: Vec<AircraftPose>,
}

impl Renderer {
    /// Builds the pipelines and buffers for `settings` and uploads `mesh` (target-body axes, ft).
    pub fn new(
        gpu: &GpuContext,
        settings: RenderSettings,
        mesh: &TargetMesh,
    ) -> Result<Self, RenderError> {
        settings
            .validate(gpu.limits().max_texture_dimension_2d)
            .map_err(RenderError::InvalidSettings)?;
        let vertices = flat_shaded_vertices(mesh).map_err(RenderError::InvalidMesh)?;
        let device = gpu.device().clone();
        let oom_scope = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation_scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let built = Self::build(gpu, settings, &vertices, mesh.vertices_ft.clone());
        let validation = pollster::block_on(validation_scope.pop());
        let oom = pollster::block_on(oom_scope.pop());
        if let Some(e) = validation.or(oom) {
            return Err(RenderError::Gpu(e));
        }
        let mut renderer = built;
        if !renderer.has_world() {
            renderer.sky_pixels = Some(renderer.read_sky()?);
        }
        Ok(renderer)
    }

    /// Reads the sky texture back: the bytes outside the target's window of every whole
    /// frame under a screen-fixed sky.
    fn read_sky(&self) -> Result<CameraImage, RenderError> {
        let whole = ImageRegion::whole(&self.settings.intrinsics);
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("sky readback"),
            });
        self.staging.copy_region(&mut encoder, &self.sky, &whole);
        let submission = self.queue.submit([encoder.finish()]);
        let mapped = self.staging.map(&whole);
        let mut sky = CameraImage::default();
        self.staging
            .read(&self.device, submission, &mapped, &whole, &mut sky)?;
        Ok(sky)
    }

    /// Creates the renderer's GPU objects (inside [`Self::new`]'s error scopes) and uploads
    /// the mesh and the first uniforms.
    fn build(
        gpu: &GpuContext,
        settings: RenderSettings,
        vertices: &[TargetVertex],
        vertices_ft: Vec<Vec3>,
    ) -> Self {
        let device = gpu.device().clone();
        let queue = gpu.queue().clone();
        let cam = settings.intrinsics;
        let shader = device.create_shader_module(wgpu::include_wgsl!("../../shaders/target.wgsl"));

        let uniform_layout = uniform_layout(&device);
        let uniform_slots = UniformSlots::new(
            &device,
            &queue,
            &uniform_layout,
            gpu.limits().min_uniform_buffer_offset_alignment,
            &settings,
        );
        let passes = Passes::new(&device, &shader, &uniform_layout, &settings, vertices);
        let image = RenderTargets::image(&device, &cam, settings.msaa_samples);
        let staging = Staging::new(&device, &cam);
        let sky = sky_texture(&device, &cam);

        let renderer = Self {
            device,
            queue,
            settings,
            passes,
            uniform_slots,
            vertices_ft,
            windows: WindowTargetsCache::default(),
            image,
            sky,
            sky_pixels: None,
            window_pixels: CameraImage::default(),
            staging,
            noise: settings
                .background
                .noise
                .map(|n| NoiseGenerator::new(n.std_grey_levels, n.seed)),
            frame: CameraImage::filled(cam.width_px, cam.height_px, [0, 0, 0, 255]),
            timings: RenderTimings::default(),
            camera_in_world: CameraInWorld::default(),
            others: Vec::new(),
        };
        if !renderer.has_world() {
            renderer.paint_sky_texture();
        }
        renderer
    }

    /// Whether the sky is a world scene (drawn per frame from the camera's pose).
    fn has_world(&self) -> bool {
        matches!(self.settings.background.sky, Sky::World(_))
    }

    /// Places the camera in the world scene for the frames begun from now on: the world is
    /// drawn from this pose (the truth), the target from its pose in the camera's axes.
    /// Frames under a screen-fixed sky do not depend on it.
    pub fn set_camera_in_world(&mut self, camera: &CameraInWorld) {
        self.camera_in_world = *camera;
    }

    /// Draws `others` (the target's mesh at their poses and scales) with the target in the
    /// frames begun from now on, occluding it and one another by depth (none by default).
    pub fn set_other_aircraft(&mut self, others: &[AircraftPose]) {
        self.others = others.to_vec();
    }

    /// Draws the sky texture, with the pass that draws the sky of a whole frame.
    fn paint_sky_texture(&self) {
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sky") });
        let view = self.sky.create_view(&Default::default());
        self.passes.draw_sky(
            &mut encoder,
            &view,
            self.uniform_slots.bind_group(false),
            None,
        );
        self.queue.submit([encoder.finish()]);
    }

    /// The settings this renderer was built with.
    pub fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    /// Renders the target at `pose` and reads the image back. `frame_index` keys the pixel
    /// noise (same index, same noise). A target wholly behind the camera (or nearer than
    /// [`crate::render::projection::NEAR_PLANE_FT`]) is clipped: the frame shows only sky.
    pub fn render(
        &mut self,
        pose: &TargetPoseInCamera,
        frame_index: u64,
    ) -> Result<&CameraImage, RenderError> {
        let pending = self.begin_frame(pose)?;
        let mut frame = std::mem::take(&mut self.frame);
        let finished = self.finish_frame(pending, frame_index, &mut frame);
        self.frame = frame;
        finished.map(|()| &self.frame)
    }

    /// Renders the target at `pose` in `region` of the image only and reads that region back
    /// (the frame's size is the region's). Its pixels are those of the whole frame there.
    pub fn render_region(
        &mut self,
        pose: &TargetPoseInCamera,
        region: &ImageRegion,
        frame_index: u64,
    ) -> Result<&CameraImage, RenderError> {
        let pending = self.begin_frame_in(pose, region)?;
        let mut frame = std::mem::take(&mut self.frame);
        let finished = self.finish_frame(pending, frame_index, &mut frame);
        self.frame = frame;
        finished.map(|()| &self.frame)
    }

    /// Starts drawing the target at `pose` and returns at once: the GPU (or lavapipe's
    /// threads) draws while the caller works; [`Self::finish_frame`] waits for it. One frame
    /// may be in flight at a time (it owns the staging buffer).
    pub fn begin_frame(&mut self, pose: &TargetPoseInCamera) -> Result<PendingFrame, RenderError> {
        let whole = ImageRegion::whole(&self.settings.intrinsics);
        self.begin_frame_in(pose, &whole)
    }

    /// As [`Self::begin_frame`], drawing and reading back only `region` of the image (cut to
    /// the image).
    pub fn begin_frame_in(
        &mut self,
        pose: &TargetPoseInCamera,
        region: &ImageRegion,
    ) -> Result<PendingFrame, RenderError> {
        let start = Instant::now();
        let pending = self.submit(pose, &self.clipped(region))?;
        self.timings.submit_s = start.elapsed().as_secs_f64();
        Ok(pending)
    }

    /// `region` cut to the image (the whole image when nothing of it is inside).
    fn clipped(&self, region: &ImageRegion) -> ImageRegion {
        let cam = &self.settings.intrinsics;
        ImageRegion::covering(
            f64::from(region.u0_px),
            f64::from(region.u_end_px()),
            f64::from(region.v0_px),
            f64::from(region.v_end_px()),
            cam,
        )
        .unwrap_or_else(|| ImageRegion::whole(cam))
    }

    /// Waits for the frame [`Self::begin_frame`] (or [`Self::begin_frame_in`]) started, reads
    /// its region back into `frame` (resized to the region) and adds the pixel noise of
    /// `frame_index` (each pixel's, as in the whole image).
    pub fn finish_frame(
        &mut self,
        pending: PendingFrame,
        frame_index: u64,
        frame: &mut CameraImage,
    ) -> Result<(), RenderError> {
        let start = Instant::now();
        let region = pending.region;
        match (&pending.window_part, &self.sky_pixels) {
            (Some(part), Some(sky)) => {
                let (device, submission) = (&self.device, pending.submission);
                let window = &mut self.window_pixels;
                self.staging
                    .read(device, submission, &pending.mapped, part, window)?;
                frame.clone_from(sky);
                frame.paste(window, [part.u0_px, part.v0_px]);
            }
            _ => self.staging.read(
                &self.device,
                pending.submission,
                &pending.mapped,
                &region,
                frame,
            )?,
        }
        let read = Instant::now();
        if let Some(noise) = &self.noise {
            let width_px = self.settings.intrinsics.width_px;
            noise.apply_in_region(&mut frame.rgba, &region, width_px, frame_index);
        }
        self.timings.readback_s = (read - start).as_secs_f64();
        self.timings.noise_s = read.elapsed().as_secs_f64();
        Ok(())
    }

    /// Timings of the last frame.
    pub fn last_timings(&self) -> RenderTimings {
        self.timings
    }

    /// Writes the uniforms for `pose`, encodes the passes of its frame plan in `region` and
    /// the copy of `region` into the staging buffer, submits them and starts mapping the
    /// staging buffer.
    fn submit(
        &mut self,
        pose: &TargetPoseInCamera,
        region: &ImageRegion,
    ) -> Result<PendingFrame, RenderError> {
        let (encoded, commands) = self.encode(pose, region)?;
        let submission = self.queue.submit([commands]);
        Ok(self.launched(encoded, submission))
    }

    /// Starts drawing a frame in each renderer of `frames` (each its pose and region, as
    /// [`Self::begin_frame_in`]) in one submission to their shared queue: one frame's work
    /// per camera, one hand-over to the GPU (or lavapipe's queue) for them all. Each frame is
    /// read back by its own renderer's [`Self::finish_frame`].
    pub fn begin_frames(
        frames: &mut [(&mut Renderer, TargetPoseInCamera, ImageRegion)],
    ) -> Result<Vec<PendingFrame>, RenderError> {
        let start = Instant::now();
        let mut encoded = Vec::new();
        let mut commands = Vec::new();
        for (renderer, pose, region) in frames.iter_mut() {
            let region = renderer.clipped(region);
            let (frame, buffer) = renderer.encode(pose, &region)?;
            encoded.push(frame);
            commands.push(buffer);
        }
        let Some((first, _, _)) = frames.first() else {
            return Ok(Vec::new());
        };
        let submission = first.queue.submit(commands);
        let submit_s = start.elapsed().as_secs_f64() / frames.len() as f64;
        let pending = (frames.iter_mut().zip(encoded))
            .map(|((renderer, _, _), frame)| {
                renderer.timings.submit_s = submit_s;
                renderer.launched(frame, submission.clone())
            })
            .collect();
        Ok(pending)
    }

    /// The frame `encoded` in flight after `submission`: the staging buffer's mapping started.
    fn launched(&self, encoded: EncodedFrame, submission: wgpu::SubmissionIndex) -> PendingFrame {
        PendingFrame {
            submission,
            region: encoded.region,
            mapped: self.staging.map(&encoded.read),
            window_part: encoded.window_part,
        }
    }

    /// Writes the uniforms for `pose` and encodes the passes of its frame plan in `region`
    /// and the copy of what is read back into the staging buffer: the commands, not yet
    /// submitted, and what they will read back.
    fn encode(
        &mut self,
        pose: &TargetPoseInCamera,
        region: &ImageRegion,
    ) -> Result<(EncodedFrame, wgpu::CommandBuffer), RenderError> {
        if !(pose.position_body_ft.iter().all(|x| x.is_finite())
            && pose.body_from_target.iter().all(|x| x.is_finite()))
        {
            return Err(RenderError::NonFinitePose(*pose));
        }
        let target_to_body =
            self.uniform_slots
                .write_image(&self.queue, pose, &self.camera_in_world);
        let cam = self.settings.intrinsics;
        let plan = if self.settings.target_window {
            plan_frame_with_others(&self.vertices_ft, pose, &self.others, region, &cam)
        } else {
            FramePlan::Whole
        };
        let window = match plan {
            FramePlan::Window(window) => Some(window),
            _ => None,
        };
        if let Some(window) = &window {
            self.uniform_slots
                .write_window(&self.queue, &self.settings, window, &target_to_body);
        }
        if !self.others.is_empty() {
            let in_window = window.as_ref().map(|w| (&self.settings, w));
            self.uniform_slots
                .write_others(&self.device, &self.queue, &self.others, in_window);
        }

        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("target frame"),
            });
        let window_part = self.window_part_over_sky(plan, region);
        let read = if let (Some(part), FramePlan::Window(window)) = (window_part, plan) {
            self.draw_window_part(&mut encoder, &window, &part);
            part
        } else {
            if region.is_whole(&cam) {
                self.encode_passes(&mut encoder, plan);
            } else {
                self.encode_region_passes(&mut encoder, plan, region);
            }
            self.staging
                .copy_region(&mut encoder, &self.image.resolve_texture, region);
            *region
        };
        let encoded = EncodedFrame {
            region: *region,
            read,
            window_part,
        };
        Ok((encoded, encoder.finish()))
    }

    /// The part of the target's window inside the image, when a whole frame is composed on
    /// the CPU: a screen-fixed sky read back once, under a target drawn in its window.
    fn window_part_over_sky(&self, plan: FramePlan, region: &ImageRegion) -> Option<ImageRegion> {
        let cam = &self.settings.intrinsics;
        let (FramePlan::Window(window), Some(_)) = (plan, &self.sky_pixels) else {
            return None;
        };
        let copy = WindowCopy::of(&window, region).filter(|_| region.is_whole(cam))?;
        Some(ImageRegion {
            u0_px: copy.to_px[0],
            v0_px: copy.to_px[1],
            width_px: copy.size_px[0],
            height_px: copy.size_px[1],
        })
    }

    /// Draws the target in its window's framebuffers and copies `part` of it (where it lies
    /// in the image) into the staging buffer.
    fn draw_window_part(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        window: &PixelWindow,
        part: &ImageRegion,
    ) {
        let slot = self.draw_in_window(encoder, window);
        let targets = self.windows.targets(slot);
        let from_px = [
            (i64::from(part.u0_px) - window.u0_px) as u32,
            (i64::from(part.v0_px) - window.v0_px) as u32,
        ];
        self.staging
            .copy_from(encoder, &targets.resolve_texture, from_px, part);
    }

    /// The render passes of `plan`, leaving the frame in the image's resolve texture.
    fn encode_passes(&mut self, encoder: &mut wgpu::CommandEncoder, plan: FramePlan) {
        let whole = ImageRegion::whole(&self.settings.intrinsics);
        let image_uniforms = self.uniform_slots.bind_group(false);
        match plan {
            FramePlan::Whole => {
                let others = self
                    .uniform_slots
                    .other_bind_groups(self.others.len(), false);
                self.passes
                    .draw_target(encoder, &self.image, image_uniforms, &others)
            }
            FramePlan::SkyOnly => self.draw_sky_in(encoder, &whole),
            FramePlan::Window(window) => {
                self.draw_sky_in(encoder, &whole);
                self.draw_window(encoder, &window, &whole);
            }
        }
    }

    /// The passes and copies of `plan` that leave, in `region` of the image's resolve
    /// texture, the pixels the whole frame has there: the sky copied from the sky texture (a
    /// world scene drawn in the region) and the target's window copied over it where they
    /// overlap. A plan that draws the target
    /// over the whole image (a near or large target) draws the whole frame.
    fn encode_region_passes(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        plan: FramePlan,
        region: &ImageRegion,
    ) {
        if plan == FramePlan::Whole {
            return self.encode_passes(encoder, plan);
        }
        self.draw_sky_in(encoder, region);
        if let FramePlan::Window(window) = plan {
            self.draw_window(encoder, &window, region);
        }
    }

    /// Leaves the sky alone in `region` of the image's resolve texture: a world scene drawn
    /// from the camera's pose, a screen-fixed sky copied from the sky texture (the bytes
    /// drawing it gives, for a copy's cost).
    fn draw_sky_in(&self, encoder: &mut wgpu::CommandEncoder, region: &ImageRegion) {
        if self.has_world() {
            let uniforms = self.uniform_slots.bind_group(false);
            let cut = (!region.is_whole(&self.settings.intrinsics)).then_some(region);
            self.passes
                .draw_sky(encoder, &self.image.resolve_view, uniforms, cut);
        } else {
            let sky_copy = WindowCopy {
                from_px: [region.u0_px, region.v0_px],
                to_px: [region.u0_px, region.v0_px],
                size_px: [region.width_px, region.height_px],
            };
            copy_window(encoder, &self.sky, &self.image.resolve_texture, &sky_copy);
        }
    }

    /// Draws the target, and the other aircraft, into its window's framebuffers; their slot
    /// in the cache.
    fn draw_in_window(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        window: &PixelWindow,
    ) -> usize {
        let samples = self.settings.msaa_samples;
        let slot = self.windows.slot_for(&self.device, window, samples);
        let others = self
            .uniform_slots
            .other_bind_groups(self.others.len(), true);
        self.passes.draw_target(
            encoder,
            self.windows.targets(slot),
            self.uniform_slots.bind_group(true),
            &others,
        );
        slot
    }

    /// Draws the target into its window's framebuffers and copies the part of the window
    /// inside `region` into the image (nothing when they do not overlap).
    fn draw_window(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        window: &PixelWindow,
        region: &ImageRegion,
    ) {
        let Some(copy) = WindowCopy::of(window, region) else {
            return;
        };
        let slot = self.draw_in_window(encoder, window);
        let targets = self.windows.targets(slot);
        copy_window(
            encoder,
            &targets.resolve_texture,
            &self.image.resolve_texture,
            &copy,
        );
    }
}
