//! Off-screen renderer: draws the target mesh, as the follower's camera sees it, into an RGBA8
//! texture (optionally 4x multisampled and resolved) and reads it back into a [`CameraImage`].
//!
//! Per frame only a 192-byte uniform block changes; the mesh is uploaded once. Readback copies
//! the texture into a persistent staging buffer whose rows are padded to
//! [`wgpu::COPY_BYTES_PER_ROW_ALIGNMENT`], maps it, waits for the exact submission (DESIGN §6:
//! another thread's poll may run the map callback, so the callback reports on a channel) and
//! unpads the rows into a reusable [`CameraImage`]. Pixel noise is then added on the CPU
//! ([`crate::render::noise`]).
//!
//! A frame may be drawn and read back in an [`ImageRegion`] only (issue 13: the camera's cost
//! should follow the target, not the image size): the region's sky is copied from a sky
//! texture drawn once, the target's window (`render::window`, planned from the pose as for a
//! whole frame) is drawn and copied over it where they overlap, and only the region is copied
//! into the staging buffer, mapped and unpadded. Nothing else of the image is touched, and the
//! region holds the bytes the whole frame holds there.

use std::sync::mpsc;
use std::time::Instant;

use bytemuck::{Pod, Zeroable};
use nalgebra::Matrix4;
use wgpu::util::DeviceExt;

use crate::frames::Vec3;
use crate::render::camera::TargetPoseInCamera;
use crate::render::gpu::GpuContext;
use crate::render::image::CameraImage;
use crate::render::mesh::TargetMesh;
use crate::render::noise::NoiseGenerator;
use crate::render::projection::{
    PixelWindow, body_from_target, clip_from_body, clip_from_body_in_window,
};
use crate::render::region::ImageRegion;
use crate::render::settings::{RenderSettings, Sky};
use crate::render::window::{FramePlan, WindowCopy, plan_frame};

const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

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

