//! The per-pixel pass of the nishita model (`shaders/nishita.wgsl`): a compute shader
//! that writes spectral radiance at the three wavelengths into the HDR target, from the
//! g_l table (the `columns` of the transmittance pass). Its CPU twin is atmosphere-core's
//! `nishita.rs`.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::model::ModelSettings;
use atmosphere_core::nishita::NishitaSettings;
use atmosphere_core::phase::PhaseFunction;
use atmosphere_core::sun_disk;
use bytemuck::{Pod, Zeroable};

use crate::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::device::GpuContext;
use crate::error::{GpuError, RenderError};
use crate::frame_uniform::FrameUniform;
use crate::shader_source;

/// Format of the HDR target: spectral radiance (W m^-2 sr^-1 nm^-1) at 680, 550 and
/// 440 nm in rgb, a = 1.
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Side of the shader's square workgroup.
const WORKGROUP_SIDE: u32 = 8;

/// WGSL `NishitaParams`, 96 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct NishitaUniform {
    pub rayleigh_scattering_per_m: [f32; 4],
    pub mie_scattering_per_m: [f32; 4],
    pub solar_irradiance: [f32; 4],
    pub sun_centre_radiance: [f32; 4],
    pub sun_limb_exponent: [f32; 4],
    pub view_samples: u32,
    pub mie_phase_kind: u32,
    pub mie_g: f32,
    pub ground_albedo: f32,
}

impl NishitaUniform {
    /// The model's coefficients at the RGB wavelengths; fails for settings the GPU does
    /// not follow (other wavelengths) and for a tabulated Mie phase function.
    pub fn new(
        atmosphere: &Atmosphere,
        model_settings: &ModelSettings,
        settings: &NishitaSettings,
    ) -> Result<NishitaUniform, RenderError> {
        if model_settings.wavelengths_nm != RGB_WAVELENGTHS_NM {
            return Err(RenderError::Unsupported(format!(
                "the GPU renders at {RGB_WAVELENGTHS_NM:?} nm, not {:?}",
                model_settings.wavelengths_nm
            )));
        }
        let (mie_phase_kind, mie_g) = match atmosphere.mie.phase {
            PhaseFunction::CornetteShanks { g } => (0, g),
            PhaseFunction::HenyeyGreenstein { g } => (1, g),
            PhaseFunction::NishitaHazy => (2, 0.0),
            PhaseFunction::Rayleigh | PhaseFunction::Tabulated { .. } => {
                return Err(RenderError::Unsupported(format!(
                    "Mie phase function {:?} is not yet on the GPU",
                    atmosphere.mie.phase
                )));
            }
        };
        let coefficients = RGB_WAVELENGTHS_NM.map(|l| atmosphere.coefficients(l));
        let row = |f: &dyn Fn(usize) -> f64| [f(0) as f32, f(1) as f32, f(2) as f32, 0.0];
        let sun = &atmosphere.sun;
        Ok(NishitaUniform {
            rayleigh_scattering_per_m: row(&|w| coefficients[w].rayleigh_scattering_per_m),
            mie_scattering_per_m: row(&|w| coefficients[w].mie_scattering_per_m),
            solar_irradiance: row(&|w| coefficients[w].solar_irradiance_w_m2_nm),
            sun_centre_radiance: row(&|w| {
                sun_disk::centre_radiance(
                    coefficients[w].solar_irradiance_w_m2_nm,
                    sun.angular_radius_rad,
                    RGB_WAVELENGTHS_NM[w],
                )
            }),
            sun_limb_exponent: row(&|w| sun_disk::limb_darkening_exponent(RGB_WAVELENGTHS_NM[w])),
            view_samples: u32::try_from(settings.view_samples).map_err(|_| {
                RenderError::Unsupported(format!("{} view samples", settings.view_samples))
            })?,
            mie_phase_kind,
            mie_g: mie_g as f32,
            ground_albedo: atmosphere.ground_albedo as f32,
        })
    }
}

/// What one nishita frame reads and writes.
#[derive(Debug)]
pub struct NishitaInputs<'a> {
    /// The uniform buffer of `AtmosphereUniform`.
    pub atmosphere: &'a wgpu::Buffer,
    pub frame: &'a FrameUniform,
    pub params: &'a NishitaUniform,
    /// The g_l table (columns of the transmittance pass).
    pub table: &'a wgpu::Texture,
    /// The target, of [`HDR_FORMAT`].
    pub hdr: &'a wgpu::Texture,
}

/// Pipeline and uniform buffers, made once.
#[derive(Debug)]
pub struct NishitaPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    frame: wgpu::Buffer,
    params: wgpu::Buffer,
}

fn uniform_entry(binding: u32, size: usize) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: wgpu::BufferSize::new(size as u64),
        },
        count: None,
    }
}

fn uniform_buffer(device: &wgpu::Device, label: &str, size: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

impl NishitaPass {
    pub fn new(gpu: &GpuContext) -> Result<NishitaPass, GpuError> {
        let device = &gpu.device;
        let source = shader_source::composed("nishita.wgsl")?;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("nishita.wgsl"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("nishita"),
            entries: &[
                uniform_entry(0, size_of::<AtmosphereUniform>()),
                uniform_entry(1, size_of::<FrameUniform>()),
                uniform_entry(2, size_of::<NishitaUniform>()),
                wgpu::BindGroupLayoutEntry {
                    binding: 3,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 4,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: HDR_FORMAT,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("nishita"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("nishita"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let frame = uniform_buffer(device, "frame", size_of::<FrameUniform>());
        let params = uniform_buffer(device, "nishita", size_of::<NishitaUniform>());
        if let Some(source) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation {
                what: "the nishita pipeline",
                source,
            });
        }
        Ok(NishitaPass {
            pipeline,
            layout,
            frame,
            params,
        })
    }

    /// Uploads the uniforms and records the pass that fills the HDR target from the g_l
    /// table, with `timestamps` around it when given.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        inputs: &NishitaInputs<'_>,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let NishitaInputs {
            atmosphere,
            frame,
            params,
            table,
            hdr,
        } = *inputs;
        gpu.queue
            .write_buffer(&self.frame, 0, bytemuck::bytes_of(frame));
        gpu.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(params));
        let table_view = table.create_view(&Default::default());
        let hdr_view = hdr.create_view(&Default::default());
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("nishita"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: atmosphere.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.frame.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: self.params.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&table_view),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::TextureView(&hdr_view),
                },
            ],
        });
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("nishita"),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(
            hdr.width().div_ceil(WORKGROUP_SIDE),
            hdr.height().div_ceil(WORKGROUP_SIDE),
            1,
        );
    }
}
