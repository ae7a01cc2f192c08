//! The oneil model on the GPU: O'Neil's 4-channel optical-depth table built by
//! `shaders/sky/oneil/optical_depth_table.wgsl` (its CPU twin `OpticalDepthTable::build`), rebuilt only
//! when the density profiles, the geometry or the table's settings change, and the
//! per-pixel pass of `shaders/sky/oneil/pixel.wgsl` (`Oneil::radiance`).

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::table_inputs::Inputs;
use atmosphere_core::models::oneil::{OneilSettings, OpticalDepthTable};
use bytemuck::{Pod, Zeroable};

use crate::frame::Frame;
use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::atmosphere_uniform::check_wavelengths;
use crate::frame::plan::{FramePlan, StepKind};
use crate::frame::surface_buffer::SurfaceBuffer;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{
    ComputePipeline, PixelPipeline, storage_texture_entry, texel_groups, uniform_buffer,
    uniform_entry,
};
use crate::gpu::readback::read_texture;
use crate::sky::model_pass::{ModelPass, PassIo};
use crate::sky::table_sampling::TableSampling;
use crate::sky::transmittance::TABLE_FORMAT;

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
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("oneil optical depth"),
            size: wgpu::Extent3d {
                width: heights,
                height: angles,
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
        gpu.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
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

/// The table and what it was built from (`None`: not yet built).
#[derive(Debug)]
struct Table {
    pass: OneilTablePass,
    built_from: Option<(Atmosphere, usize)>,
}

/// The per-pixel pipeline and uniform, made once; the table, remade when its size
/// changes.
#[derive(Debug)]
pub struct OneilPass {
    pipeline: PixelPipeline,
    params: wgpu::Buffer,
    table: Option<Table>,
    settings: OneilSettings,
    /// What the table build of the frame being planned is for.
    pending: Option<(Atmosphere, usize)>,
    /// How the pass reads the table.
    sampling: TableSampling,
}

impl OneilPass {
    pub fn new(gpu: &GpuContext) -> Result<OneilPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let surface_entries = SurfaceBuffer::layout_entries();
        // The table may be sampled (`table_sampling`).
        let sampling = TableSampling::new(gpu);
        let pipeline = PixelPipeline::with_constants(
            gpu,
            "sky/oneil/pixel.wgsl",
            "main",
            "the oneil pass",
            &[
                uniform_entry(0, size_of::<AtmosphereUniform>()),
                uniform_entry(1, size_of::<FrameUniform>()),
                uniform_entry(2, size_of::<OneilUniform>()),
                sampling.texture_entry(3, D2),
                storage_texture_entry(4, HDR_FORMAT, D2),
                sampling.sampler_entry(),
                surface_entries[0],
                surface_entries[1],
            ],
            &[sampling.constant()],
        )?;
        Ok(OneilPass {
            params: uniform_buffer(&gpu.device, "oneil", size_of::<OneilUniform>()),
            pipeline,
            table: None,
            settings: OneilSettings::default(),
            pending: None,
            sampling,
        })
    }
}

impl ModelPass for OneilPass {
    fn plan(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        plan: &mut FramePlan,
    ) -> Result<(), RenderError> {
        check_wavelengths(&frame.settings.wavelengths_nm)?;
        let settings = OneilSettings::from_options(&frame.settings.options)?;
        let params = OneilUniform {
            samples: count("samples", settings.samples)?,
            ..Default::default()
        };
        let size = (
            count("table_heights", settings.table_heights)?,
            count("table_angles", settings.table_angles)?,
        );
        count("table_ray_samples", settings.table_ray_samples)?;
        if self.table.as_ref().is_none_or(|t| t.pass.size() != size) {
            self.table = Some(Table {
                pass: OneilTablePass::new(gpu, size.0, size.1)?,
                built_from: None,
            });
        }
        let stale = self.table.as_ref().is_none_or(|t| {
            t.built_from.as_ref().is_none_or(|(old, ray_samples)| {
                *ray_samples != settings.table_ray_samples
                    || Inputs::changed(old, &frame.atmosphere).intersects(OpticalDepthTable::INPUTS)
            })
        });
        self.settings = settings;
        self.pending = stale.then(|| (frame.atmosphere.clone(), settings.table_ray_samples));
        plan.build_if("optical_depth", stale);
        plan.run("oneil", StepKind::Pass);
        gpu.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        Ok(())
    }

    fn encode(
        &mut self,
        step: &'static str,
        gpu: &GpuContext,
        io: &PassIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let Some(table) = self.table.as_mut() else {
            unreachable!("plan makes the table before any step");
        };
        match step {
            "optical_depth" => {
                // `plan` checked that the count fits in u32.
                let ray_samples = self.settings.table_ray_samples as u32;
                table
                    .pass
                    .encode(gpu, io.atmosphere, ray_samples, encoder, timestamps);
                table.built_from = self.pending.take();
            }
            "oneil" => {
                let view = table.pass.texture().create_view(&Default::default());
                let hdr = io.hdr.create_view(&Default::default());
                let pipeline = self.pipeline.variant(io.has_surface);
                let bind_group = self.sampling.bind_group(
                    gpu,
                    pipeline,
                    &[
                        io.atmosphere.as_entire_binding(),
                        io.frame.as_entire_binding(),
                        self.params.as_entire_binding(),
                        wgpu::BindingResource::TextureView(&view),
                        wgpu::BindingResource::TextureView(&hdr),
                    ],
                    Some(io.surface),
                );
                let groups = texel_groups(io.hdr);
                pipeline.dispatch(encoder, "oneil", &bind_group, groups, timestamps);
            }
            other => unreachable!("the oneil plan has no step {other}"),
        }
    }

    fn table_bytes(&self) -> u64 {
        self.table.as_ref().map_or(0, |t| {
            let (w, h) = t.pass.size();
            u64::from(w) * u64::from(h) * 16
        })
    }
}