/// The step of a frame's readback that failed, with wgpu's error.
#[derive(Debug, thiserror::Error)]
pub enum ReadbackError {
    /// Waiting for the frame's submission failed.
    #[error("waiting for the GPU: {0}")]
    Wait(#[from] wgpu::PollError),
    /// The staging buffer's map callback was dropped without reporting.
    #[error("map callback was dropped")]
    CallbackDropped(#[from] mpsc::RecvError),
    /// The staging buffer could not be mapped.
    #[error("mapping the staging buffer: {0}")]
    Map(#[from] wgpu::BufferAsyncError),
    /// The mapped staging buffer could not be viewed.
    #[error("{0}")]
    View(#[from] wgpu::MapRangeError),
}

/// A frame submitted by [`Renderer::begin_frame`] and not yet read back.
#[derive(Debug)]
pub struct PendingFrame {
    submission: wgpu::SubmissionIndex,
    /// The part of the image drawn and read back.
    region: ImageRegion,
    /// Reports the staging buffer's mapping (DESIGN §6: another thread's poll may run the
    /// callback).
    mapped: mpsc::Receiver<Result<(), wgpu::BufferAsyncError>>,
}

impl PendingFrame {
    /// The part of the image this frame draws and reads back.
    pub fn region(&self) -> ImageRegion {
        self.region
    }
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

/// The per-frame uniform block; layout matches `FrameUniforms` in `shaders/target.wgsl`
/// (mat3x3 columns padded to vec4, total 192 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct FrameUniforms {
    clip_from_target: [[f32; 4]; 4],
    body_from_target: [[f32; 4]; 3],
    light_dir_body: [f32; 4],
    target_grey: [f32; 4],
    sky_top: [f32; 4],
    sky_bottom: [f32; 4],
    image: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<FrameUniforms>() == 192);

/// One vertex of the un-indexed, flat-shaded target: position and its face's normal.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct TargetVertex {
    position_target_ft: [f32; 3],
    normal_target: [f32; 3],
}

fn unit_rgb(rgb: [u8; 3]) -> [f32; 4] {
    [
        f32::from(rgb[0]) / 255.0,
        f32::from(rgb[1]) / 255.0,
        f32::from(rgb[2]) / 255.0,
        1.0,
    ]
}

fn columns_f32(m: &Matrix4<f64>) -> [[f32; 4]; 4] {
    std::array::from_fn(|c| std::array::from_fn(|r| m[(r, c)] as f32))
}

/// Renders the target into frames of a fixed size.
#[derive(Debug)]
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    settings: RenderSettings,
    pipelines: Pipelines,
    vertex_buffer: wgpu::Buffer,
    vertex_count: u32,
    uniform_slots: UniformSlots,
    /// The mesh's vertices, target axes, ft (plan the target's window).
    vertices_ft: Vec<Vec3>,
    /// Window framebuffers by size, made when first needed.
    windows: WindowTargetsCache,
    uniforms: FrameUniforms,
    clip_from_body: Matrix4<f64>,
    /// The whole image's framebuffers; its resolve texture is the image read back.
    image: RenderTargets,
    /// The sky alone over the whole image, drawn once: a frame drawn in a region of the image
    /// copies its sky from here (the sky depends on the pixel only, never on the pose).
    sky: wgpu::Texture,
    staging: wgpu::Buffer,
    clear_color: wgpu::Color,
    noise: Option<NoiseGenerator>,
    /// The frame [`Renderer::render`] reads back into and returns.
    frame: CameraImage,
    timings: RenderTimings,
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
        let vertices = flat_shaded_vertices(mesh)?;
        let device = gpu.device().clone();
        let oom_scope = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation_scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let built = Self::build(gpu, settings, &vertices, mesh.vertices_ft.clone());
        let validation = pollster::block_on(validation_scope.pop());
        let oom = pollster::block_on(oom_scope.pop());
        if let Some(e) = validation.or(oom) {
            return Err(RenderError::Gpu(e));
        }
        Ok(built)
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

        let uniforms = initial_uniforms(&settings);
        let uniform_layout = uniform_layout(&device);
        let uniform_slots = UniformSlots::new(
            &device,
            &uniform_layout,
            gpu.limits().min_uniform_buffer_offset_alignment,
        );
        queue.write_buffer(&uniform_slots.buffer, 0, bytemuck::bytes_of(&uniforms));
        let pipelines = Pipelines::new(&device, &shader, &uniform_layout, &settings);
        let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("target vertices"),
            contents: bytemuck::cast_slice(vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let image = RenderTargets::new(
            &device,
            "",
            extent_px(cam.width_px, cam.height_px),
            settings.msaa_samples,
            wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST,
        );
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: staging_bytes(&ImageRegion::whole(&cam)),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let sky = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("sky"),
            size: extent_px(cam.width_px, cam.height_px),
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: COLOR_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });

        let renderer = Self {
            device,
            queue,
            settings,
            pipelines,
            vertex_buffer,
            vertex_count: vertices.len() as u32,
            uniform_slots,
            vertices_ft,
            windows: WindowTargetsCache::default(),
            uniforms,
            clip_from_body: clip_from_body(&cam),
            image,
            sky,
            staging,
            clear_color: clear_color(&settings.background.sky),
            noise: settings
                .background
                .noise
                .map(|n| NoiseGenerator::new(n.std_grey_levels, n.seed)),
            frame: CameraImage::filled(cam.width_px, cam.height_px, [0, 0, 0, 255]),
            timings: RenderTimings::default(),
        };
        renderer.paint_sky_texture();
        renderer
    }

