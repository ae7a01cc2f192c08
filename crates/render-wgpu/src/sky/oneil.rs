//! The oneil model on the GPU: the 4-channel optical-depth table of O'Neil 2004 built by
//! `shaders/sky/oneil/optical_depth_table.wgsl` (its CPU twin `OpticalDepthTable::build`),
//! rebuilt only when the density profiles, the geometry or the table's settings change,
//! and the per-pixel pass of `shaders/sky/oneil/pixel.wgsl` (`Oneil::radiance`).

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::oneil::{OneilSettings, OpticalDepthTable};
use bytemuck::{Pod, Zeroable};

use crate::frame::atmosphere_uniform::{AtmosphereUniform, check_wavelengths};
use crate::frame::plan::StepKind;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    ComputePipeline, storage_texture_entry, texel_groups, texture_entry, uniform_buffer,
    uniform_entry,
};
use crate::gpu::readback::read_texture;
use crate::shafts::terrain::uniform::ShadowMapUniform;
use crate::sky::model_pass::{ModelPass, StepContext};
use crate::sky::pixel_pass::{PixelPass, PixelShader};
use crate::sky::steps::{PassStep, SkyPlan};
use crate::sky::table_limits::table_extent;
use crate::sky::table_sampling::TableSampling;
use crate::sky::transmittance::{TABLE_FORMAT, table_texture};

/// WGSL `OneilParams` (the per-pixel pass), 16 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct OneilUniform {
    pub samples: u32,
    pub pad0: u32,
    pub pad1: u32,
    pub pad2: u32,
}

/// WGSL `OneilTableParams` (the table build), 16 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct OneilTableUniform {
    pub ray_samples: u32,
    pub pad0: u32,
    pub pad1: u32,
    pub pad2: u32,
}

/// A count the shaders loop over, as u32.
fn count(what: &str, n: usize) -> Result<u32, RenderError> {
    u32::try_from(n).map_err(|_| RenderError::Unsupported(format!("oneil: {n} {what}")))
}

/// The optical-depth table on the GPU: `Rgba32Float`, `heights` x `angles` texels, texel
/// (i, j) = node (i, j) of the CPU's table, channels in the CPU's order.
#[derive(Debug)]
pub struct OneilTablePass {
    pipeline: ComputePipeline,
    params: wgpu::Buffer,
    texture: wgpu::Texture,
}

impl OneilTablePass {
    /// The pipeline and an unbuilt table of `heights` x `angles` nodes (each at least 2).
    pub fn new(gpu: &GpuContext, heights: u32, angles: u32) -> Result<OneilTablePass, GpuError> {
        let pipeline = ComputePipeline::new(
            gpu,
            "sky/oneil/optical_depth_table.wgsl",
            "main",
            "the oneil optical-depth table",
            &[
                uniform_entry(0, size_of::<AtmosphereUniform>()),
                uniform_entry(1, size_of::<OneilTableUniform>()),
                storage_texture_entry(2, TABLE_FORMAT, wgpu::TextureViewDimension::D2),
            ],
        )?;
        let texture = table_texture(gpu, "oneil optical depth", (heights, angles));
        Ok(OneilTablePass {
            pipeline,
            params: uniform_buffer(&gpu.device, "oneil table", size_of::<OneilTableUniform>()),
            texture,
        })
    }

    /// The table texture.
    pub fn texture(&self) -> &wgpu::Texture {
        &self.texture
    }

    /// (heights, angles).
    pub fn size(&self) -> (u32, u32) {
        (self.texture.width(), self.texture.height())
    }

    /// Records the build from the `AtmosphereUniform` in `atmosphere`, each node's
    /// columns by the midpoint rule with `ray_samples` samples.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        atmosphere: &wgpu::Buffer,
        ray_samples: u32,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let params = OneilTableUniform {
            ray_samples,
            ..Default::default()
        };
        gpu.write_uniform(&self.params, &params);
        let view = self.texture.create_view(&Default::default());
        let bind_group = self.pipeline.bind_group(
            gpu,
            &[
                atmosphere.as_entire_binding(),
                self.params.as_entire_binding(),
                wgpu::BindingResource::TextureView(&view),
            ],
        );
        let groups = texel_groups(&self.texture);
        self.pipeline
            .dispatch(encoder, "oneil table", &bind_group, groups, timestamps);
    }

    /// The nodes, row-major: node (i, j) at `j * heights + i`, as the CPU stores them.
    pub fn read_back(&self, gpu: &GpuContext) -> Result<Vec<[f32; 4]>, GpuError> {
        let bytes = read_texture(gpu, &self.texture, size_of::<[f32; 4]>() as u32)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}

/// The model's steps: the optical-depth table and the pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OneilStep {
    OpticalDepth,
    Pass,
}

impl PassStep for OneilStep {
    fn name(self) -> &'static str {
        match self {
            OneilStep::OpticalDepth => "optical_depth",
            OneilStep::Pass => "oneil",
        }
    }

    fn kind(self) -> StepKind {
        match self {
            OneilStep::OpticalDepth => StepKind::TableBuild,
            OneilStep::Pass => StepKind::Pass,
        }
    }
}

