//! The per-frame uniforms: the block the shaders read and the buffer that holds it twice, once
//! with the whole image's projection and once with the target window's; one such buffer
//! for the target and one for each other aircraft drawn with it.
//!
//! Per frame only this 192-byte block changes; the mesh is uploaded once.

use bytemuck::{Pod, Zeroable};
use nalgebra::Matrix4;

use crate::render::camera::{AircraftPose, TargetPoseInCamera};
use crate::render::projection::{
    PixelWindow, body_from_target, clip_from_body, clip_from_body_in_window,
};
use crate::render::scene::{CameraInWorld, WorldScene, cloud_threshold};
use crate::render::settings::{RenderSettings, Sky};

/// The per-frame uniform block; layout matches `FrameUniforms` in `shaders/target.wgsl`
/// (mat3x3 columns padded to vec4, total 352 bytes).
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
    ned_from_camera: [[f32; 4]; 3],
    camera_ned_ft: [f32; 4],
    optics: [f32; 4],
    ground: [f32; 4],
    clouds: [f32; 4],
    sun: [f32; 4],
    haze: [f32; 4],
    flags: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<FrameUniforms>() == 352);

/// A uniform buffer of two slots, the whole image's projection and the target window's, and
/// a bind group for each.
#[derive(Debug)]
struct SlotPair {
    buffer: wgpu::Buffer,
    /// Binds the first slot: the whole image's projection.
    whole: wgpu::BindGroup,
    /// Binds the second slot: the target window's projection.
    window: wgpu::BindGroup,
    /// Byte offset of the second slot.
    window_offset: u64,
}

impl SlotPair {
    /// The buffer, its second slot at the first multiple of `min_offset_alignment` after the
    /// first, and the slots' bind groups of `layout`.
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

    fn bind_group(&self, in_window: bool) -> &wgpu::BindGroup {
        if in_window { &self.window } else { &self.whole }
    }
}

/// The uniform slots: the target's pair (the whole image's projection and the target
/// window's), a pair for each other aircraft drawn with it (made when first needed), and
/// the block last written to the target's first slot.
#[derive(Debug)]
pub(super) struct UniformSlots {
    target: SlotPair,
    /// One pair per other aircraft drawn in the last frame, or earlier ones.
    others: Vec<SlotPair>,
    /// What the pairs are made with.
    layout: wgpu::BindGroupLayout,
    min_offset_alignment: u32,
    /// The target's first slot's block (the second is this one with the window's projection).
    uniforms: FrameUniforms,
    /// The whole image's projection of camera/body points.
    clip_from_body: Matrix4<f64>,
    /// The world scene, when the sky is one (its sun lights the target).
    world: Option<WorldScene>,
}

impl UniformSlots {
    /// The target's pair, its first slot written with the block of `settings` (no target
    /// pose yet).
    pub(super) fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layout: &wgpu::BindGroupLayout,
        min_offset_alignment: u32,
        settings: &RenderSettings,
    ) -> Self {
        let slots = Self {
            target: SlotPair::new(device, layout, min_offset_alignment),
            others: Vec::new(),
            layout: layout.clone(),
            min_offset_alignment,
            uniforms: initial_uniforms(settings),
            clip_from_body: clip_from_body(&settings.intrinsics),
            world: match settings.background.sky {
                Sky::World(world) => Some(world),
                _ => None,
            },
        };
        queue.write_buffer(&slots.target.buffer, 0, bytemuck::bytes_of(&slots.uniforms));
        slots
    }

    /// The bind group of the whole image's projection or, `in_window`, of the window's.
    pub(super) fn bind_group(&self, in_window: bool) -> &wgpu::BindGroup {
        self.target.bind_group(in_window)
    }

    /// The bind groups of the first `count` other aircraft (see [`Self::write_others`]).
    pub(super) fn other_bind_groups(&self, count: usize, in_window: bool) -> Vec<&wgpu::BindGroup> {
        self.others[..count]
            .iter()
            .map(|pair| pair.bind_group(in_window))
            .collect()
    }

    /// Writes the first slot (the whole image's projection of the target at `pose`, and the
    /// world seen from `camera` when the sky is a world) and returns the target-to-body
    /// transform.
    pub(super) fn write_image(
        &mut self,
        queue: &wgpu::Queue,
        pose: &TargetPoseInCamera,
        camera: &CameraInWorld,
    ) -> Matrix4<f64> {
        if let Some(world) = &self.world {
            let r = &camera.ned_from_camera;
            self.uniforms.ned_from_camera = columns3_f32(r);
            let p = camera.position_ned_ft;
            self.uniforms.camera_ned_ft = [p.x as f32, p.y as f32, p.z as f32, 0.0];
            let light = r.transpose() * world.sun.towards_ned.normalize();
            self.uniforms.light_dir_body = [light.x as f32, light.y as f32, light.z as f32, 0.0];
        }
        let target_to_body = body_from_target(pose);
        let clip_from_target = self.clip_from_body * target_to_body;
        self.uniforms.clip_from_target = columns_f32(&clip_from_target);
        self.uniforms.body_from_target = columns3_f32(&pose.body_from_target);
        queue.write_buffer(&self.target.buffer, 0, bytemuck::bytes_of(&self.uniforms));
        target_to_body
    }

    /// Writes the second slot: the first with the projection of `settings`' camera into
    /// `window`.
    pub(super) fn write_window(
        &self,
        queue: &wgpu::Queue,
        settings: &RenderSettings,
        window: &PixelWindow,
        target_to_body: &Matrix4<f64>,
    ) {
        write_in_window(
            queue,
            &self.target,
            self.uniforms,
            settings,
            window,
            target_to_body,
        );
    }

    /// Writes the pairs of the other aircraft drawn with the target (after
    /// [`Self::write_image`], whose world and light they share): each the target's block
    /// with the aircraft's pose and scale, in the whole image and, when the frame has one,
    /// in `window`.
    pub(super) fn write_others(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        others: &[AircraftPose],
        window: Option<(&RenderSettings, &PixelWindow)>,
    ) {
        while self.others.len() < others.len() {
            let pair = SlotPair::new(device, &self.layout, self.min_offset_alignment);
            self.others.push(pair);
        }
        for (other, pair) in others.iter().zip(&self.others) {
            let to_body = body_from_target(&other.pose) * Matrix4::new_scaling(other.scale);
            let mut block = self.uniforms;
            block.clip_from_target = columns_f32(&(self.clip_from_body * to_body));
            block.body_from_target = columns3_f32(&other.pose.body_from_target);
            queue.write_buffer(&pair.buffer, 0, bytemuck::bytes_of(&block));
            if let Some((settings, window)) = window {
                write_in_window(queue, pair, block, settings, window, &to_body);
            }
        }
    }
}