    /// Draws the sky texture, with the pass that draws the sky of a whole frame.
    fn paint_sky_texture(&self) {
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("sky") });
        let view = self.sky.create_view(&Default::default());
        self.draw_sky(&mut encoder, &view);
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
        self.read_back(pending, frame)?;
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
        if !(pose.position_body_ft.iter().all(|x| x.is_finite())
            && pose.body_from_target.iter().all(|x| x.is_finite()))
        {
            return Err(RenderError::NonFinitePose(*pose));
        }
        let target_to_body = self.write_image_uniforms(pose);
        let cam = self.settings.intrinsics;
        let plan = if self.settings.target_window {
            plan_frame(&self.vertices_ft, pose, &cam)
        } else {
            FramePlan::Whole
        };
        if let FramePlan::Window(window) = plan {
            self.write_window_uniforms(&window, &target_to_body);
        }

        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("target frame"),
            });
        if region.is_whole(&cam) {
            self.encode_passes(&mut encoder, plan);
        } else {
            self.encode_region_passes(&mut encoder, plan, region);
        }
        self.copy_region_to_staging(&mut encoder, region);
        let submission = self.queue.submit([encoder.finish()]);
        Ok(self.map_staging(submission, *region))
    }

    /// Writes the first uniform slot (the whole image's projection of the target at `pose`)
    /// and returns the target-to-body transform.
    fn write_image_uniforms(&mut self, pose: &TargetPoseInCamera) -> Matrix4<f64> {
        let target_to_body = body_from_target(pose);
        let clip_from_target = self.clip_from_body * target_to_body;
        self.uniforms.clip_from_target = columns_f32(&clip_from_target);
        let r = &pose.body_from_target;
        self.uniforms.body_from_target =
            std::array::from_fn(|c| [r[(0, c)] as f32, r[(1, c)] as f32, r[(2, c)] as f32, 0.0]);
        self.queue.write_buffer(
            &self.uniform_slots.buffer,
            0,
            bytemuck::bytes_of(&self.uniforms),
        );
        target_to_body
    }

    /// Writes the second uniform slot: the first with the projection into `window`.
    fn write_window_uniforms(&self, window: &PixelWindow, target_to_body: &Matrix4<f64>) {
        let cam = self.settings.intrinsics;
        let mut in_window = self.uniforms;
        in_window.clip_from_target =
            columns_f32(&(clip_from_body_in_window(&cam, window) * target_to_body));
        in_window.image[1] = window.v0_px as f32;
        self.queue.write_buffer(
            &self.uniform_slots.buffer,
            self.uniform_slots.window_offset,
            bytemuck::bytes_of(&in_window),
        );
    }

    /// The render passes of `plan`, leaving the frame in the image's resolve texture.
    fn encode_passes(&mut self, encoder: &mut wgpu::CommandEncoder, plan: FramePlan) {
        let whole = ImageRegion::whole(&self.settings.intrinsics);
        match plan {
            FramePlan::Whole => self.draw_target(encoder, &self.image, false),
            FramePlan::SkyOnly => self.draw_sky(encoder, &self.image.resolve_view),
            FramePlan::Window(window) => {
                self.draw_sky(encoder, &self.image.resolve_view);
                self.draw_window(encoder, &window, &whole);
            }
        }
    }

    /// The passes and copies of `plan` that leave, in `region` of the image's resolve
    /// texture, the pixels the whole frame has there: the sky copied from the sky texture and
    /// the target's window copied over it where they overlap. A plan that draws the target
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
        let sky_copy = WindowCopy {
            from_px: [region.u0_px, region.v0_px],
            to_px: [region.u0_px, region.v0_px],
            size_px: [region.width_px, region.height_px],
        };
        copy_window(encoder, &self.sky, &self.image.resolve_texture, &sky_copy);
        if let FramePlan::Window(window) = plan {
            self.draw_window(encoder, &window, region);
        }
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
        let samples = self.settings.msaa_samples;
        let slot = self.windows.slot_for(&self.device, window, samples);
        let targets = self.windows.targets(slot);
        self.draw_target(encoder, targets, true);
        copy_window(
            encoder,
            &targets.resolve_texture,
            &self.image.resolve_texture,
            &copy,
        );
    }

    /// Copies `region` of the image's resolve texture into the staging buffer (rows padded).
    fn copy_region_to_staging(&self, encoder: &mut wgpu::CommandEncoder, region: &ImageRegion) {
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &self.image.resolve_texture,
                mip_level: 0,
                origin: wgpu::Origin3d {
                    x: region.u0_px,
                    y: region.v0_px,
                    z: 0,
                },
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &self.staging,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_bytes_per_row(region.width_px)),
                    rows_per_image: Some(region.height_px),
                },
            },
            extent_px(region.width_px, region.height_px),
        );
    }

    /// Starts mapping the part of the staging buffer that holds `region` once `submission`
    /// is done; the frame reports on a channel (DESIGN §6).
    fn map_staging(&self, submission: wgpu::SubmissionIndex, region: ImageRegion) -> PendingFrame {
        let (sender, receiver) = mpsc::channel();
        self.staging.slice(..staging_bytes(&region)).map_async(
            wgpu::MapMode::Read,
            move |result| {
                // The receiver lives until the frame is read back; a send error cannot matter.
                let _ = sender.send(result);
            },
        );
        PendingFrame {
            submission,
            region,
            mapped: receiver,
        }
    }

    /// One pass: sky and target into `targets` (multisampled and resolved when they have
    /// multisampled colour), with the whole image's projection or, `in_window`, the window's.
    fn draw_target(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &RenderTargets,
        in_window: bool,
    ) {
        let (view, resolve_target) = targets.colour_attachment();
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("target frame"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(self.clear_color),
                    store: if resolve_target.is_some() {
                        wgpu::StoreOp::Discard
                    } else {
                        wgpu::StoreOp::Store
                    },
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &targets.depth_view,
                // Reversed depth: 0 is the far plane.
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        let uniforms = if in_window {
            &self.uniform_slots.window
        } else {
            &self.uniform_slots.whole
        };
        pass.set_bind_group(0, uniforms, &[]);
        if let Some(background) = &self.pipelines.background {
            pass.set_pipeline(background);
            pass.draw(0..3, 0..1);
        }
        pass.set_pipeline(&self.pipelines.target);
        pass.set_vertex_buffer(0, self.vertex_buffer.slice(..));
        pass.draw(0..self.vertex_count, 0..1);
    }

    /// The sky alone, one sample per pixel, over the whole image of `view`.
    fn draw_sky(&self, encoder: &mut wgpu::CommandEncoder, view: &wgpu::TextureView) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("sky"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(self.clear_color),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some(sky) = &self.pipelines.one_sample_sky {
            pass.set_bind_group(0, &self.uniform_slots.whole, &[]);
            pass.set_pipeline(sky);
            pass.draw(0..3, 0..1);
        }
    }

    /// Waits for the frame's submission and mapping, and unpads the staging buffer's rows
    /// into `frame` (resized to the frame's region).
    fn read_back(
        &mut self,
        pending: PendingFrame,
        frame: &mut CameraImage,
    ) -> Result<(), ReadbackError> {
        self.device.poll(wgpu::PollType::Wait {
            submission_index: Some(pending.submission),
            timeout: None,
        })?;
        pending.mapped.recv()??;
        let region = pending.region;
        frame.width_px = region.width_px;
        frame.height_px = region.height_px;
        frame.rgba.resize(4 * region.pixel_count(), 0);
        let row_bytes = 4 * region.width_px as usize;
        {
            let mapped = self
                .staging
                .slice(..staging_bytes(&region))
                .get_mapped_range()?;
            for (dst, src) in frame
                .rgba
                .chunks_exact_mut(row_bytes)
                .zip(mapped.chunks_exact(padded_bytes_per_row(region.width_px) as usize))
            {
                dst.copy_from_slice(&src[..row_bytes]);
            }
        }
        self.staging.unmap();
        Ok(())
    }
}