/// What the table was built from: the atmosphere and the samples per node's ray.
type TableKey = (Atmosphere, usize);

/// The table, what it was built from and what the planned build is for.
#[derive(Debug)]
struct Table {
    pass: OneilTablePass,
    built_from: Option<TableKey>,
    pending: Option<TableKey>,
}

impl Table {
    /// An unbuilt table of the sizes of `settings`; an error names a size the shaders
    /// cannot index.
    fn new(gpu: &GpuContext, settings: &OneilSettings) -> Result<Table, RenderError> {
        let (heights, angles) = table_size(settings)?;
        let size = (settings.table_heights, settings.table_angles, 1);
        let sides = "table_heights x table_angles";
        let d2 = wgpu::TextureDimension::D2;
        table_extent(gpu, "oneil optical depth", sides, d2, size)?;
        Ok(Table {
            pass: OneilTablePass::new(gpu, heights, angles)?,
            built_from: None,
            pending: None,
        })
    }
}

/// The table's (heights, angles) for `settings`.
fn table_size(settings: &OneilSettings) -> Result<(u32, u32), RenderError> {
    Ok((
        count("table_heights", settings.table_heights)?,
        count("table_angles", settings.table_angles)?,
    ))
}

/// The per-pixel pipeline and uniform, made once; the table, remade when its size
/// changes.
#[derive(Debug)]
pub struct OneilPass {
    pass: PixelPass,
    params: wgpu::Buffer,
    table: Table,
    settings: OneilSettings,
}

impl OneilPass {
    /// The pipelines and an unbuilt table of the default settings' size.
    pub fn new(gpu: &GpuContext) -> Result<OneilPass, RenderError> {
        // The table may be sampled (`table_sampling`).
        let sampling = TableSampling::new(gpu);
        let pass = PixelPass::new(
            gpu,
            PixelShader {
                path: "sky/oneil/pixel.wgsl",
                entry: "main",
                label: "the oneil pass",
                params_size: size_of::<OneilUniform>(),
                tables: &[
                    sampling.texture_entry(3, wgpu::TextureViewDimension::D2),
                    texture_entry(4, wgpu::TextureViewDimension::D2),
                    uniform_entry(5, size_of::<ShadowMapUniform>()),
                ],
                sampling: Some(&sampling),
            },
        )?;
        let settings = OneilSettings::default();
        Ok(OneilPass {
            params: uniform_buffer(&gpu.device, "oneil", size_of::<OneilUniform>()),
            pass,
            table: Table::new(gpu, &settings)?,
            settings,
        })
    }
}

impl ModelPass for OneilPass {
    type Step = OneilStep;

    fn plan(&mut self, plan: &mut SkyPlan<'_, OneilStep>) -> Result<(), RenderError> {
        let (gpu, frame) = (plan.gpu, plan.frame);
        check_wavelengths(&frame.settings.wavelengths_nm)?;
        let settings = OneilSettings::from_options(&frame.settings.options)?;
        let params = OneilUniform {
            samples: count("samples", settings.samples)?,
            ..Default::default()
        };
        let size = table_size(&settings)?;
        count("table_ray_samples", settings.table_ray_samples)?;
        if self.table.pass.size() != size {
            self.table = Table::new(gpu, &settings)?;
        }
        let built = self.table.built_from.as_ref();
        let stale = built.is_none_or(|(_, ray_samples)| *ray_samples != settings.table_ray_samples)
            || OpticalDepthTable::INPUTS.stale(built.map(|(old, _)| old), &frame.atmosphere);
        self.settings = settings;
        self.table.pending = stale.then(|| (frame.atmosphere.clone(), settings.table_ray_samples));
        plan.build_if(OneilStep::OpticalDepth, stale);
        plan.run(OneilStep::Pass);
        gpu.write_uniform(&self.params, &params);
        Ok(())
    }

    fn encode(&mut self, step: OneilStep, cx: StepContext<'_>) {
        let table = &mut self.table;
        match step {
            OneilStep::OpticalDepth => {
                // `plan` checked that the count fits in u32.
                let ray_samples = self.settings.table_ray_samples as u32;
                let atmosphere = cx.io.atmosphere;
                table
                    .pass
                    .encode(cx.gpu, atmosphere, ray_samples, cx.encoder, cx.timestamps);
                if let Some(key) = table.pending.take() {
                    table.built_from = Some(key);
                }
            }
            OneilStep::Pass => {
                let view = table.pass.texture().create_view(&Default::default());
                let shadow = cx.io.shadow.view();
                let tables = [
                    wgpu::BindingResource::TextureView(&view),
                    wgpu::BindingResource::TextureView(&shadow),
                    cx.io.shadow.params().as_entire_binding(),
                ];
                self.pass.encode(cx, &self.params, &tables);
            }
        }
    }

    fn table_bytes(&self) -> u64 {
        let (w, h) = self.table.pass.size();
        u64::from(w) * u64::from(h) * 16
    }
}
