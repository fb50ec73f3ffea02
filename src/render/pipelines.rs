//! The render pipelines: the target, and the gradient sky or the world scene drawn with it or
//! alone.

use crate::render::settings::{RenderSettings, Sky};
use crate::render::targets::{COLOR_FORMAT, DEPTH_FORMAT};
use crate::render::vertices::TargetVertex;

/// The render pipelines.
#[derive(Debug)]
pub(super) struct Pipelines {
    /// The target, `msaa_samples` per pixel, with depth.
    pub(super) target: wgpu::RenderPipeline,
    /// The gradient sky or the world in the target's pass (none for a uniform sky: the clear
    /// colour is the sky).
    pub(super) background: Option<wgpu::RenderPipeline>,
    /// The one-sample sky of a frame whose target is drawn in a window (gradient sky or
    /// world only).
    pub(super) one_sample_sky: Option<wgpu::RenderPipeline>,
}

impl Pipelines {
    /// The pipelines `settings` need, of `shader`'s programs, binding `uniform_layout`.
    pub(super) fn new(
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
        let target = builder.create(
            "target",
            &[Some(TargetVertex::buffer_layout())],
            Some(depth_state(true, wgpu::CompareFunction::Greater)),
            samples,
        );
        let (needs_background_pass, program) = match settings.background.sky {
            Sky::Uniform { .. } => (false, "background"),
            Sky::VerticalGradient { .. } => (true, "background"),
            Sky::World(_) => (true, "scene"),
        };
        // The sky: `samples` per pixel when drawn with the target, one in the sky pass of a
        // windowed frame (no depth there).
        let sky = |sample_count: u32, depth: bool| {
            builder.create(
                program,
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

fn depth_state(write: bool, compare: wgpu::CompareFunction) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: Default::default(),
        bias: Default::default(),
    }
}