/// Window framebuffers by size, made when first needed; the least recently used goes when
/// more than [`WindowTargetsCache::CAPACITY`] sizes are kept.
#[derive(Debug, Default)]
struct WindowTargetsCache {
    /// (width, height, frame last used, framebuffers).
    entries: Vec<(u32, u32, u64, RenderTargets)>,
    /// Frames drawn with a window.
    uses: u64,
}

impl WindowTargetsCache {
    /// Sizes kept: a target's window changes size with its range and attitude, a few sizes
    /// at a time.
    const CAPACITY: usize = 12;

    /// The slot of the framebuffers of `window`'s size with `samples` per pixel, made when
    /// missing.
    fn slot_for(&mut self, device: &wgpu::Device, window: &PixelWindow, samples: u32) -> usize {
        self.uses += 1;
        let size = (window.width_px, window.height_px);
        let found = self.entries.iter().position(|e| (e.0, e.1) == size);
        let index = found.unwrap_or_else(|| {
            if self.entries.len() >= Self::CAPACITY
                && let Some(oldest) = (0..self.entries.len()).min_by_key(|&i| self.entries[i].2)
            {
                self.entries.swap_remove(oldest);
            }
            let targets = RenderTargets::new(
                device,
                "window ",
                extent_px(size.0, size.1),
                samples,
                wgpu::TextureUsages::COPY_SRC,
            );
            self.entries.push((size.0, size.1, 0, targets));
            self.entries.len() - 1
        });
        self.entries[index].2 = self.uses;
        index
    }

