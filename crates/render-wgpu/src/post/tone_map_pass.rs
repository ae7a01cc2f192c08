//! The tone-map pass (`shaders/post/tone_map.wgsl`): a full-screen triangle that reads the HDR
//! target and writes display pixels to any `Rgba8UnormSrgb` view, an off-screen texture
//! now and a window's surface later. Its CPU twin is [`crate::post::tone_map`].

use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::formats::LDR_FORMAT;
use crate::gpu::pipeline::{
    in_stage, one_group_layout, ordered_bind_group, shader_module, texture_entry, uniform_buffer,
    uniform_entry,
};
use crate::post::tone_map::ToneMapUniform;

/// Pipeline and uniform buffer, made once.
#[derive(Debug)]
pub struct ToneMapPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
}

impl ToneMapPass {
    pub fn new(gpu: &GpuContext) -> Result<ToneMapPass, GpuError> {
        let device = &gpu.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = shader_module(device, "post/tone_map.wgsl")?;
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let (layout, pipeline_layout) = one_group_layout(
            device,
            "tone map",
            &[
                in_stage(fragment, uniform_entry(0, size_of::<ToneMapUniform>())),
                in_stage(fragment, texture_entry(1, wgpu::TextureViewDimension::D2)),
            ],
        );
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("tone map"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vertex"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fragment"),
                compilation_options: Default::default(),
                targets: &[Some(LDR_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let params = uniform_buffer(device, "tone map", size_of::<ToneMapUniform>());
        if let Some(source) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation {
                what: "the tone-map pipeline",
                source,
            });
        }
        Ok(ToneMapPass {
            pipeline,
            layout,
            params,
        })
    }

    /// Uploads the uniform and records the pass from `hdr` to `target` (a view of
    /// [`LDR_FORMAT`] of the same size), with `timestamps` around it when given.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        params: &ToneMapUniform,
        hdr: &wgpu::Texture,
        target: &wgpu::TextureView,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        gpu.write_uniform(&self.params, params);
        let hdr_view = hdr.create_view(&Default::default());
        let bind_group = ordered_bind_group(
            &gpu.device,
            Some("tone map"),
            &self.layout,
            &[
                self.params.as_entire_binding(),
                wgpu::BindingResource::TextureView(&hdr_view),
            ],
        );
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("tone map"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: timestamps,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}
