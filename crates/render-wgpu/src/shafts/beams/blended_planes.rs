//! What the passes that draw planes share (Dobashi, Yamamoto and Nishita 2000 section
//! 5; Dobashi et al. 2002 section 4): a render pipeline whose fragments add into the
//! `Rgba32Float` radiance image (blending), with the scene's bindings as group 0 and
//! the method's own as group 1, and the render pass that draws into the image.

use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{in_stage, shader_module};
use crate::shafts::beams::image::RADIANCE_FORMAT;
use crate::shafts::beams::scene_buffers::scene_entries;

/// A render pipeline of additive planes and its two bind group layouts.
#[derive(Debug)]
pub struct BlendedPlanes {
    pub pipeline: wgpu::RenderPipeline,
    pub scene_layout: wgpu::BindGroupLayout,
    pub own_layout: wgpu::BindGroupLayout,
}

impl BlendedPlanes {
    /// The pipeline of entry points `vertex` and `fragment` of `shader`, group 1 laid
    /// out by `own_entries`, vertices from `buffers`; an error where the device cannot
    /// blend `Rgba32Float` targets.
    pub fn new(
        gpu: &GpuContext,
        shader: &str,
        label: &'static str,
        own_entries: &[wgpu::BindGroupLayoutEntry],
        buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
    ) -> Result<BlendedPlanes, RenderError> {
        Self::with_depth(gpu, shader, label, own_entries, buffers, None)
    }

    /// [`BlendedPlanes::new`] with a depth test and its writes.
    pub fn with_depth(
        gpu: &GpuContext,
        shader: &str,
        label: &'static str,
        own_entries: &[wgpu::BindGroupLayoutEntry],
        buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
        depth: Option<wgpu::DepthStencilState>,
    ) -> Result<BlendedPlanes, RenderError> {
        let device = &gpu.device;
        if !device
            .features()
            .contains(wgpu::Features::FLOAT32_BLENDABLE)
        {
            return Err(RenderError::Unsupported(format!(
                "{label} sums its planes by blending into an Rgba32Float image; this device \
                 lacks FLOAT32_BLENDABLE (use --model march)"
            )));
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let stages = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let scene_entries: Vec<_> = scene_entries()
            .into_iter()
            .map(|e| in_stage(stages, e))
            .collect();
        let scene_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &scene_entries,
        });
        let own_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: own_entries,
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&scene_layout), Some(&own_layout)],
            immediate_size: 0,
        });
        let module = shader_module(device, shader)?;
        let stages = PipelineStages {
            module: &module,
            vertex: "vertex",
            fragment: "fragment",
            buffers,
            depth,
        };
        let pipeline = additive_pipeline(device, label, &layout, &stages);
        if let Some(source) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation {
                what: label,
                source,
            }
            .into());
        }
        Ok(BlendedPlanes {
            pipeline,
            scene_layout,
            own_layout,
        })
    }
}

/// What a pipeline of additive planes runs: entry points `vertex` and `fragment` of
/// `module`, its vertices from `buffers`, its depth test.
#[derive(Debug)]
pub struct PipelineStages<'a> {
    pub module: &'a wgpu::ShaderModule,
    pub vertex: &'a str,
    pub fragment: &'a str,
    pub buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    pub depth: Option<wgpu::DepthStencilState>,
}

/// A render pipeline of `stages` laid out by `layout` adding its fragments into the
/// `Rgba32Float` radiance image.
pub fn additive_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::PipelineLayout,
    stages: &PipelineStages<'_>,
) -> wgpu::RenderPipeline {
    let add = wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    };
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module: stages.module,
            entry_point: Some(stages.vertex),
            compilation_options: Default::default(),
            buffers: stages.buffers,
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: stages.depth.clone(),
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: stages.module,
            entry_point: Some(stages.fragment),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: RADIANCE_FORMAT,
                blend: Some(wgpu::BlendState {
                    color: add,
                    alpha: add,
                }),
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// A render pass into `target`, cleared to black (alpha 1), and into `depth` (cleared to
/// 0) where given, timed by `timestamps`.
pub fn begin_planes_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    depth: Option<&wgpu::TextureView>,
    timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color {
                    r: 0.0,
                    g: 0.0,
                    b: 0.0,
                    a: 1.0,
                }),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: depth.map(|view| wgpu::RenderPassDepthStencilAttachment {
            view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(0.0),
                store: wgpu::StoreOp::Discard,
            }),
            stencil_ops: None,
        }),
        timestamp_writes: timestamps,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}