    /// The framebuffers in `slot` (from [`Self::slot_for`]).
    fn targets(&self, slot: usize) -> &RenderTargets {
        &self.entries[slot].3
    }
}

/// The uniform buffer's two slots, the whole image's projection and the target window's, and
/// a bind group for each.
#[derive(Debug)]
struct UniformSlots {
    buffer: wgpu::Buffer,
    /// Binds the first slot: the whole image's projection.
    whole: wgpu::BindGroup,
    /// Binds the second slot: the target window's projection.
    window: wgpu::BindGroup,
    /// Byte offset of the second slot.
    window_offset: u64,
}

impl UniformSlots {
    /// The buffer, its second slot at the first multiple of `min_offset_alignment` after the
    /// first slot, and the slots' bind groups of `layout`.
    fn new(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        min_offset_alignment: u32,
    ) -> Self {
        let uniform_size = std::mem::size_of::<FrameUniforms>() as u64;
        let window_offset = uniform_size.next_multiple_of(u64::from(min_offset_alignment));
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame uniforms"),
            size: window_offset + uniform_size,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let slot = |offset: u64| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("frame uniforms"),
                layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &buffer,
                        offset,
                        size: wgpu::BufferSize::new(uniform_size),
                    }),
                }],
            })
        };
        Self {
            whole: slot(0),
            window: slot(window_offset),
            window_offset,
            buffer,
        }
    }
}

/// The layout of one uniform slot: a [`FrameUniforms`] at binding 0, seen by both stages.
fn uniform_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("frame uniforms"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(
                    std::mem::size_of::<FrameUniforms>() as u64
                ),
            },
            count: None,
        }],
    })
}

/// The render pipelines.
#[derive(Debug)]
struct Pipelines {
    /// The target, `msaa_samples` per pixel, with depth.
    target: wgpu::RenderPipeline,
    /// The gradient sky in the target's pass (none for a uniform sky: the clear colour is
    /// the sky).
    background: Option<wgpu::RenderPipeline>,
    /// The one-sample sky of a frame whose target is drawn in a window (gradient sky only).
    one_sample_sky: Option<wgpu::RenderPipeline>,
}

impl Pipelines {
    /// The pipelines `settings` need, of `shader`'s programs, binding `uniform_layout`.
    fn new(
        device: &wgpu::Device,
        shader: &wgpu::ShaderModule,
        uniform_layout: &wgpu::BindGroupLayout,
        settings: &RenderSettings,
    ) -> Self {
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("target"),
            bind_group_layouts: &[Some(uniform_layout)],
            immediate_size: 0,
        });
        let builder = PipelineBuilder {
            device,
            layout: &layout,
            shader,
        };
        let samples = settings.msaa_samples;
        let attributes = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
        let target = builder.create(
            "target",
            &[Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<TargetVertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &attributes,
            })],
            Some(depth_state(true, wgpu::CompareFunction::Greater)),
            samples,
        );
        let needs_background_pass = matches!(settings.background.sky, Sky::VerticalGradient { .. });
        // The sky: `samples` per pixel when drawn with the target, one in the sky pass of a
        // windowed frame (no depth there).
        let sky = |sample_count: u32, depth: bool| {
            builder.create(
                "background",
                &[],
                depth.then(|| depth_state(false, wgpu::CompareFunction::Always)),
                sample_count,
            )
        };
        Self {
            target,
            background: needs_background_pass.then(|| sky(samples, true)),
            one_sample_sky: needs_background_pass.then(|| sky(1, false)),
        }
    }
}

