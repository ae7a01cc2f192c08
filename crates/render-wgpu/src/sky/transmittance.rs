//! The compute pass that builds the transmittance table T(r, mu) of
//! `shaders/sky/transmittance_table.wgsl` into an `Rgba32Float` texture: rgb = transmittance
//! at the uniform's three wavelengths, or the columns of matter per species (the
//! nishita model's g_l), a = 1. Its CPU twin is atmosphere-core's `transmittance_table.rs`.

use atmosphere_core::optics::transmittance_table::BRUNETON_TABLE_SIZE;

use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::texel_groups;
use crate::gpu::readback::read_texture;
use crate::gpu::shaders;

/// Texture format of the table.
pub const TABLE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

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
    pipeline: wgpu::ComputePipeline,
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
        let device = &gpu.device;
        let source = shaders::composed("sky/transmittance_table.wgsl")?;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("sky/transmittance_table.wgsl"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("transmittance table"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(
                            size_of::<AtmosphereUniform>() as u64
                        ),
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: TABLE_FORMAT,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("transmittance table"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("transmittance table"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some(match output {
                TableOutput::Transmittance => "main",
                TableOutput::Columns => "columns",
            }),
            compilation_options: Default::default(),
            cache: None,
        });
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("atmosphere"),
            size: size_of::<AtmosphereUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("transmittance table"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: TABLE_FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("transmittance table"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
            ],
        });
        if let Some(source) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation {
                what: "the transmittance pipeline",
                source,
            });
        }
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
        gpu.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(atmosphere));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("transmittance table"),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        let [x, y, z] = texel_groups(&self.texture);
        pass.dispatch_workgroups(x, y, z);
    }

    /// The table's texels, row-major (row = r, column = mu), waiting for the GPU.
    pub fn read_back(&self, gpu: &GpuContext) -> Result<Vec<[f32; 4]>, GpuError> {
        let bytes = read_texture(gpu, &self.texture, size_of::<[f32; 4]>() as u32)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}
