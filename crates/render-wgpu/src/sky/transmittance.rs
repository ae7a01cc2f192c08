//! The compute pass that builds the transmittance table T(r, mu) of
//! `shaders/sky/transmittance_table.wgsl` into an `Rgba32Float` texture: rgb =
//! transmittance at the uniform's three wavelengths, or the columns of matter per species
//! (the nishita model's g_l), a = 1. Its CPU twin is atmosphere-core's
//! `transmittance_table.rs`.

use atmosphere_core::optics::transmittance_table::BRUNETON_TABLE_SIZE;

use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::{
    ComputePipeline, storage_texture_entry, texel_groups, texture_2d, uniform_buffer, uniform_entry,
};
use crate::gpu::readback::read_texture;

/// Texture format of the table.
pub const TABLE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// A 2D table of [`TABLE_FORMAT`], `width` x `height` texels, that a compute pass writes,
/// later passes read, and tests copy back.
pub fn table_texture(gpu: &GpuContext, label: &str, (width, height): (u32, u32)) -> wgpu::Texture {
    let usage = wgpu::TextureUsages::STORAGE_BINDING
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC;
    texture_2d(&gpu.device, label, (width, height), TABLE_FORMAT, usage)
}

/// What the table's texels hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TableOutput {
    /// Transmittance at the three wavelengths of the uniform (entry point `main`).
    Transmittance,
    /// Columns of matter (Rayleigh, Mie, ozone), m (entry point `columns`).
    Columns,
}

/// Pipeline, uniform buffer and table texture, made once; [`TransmittancePass::run`]
/// rebuilds the table for an atmosphere.
#[derive(Debug)]
pub struct TransmittancePass {
    pipeline: ComputePipeline,
    uniform: wgpu::Buffer,
    texture: wgpu::Texture,
    bind_group: wgpu::BindGroup,
}

impl TransmittancePass {
    /// The pipeline and a transmittance table of `BRUNETON_TABLE_SIZE` (256 x 64).
    pub fn new(gpu: &GpuContext) -> Result<TransmittancePass, GpuError> {
        let (width, height) = BRUNETON_TABLE_SIZE;
        Self::with(gpu, TableOutput::Transmittance, width as u32, height as u32)
    }

    /// The pipeline and a table of `output` with `width` sun angles (mu) and `height`
    /// radii, each at least 2.
    pub fn with(
        gpu: &GpuContext,
        output: TableOutput,
        width: u32,
        height: u32,
    ) -> Result<TransmittancePass, GpuError> {
        let entry = match output {
            TableOutput::Transmittance => "main",
            TableOutput::Columns => "columns",
        };
        let pipeline = ComputePipeline::new(
            gpu,
            "sky/transmittance_table.wgsl",
            entry,
            "the transmittance pipeline",
            &[
                uniform_entry(0, size_of::<AtmosphereUniform>()),
                storage_texture_entry(1, TABLE_FORMAT, wgpu::TextureViewDimension::D2),
            ],
        )?;
        let uniform = uniform_buffer(&gpu.device, "atmosphere", size_of::<AtmosphereUniform>());
        let texture = table_texture(gpu, "transmittance table", (width, height));
        let view = texture.create_view(&Default::default());
        let bind_group = pipeline.bind_group(
            gpu,
            &[
                uniform.as_entire_binding(),
                wgpu::BindingResource::TextureView(&view),
            ],
        );
        Ok(TransmittancePass {
            pipeline,
            uniform,
            texture,
            bind_group,
        })
    }

    /// The table texture, for later passes to sample.
    pub fn texture(&self) -> &wgpu::Texture {
        &self.texture
    }

    /// Uploads `atmosphere` and submits the dispatch that fills the table.
    pub fn run(&self, gpu: &GpuContext, atmosphere: &AtmosphereUniform) {
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.encode(gpu, atmosphere, &mut encoder, None);
        gpu.queue.submit([encoder.finish()]);
    }

    /// Uploads `atmosphere` and records the dispatch into `encoder`, with `timestamps`
    /// written around it when given.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        atmosphere: &AtmosphereUniform,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        gpu.write_uniform(&self.uniform, atmosphere);
        let groups = texel_groups(&self.texture);
        self.pipeline.dispatch(
            encoder,
            "transmittance table",
            &self.bind_group,
            groups,
            timestamps,
        );
    }

    /// The table's texels, row-major (row = r, column = mu), waiting for the GPU.
    pub fn read_back(&self, gpu: &GpuContext) -> Result<Vec<[f32; 4]>, GpuError> {
        let bytes = read_texture(gpu, &self.texture, size_of::<[f32; 4]>() as u32)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}