/// Writes the second slot of `pair`: `block` with the projection of `settings`' camera
/// into `window` of the points `to_body` takes to camera/body axes.
fn write_in_window(
    queue: &wgpu::Queue,
    pair: &SlotPair,
    block: FrameUniforms,
    settings: &RenderSettings,
    window: &PixelWindow,
    to_body: &Matrix4<f64>,
) {
    let mut in_window = block;
    in_window.clip_from_target =
        columns_f32(&(clip_from_body_in_window(&settings.intrinsics, window) * to_body));
    in_window.image[1] = window.v0_px as f32;
    in_window.image[2] = window.u0_px as f32;
    queue.write_buffer(
        &pair.buffer,
        pair.window_offset,
        bytemuck::bytes_of(&in_window),
    );
}

/// The layout of one uniform slot: a [`FrameUniforms`] at binding 0, seen by both stages.
pub(super) fn uniform_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
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

/// The sky's colours at the top and at the bottom of the image (RGB, 0-255).
pub(super) fn sky_top_bottom_rgb(sky: &Sky) -> ([u8; 3], [u8; 3]) {
    match *sky {
        Sky::Uniform { rgb } => (rgb, rgb),
        Sky::VerticalGradient {
            top_rgb,
            bottom_rgb,
        } => (top_rgb, bottom_rgb),
        Sky::World(world) => (world.zenith_rgb, world.horizon_rgb),
    }
}

/// A rotation's columns, each padded to 4 floats (a WGSL mat3x3).
fn columns3_f32(r: &crate::frames::Mat3) -> [[f32; 4]; 3] {
    std::array::from_fn(|c| [r[(0, c)] as f32, r[(1, c)] as f32, r[(2, c)] as f32, 0.0])
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
        ned_from_camera: columns3_f32(&crate::frames::Mat3::identity()),
        camera_ned_ft: [0.0; 4],
        optics: [
            settings.intrinsics.cx() as f32,
            settings.intrinsics.cy() as f32,
            settings.intrinsics.focal_px as f32,
            0.0,
        ],
        ..world_uniforms(&settings.background.sky)
    }
}

/// The blocks' world-scene fields (zero, and off, without a world).
fn world_uniforms(sky: &Sky) -> FrameUniforms {
    let mut uniforms = FrameUniforms::zeroed();
    let Sky::World(world) = sky else {
        return uniforms;
    };
    if let Some(g) = &world.ground {
        let road_period_ft = g.field_ft * f64::from(g.road_every_fields);
        uniforms.ground =
            [g.down_ft, g.field_ft, road_period_ft, g.road_width_ft].map(|x| x as f32);
    }
    if let Some(c) = &world.clouds {
        let threshold = cloud_threshold(c.coverage, world.seed);
        uniforms.clouds = [c.down_ft as f32, c.cell_ft as f32, threshold, 0.0];
    }
    let s = world.sun.towards_ned.normalize();
    uniforms.sun = [s.x, s.y, s.z, world.sun.glare].map(|x| x as f32);
    uniforms.haze = [world.visibility_ft as f32, 0.0, 0.0, 0.0];
    uniforms.flags = [
        1,
        u32::from(world.ground.is_some()),
        u32::from(world.clouds.is_some()),
        world.seed,
    ];
    uniforms
}
