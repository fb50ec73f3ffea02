//! The two render passes a frame is made of: the target with its sky into a framebuffer, and
//! the sky alone, one sample per pixel.

use wgpu::util::DeviceExt;

use crate::render::pipelines::Pipelines;
use crate::render::region::ImageRegion;
use crate::render::settings::{RenderSettings, Sky};
use crate::render::targets::RenderTargets;
use crate::render::uniforms::sky_top_bottom_rgb;
use crate::render::vertices::TargetVertex;

/// What the passes draw with: the pipelines, the target's vertices and the clear colour.
#[derive(Debug)]
pub(super) struct Passes {
    pipelines: Pipelines,
    vertex_buffer: wgpu::Buffer,
    vertex_count: u32,
    clear_color: wgpu::Color,
}

impl Passes {
    /// The pipelines of `settings` (of `shader`'s programs, binding `uniform_layout`) and the
    /// uploaded `vertices`.
    pub(super) fn new(
        device: &wgpu::Device,
        shader: &wgpu::ShaderModule,
        uniform_layout: &wgpu::BindGroupLayout,
        settings: &RenderSettings,
        vertices: &[TargetVertex],
    ) -> Self {
        let pipelines = Pipelines::new(device, shader, uniform_layout, settings);
        let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("target vertices"),
            contents: bytemuck::cast_slice(vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        Self {
            pipelines,
            vertex_buffer,
            vertex_count: vertices.len() as u32,
            clear_color: clear_color(&settings.background.sky),
        }
    }

    /// One pass: sky and target into `targets` (multisampled and resolved when they have
    /// multisampled colour), with the projection `uniforms` binds, and the same mesh once
    /// more for each of `others` (other aircraft's projections), the nearer surface of any
    /// two drawn (depth).
    pub(super) fn draw_target(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &RenderTargets,
        uniforms: &wgpu::BindGroup,
        others: &[&wgpu::BindGroup],
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
        pass.set_bind_group(0, uniforms, &[]);
        if let Some(background) = &self.pipelines.background {
            pass.set_pipeline(background);
            pass.draw(0..3, 0..1);
        }
        pass.set_pipeline(&self.pipelines.target);
        pass.set_vertex_buffer(0, self.vertex_buffer.slice(..));
        pass.draw(0..self.vertex_count, 0..1);
        for other in others {
            pass.set_bind_group(0, *other, &[]);
            pass.draw(0..self.vertex_count, 0..1);
        }
    }

    /// The sky alone, one sample per pixel, over the whole image of `view` or only over
    /// `region` of it (the rest of the image is left as it was), with the whole image's
    /// `uniforms`.
    pub(super) fn draw_sky(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        uniforms: &wgpu::BindGroup,
        region: Option<&ImageRegion>,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("sky"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: match region {
                        Some(_) => wgpu::LoadOp::Load,
                        None => wgpu::LoadOp::Clear(self.clear_color),
                    },
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some(sky) = &self.pipelines.one_sample_sky {
            if let Some(r) = region {
                pass.set_scissor_rect(r.u0_px, r.v0_px, r.width_px, r.height_px);
            }
            pass.set_bind_group(0, uniforms, &[]);
            pass.set_pipeline(sky);
            pass.draw(0..3, 0..1);
        }
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