/// Makes pipelines of one shader module with one layout.
struct PipelineBuilder<'a> {
    device: &'a wgpu::Device,
    layout: &'a wgpu::PipelineLayout,
    shader: &'a wgpu::ShaderModule,
}

impl PipelineBuilder<'_> {
    /// The pipeline of the shader's `vs_{name}` and `fs_{name}`, drawing triangles into one
    /// colour target with `sample_count` samples.
    fn create(
        &self,
        name: &str,
        buffers: &[Option<wgpu::VertexBufferLayout>],
        depth_stencil: Option<wgpu::DepthStencilState>,
        sample_count: u32,
    ) -> wgpu::RenderPipeline {
        self.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(name),
                layout: Some(self.layout),
                vertex: wgpu::VertexState {
                    module: self.shader,
                    entry_point: Some(&format!("vs_{name}")),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    cull_mode: None,
                    ..Default::default()
                },
                depth_stencil,
                multisample: wgpu::MultisampleState {
                    count: sample_count,
                    ..Default::default()
                },
                fragment: Some(wgpu::FragmentState {
                    module: self.shader,
                    entry_point: Some(&format!("fs_{name}")),
                    compilation_options: Default::default(),
                    targets: &[Some(COLOR_FORMAT.into())],
                }),
                multiview_mask: None,
                cache: None,
            })
    }
}

/// Colour (multisampled when there are several samples) and depth attachments of one size,
/// and the one-sample texture the colour resolves into (or is drawn into without
/// multisampling).
#[derive(Debug)]
struct RenderTargets {
    msaa_view: Option<wgpu::TextureView>,
    depth_view: wgpu::TextureView,
    resolve_texture: wgpu::Texture,
    resolve_view: wgpu::TextureView,
}

impl RenderTargets {
    /// Targets of `size` with `samples` per pixel, labelled `label_prefix` + their role; the
    /// resolve texture is also used as `resolve_usage` says.
    fn new(
        device: &wgpu::Device,
        label_prefix: &str,
        size: wgpu::Extent3d,
        samples: u32,
        resolve_usage: wgpu::TextureUsages,
    ) -> Self {
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let texture = |role: &str, sample_count, format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(&format!("{label_prefix}{role}")),
                size,
                mip_level_count: 1,
                sample_count,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let resolve_texture = texture("colour", 1, COLOR_FORMAT, attachment | resolve_usage);
        Self {
            msaa_view: (samples > 1).then(|| {
                texture("colour msaa", samples, COLOR_FORMAT, attachment)
                    .create_view(&Default::default())
            }),
            depth_view: texture("depth", samples, DEPTH_FORMAT, attachment)
                .create_view(&Default::default()),
            resolve_view: resolve_texture.create_view(&Default::default()),
            resolve_texture,
        }
    }

    /// The colour view to draw into and the view it resolves into (none without
    /// multisampling).
    fn colour_attachment(&self) -> (&wgpu::TextureView, Option<&wgpu::TextureView>) {
        match &self.msaa_view {
            Some(msaa) => (msaa, Some(&self.resolve_view)),
            None => (&self.resolve_view, None),
        }
    }
}

/// A 2-D extent of `width_px` x `height_px`.
fn extent_px(width_px: u32, height_px: u32) -> wgpu::Extent3d {
    wgpu::Extent3d {
        width: width_px,
        height: height_px,
        depth_or_array_layers: 1,
    }
}

/// Copies the part of a window inside the image into the image.
fn copy_window(
    encoder: &mut wgpu::CommandEncoder,
    window: &wgpu::Texture,
    image: &wgpu::Texture,
    copy: &WindowCopy,
) {
    let at = |texture, [x, y]: [u32; 2]| wgpu::TexelCopyTextureInfo {
        texture,
        mip_level: 0,
        origin: wgpu::Origin3d { x, y, z: 0 },
        aspect: wgpu::TextureAspect::All,
    };
    encoder.copy_texture_to_texture(
        at(window, copy.from_px),
        at(image, copy.to_px),
        extent_px(copy.size_px[0], copy.size_px[1]),
    );
}

