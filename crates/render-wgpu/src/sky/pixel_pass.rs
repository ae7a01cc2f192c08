//! A model's per-pixel pass: the compute shader that writes every pixel's spectral
//! radiance into the HDR target. Every model's pass has the same layout: the atmosphere
//! at binding 0 (`common/atmosphere_params.wgsl`), the frame at 1
//! (`common/frame_params.wgsl`), the model's parameters at 2, the model's tables (and
//! other inputs) from 3 on, the HDR target after them, the table sampler at its binding
//! where tables are sampled (`common/table_sampling.wgsl`), and the frame's surface at 30
//! and 31 (`common/surface.wgsl`) with the clouds' sun map at 32 and 33
//! (`clouds/sun_map_read.wgsl`). Each pass compiles in the two variants of a
//! [`PixelPipeline`], with and without a surface.

use crate::clouds::sun_map_texture::SunMapTexture;
use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::surface_buffer::{ALBEDO_BINDING, GEOMETRY_BINDING, SurfaceBuffer};
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{PixelPipeline, storage_texture_entry, texel_groups, uniform_entry};
use crate::sky::model_pass::StepContext;
use crate::sky::table_sampling::TableSampling;

/// The entry point of a model's pass and what it binds besides the frame's; see the
/// module documentation.
#[derive(Clone, Copy, Debug)]
pub struct PixelShader<'a> {
    /// The embedded shader (`sky/nishita/pixel.wgsl`) and its entry point.
    pub path: &'a str,
    pub entry: &'a str,
    /// Names the pass in errors and GPU captures.
    pub label: &'static str,
    /// Bytes of the model's parameters at binding 2.
    pub params_size: usize,
    /// The layout entries of the model's tables, at bindings 3 and on.
    pub tables: &'a [wgpu::BindGroupLayoutEntry],
    /// How the tables are read, where any is sampled.
    pub sampling: Option<&'a TableSampling>,
}

/// A model's per-pixel pass, compiled; see the module documentation.
#[derive(Debug)]
pub struct PixelPass {
    pipeline: PixelPipeline,
    label: &'static str,
    sampling: Option<TableSampling>,
}

impl PixelPass {
    /// Compiles both variants of `shader`.
    pub fn new(gpu: &GpuContext, shader: PixelShader<'_>) -> Result<PixelPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let hdr_binding = 3 + shader.tables.len() as u32;
        let mut entries = vec![
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            uniform_entry(2, shader.params_size),
        ];
        entries.extend_from_slice(shader.tables);
        entries.push(storage_texture_entry(hdr_binding, HDR_FORMAT, D2));
        entries.extend(SurfaceBuffer::layout_entries());
        entries.extend(SunMapTexture::layout_entries());
        let mut constants = Vec::new();
        if let Some(sampling) = shader.sampling {
            entries.push(sampling.sampler_entry());
            constants.push(sampling.constant());
        }
        let pipeline = PixelPipeline::with_constants(
            gpu,
            shader.path,
            shader.entry,
            shader.label,
            &entries,
            &constants,
        )?;
        Ok(PixelPass {
            pipeline,
            label: shader.label,
            sampling: shader.sampling.cloned(),
        })
    }

    /// Records into `cx` the pass over every pixel of its HDR target, with `params` at
    /// binding 2 and `tables` from binding 3 on.
    pub fn encode(
        &self,
        cx: StepContext<'_>,
        params: &wgpu::Buffer,
        tables: &[wgpu::BindingResource<'_>],
    ) {
        let io = cx.io;
        let hdr = io.hdr.create_view(&Default::default());
        let [geometry, albedo] = io.surface;
        let mut resources: Vec<(u32, wgpu::BindingResource<'_>)> = (0..)
            .zip(
                [
                    io.atmosphere.as_entire_binding(),
                    io.frame.as_entire_binding(),
                    params.as_entire_binding(),
                ]
                .into_iter()
                .chain(tables.iter().cloned())
                .chain([wgpu::BindingResource::TextureView(&hdr)]),
            )
            .collect();
        resources.push((
            GEOMETRY_BINDING,
            wgpu::BindingResource::TextureView(geometry),
        ));
        resources.push((ALBEDO_BINDING, wgpu::BindingResource::TextureView(albedo)));
        resources.extend(io.sun_map.bindings());
        if let Some(sampling) = &self.sampling {
            resources.push(sampling.sampler_binding());
        }
        let pipeline = self.pipeline.variant(io.has_surface, io.has_sea);
        let bind_group = pipeline.bind_group_numbered(cx.gpu, &resources);
        let groups = texel_groups(io.hdr);
        pipeline.dispatch(cx.encoder, self.label, &bind_group, groups, cx.timestamps);
    }
}