fn depth_state(write: bool, compare: wgpu::CompareFunction) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

/// Bytes per staging-buffer row: 4 bytes a pixel, rounded up to 256 (a wgpu copy rule).
fn padded_bytes_per_row(width_px: u32) -> u32 {
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    (4 * width_px).div_ceil(align) * align
}

/// Bytes of the staging buffer that hold `region`, its rows padded.
fn staging_bytes(region: &ImageRegion) -> u64 {
    u64::from(padded_bytes_per_row(region.width_px)) * u64::from(region.height_px)
}

/// The sky's colours at the top and at the bottom of the image (RGB, 0-255).
fn sky_top_bottom_rgb(sky: &Sky) -> ([u8; 3], [u8; 3]) {
    match *sky {
        Sky::Uniform { rgb } => (rgb, rgb),
        Sky::VerticalGradient {
            top_rgb,
            bottom_rgb,
        } => (top_rgb, bottom_rgb),
    }
}

/// The colour frames are cleared to: the sky's top colour.
fn clear_color(sky: &Sky) -> wgpu::Color {
    let (top_rgb, _) = sky_top_bottom_rgb(sky);
    wgpu::Color {
        r: f64::from(top_rgb[0]) / 255.0,
        g: f64::from(top_rgb[1]) / 255.0,
        b: f64::from(top_rgb[2]) / 255.0,
        a: 1.0,
    }
}

fn initial_uniforms(settings: &RenderSettings) -> FrameUniforms {
    let (top, bottom) = sky_top_bottom_rgb(&settings.background.sky);
    let light = settings.shading.light_dir_body.normalize();
    FrameUniforms {
        clip_from_target: [[0.0; 4]; 4],
        body_from_target: [[0.0; 4]; 3],
        light_dir_body: [light.x as f32, light.y as f32, light.z as f32, 0.0],
        target_grey: [
            f32::from(settings.shading.unlit_grey) / 255.0,
            f32::from(settings.shading.lit_grey) / 255.0,
            0.0,
            0.0,
        ],
        sky_top: unit_rgb(top),
        sky_bottom: unit_rgb(bottom),
        image: [settings.intrinsics.height_px as f32, 0.0, 0.0, 0.0],
    }
}

/// Three vertices per triangle, each carrying its face's unit normal (zero if degenerate).
fn flat_shaded_vertices(mesh: &TargetMesh) -> Result<Vec<TargetVertex>, RenderError> {
    if mesh.triangles.is_empty() {
        return Err(RenderError::InvalidMesh("no triangles".into()));
    }
    let mut out = Vec::with_capacity(3 * mesh.triangles.len());
    for (k, t) in mesh.triangles.iter().enumerate() {
        let corner = |i: u32| {
            mesh.vertices_ft.get(i as usize).copied().ok_or_else(|| {
                RenderError::InvalidMesh(format!(
                    "triangle {k} refers to vertex {i} of {}",
                    mesh.vertices_ft.len()
                ))
            })
        };
        let (a, b, c) = (corner(t[0])?, corner(t[1])?, corner(t[2])?);
        let n = (b - a).cross(&(c - a));
        let n = if n.norm() > 0.0 { n.normalize() } else { n };
        let normal_target = [n.x as f32, n.y as f32, n.z as f32];
        for p in [a, b, c] {
            out.push(TargetVertex {
                position_target_ft: [p.x as f32, p.y as f32, p.z as f32],
                normal_target,
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::Vec3;

    #[test]
    fn rows_are_padded_to_256_bytes() {
        assert_eq!(padded_bytes_per_row(64), 256);
        assert_eq!(padded_bytes_per_row(65), 512);
        assert_eq!(padded_bytes_per_row(160), 768);
        assert_eq!(padded_bytes_per_row(1920), 7680);
    }

    #[test]
    fn degenerate_mesh_is_rejected() {
        let mesh = TargetMesh {
            vertices_ft: vec![Vec3::zeros()],
            triangles: vec![[0, 0, 5]],
        };
        assert!(flat_shaded_vertices(&mesh).is_err());
        assert!(flat_shaded_vertices(&TargetMesh::default()).is_err());
    }
}
