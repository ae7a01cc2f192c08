//! The cloud layer's shadow in the air below its base, per pixel, for every sky model
//! (`shaders/clouds/air_shadow.wgsl`; CPU twin: atmosphere-core's
//! `clouds/layer/air_shadow.rs`): run after the sun map's fill in frames whose map shades
//! the air ([`crate::frame::plan::FramePlan::cloud_shafts`]), it writes each pixel's
//! single scattering that the cloud takes out beyond the terrain's shadow beside the
//! surface's cloud transmittance into the map's per-pixel image, which every model's
//! pixel pass reads and subtracts. It marches through a columns table of its own,
//! rebuilt when the atmosphere's columns change. The map is read here rather than inside
//! the pixel passes, which crashed lavapipe (Mesa 22.3.6) with it (docs/clouds.md,
//! "Cloud shadows in the air").

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::layer::air_shadow::CloudAirShadow;

use crate::clouds::sun_map_pass::PixelInputs;
use crate::clouds::sun_map_texture::{
    PIXELS_FORMAT, PIXELS_OUT_BINDING, SUN_MAP_BINDING, SUN_MAP_PARAMS_BINDING, SunMapTexture,
    SunMapUniform,
};
use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::surface_buffer::GEOMETRY_BINDING;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::{
    ComputePipeline, storage_texture_entry, texel_groups, texture_entry, uniform_entry,
};
use crate::shafts::terrain::uniform::ShadowMapUniform;
use crate::sky::columns_table::ColumnsTable;
use crate::sky::table_sampling::TableSampling;

/// The columns table's binding (that of `sky/hillaire/bindings.wgsl`, whose march the
/// shader runs).
const COLUMNS_BINDING: u32 = 3;

/// The pass in two variants (with the frame's surface and without, the buffer unread)
/// and its columns table.
#[derive(Debug)]
pub struct AirShadowPass {
    with_surface: ComputePipeline,
    without_surface: ComputePipeline,
    sampling: TableSampling,
    columns: ColumnsTable,
    stale: bool,
}

impl AirShadowPass {
    /// Compiles both variants; the table, of [`CloudAirShadow::TABLE_SIZE`], unbuilt.
    pub fn new(gpu: &GpuContext) -> Result<AirShadowPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let sampling = TableSampling::new(gpu);
        let entries = [
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            sampling.texture_entry(COLUMNS_BINDING, D2),
            texture_entry(9, D2),
            uniform_entry(10, size_of::<ShadowMapUniform>()),
            texture_entry(GEOMETRY_BINDING, D2),
            uniform_entry(SUN_MAP_PARAMS_BINDING, size_of::<SunMapUniform>()),
            storage_texture_entry(PIXELS_OUT_BINDING, PIXELS_FORMAT, D2),
            texture_entry(SUN_MAP_BINDING, D2),
            sampling.sampler_entry(),
        ];
        let variant = |surface: f64| {
            ComputePipeline::with_constants(
                gpu,
                "clouds/air_shadow.wgsl",
                "main",
                "cloud shadow in the air",
                &entries,
                &[("SURFACE", surface), sampling.constant()],
            )
        };
        let (width, height) = CloudAirShadow::TABLE_SIZE;
        Ok(AirShadowPass {
            with_surface: variant(1.0)?,
            without_surface: variant(0.0)?,
            columns: ColumnsTable::new(gpu, (width as u32, height as u32))?,
            sampling,
            stale: false,
        })
    }

    /// Plans the table's build for a frame of `atmosphere` when its columns changed.
    pub fn plan(&mut self, atmosphere: &Atmosphere) {
        self.stale = self.columns.plan(atmosphere);
    }

    /// Records the table's planned build, from `atmosphere` in the GPU's layout, then the
    /// pass over every pixel of the frame of `inputs` into `map`'s per-pixel image (after
    /// the map's fill), timed by `timestamps`.
    pub fn encode(
        &mut self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        (inputs, atmosphere): (PixelInputs<'_>, &AtmosphereUniform),
        map: &SunMapTexture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        if std::mem::take(&mut self.stale) {
            self.columns.build(gpu, atmosphere, encoder, None);
        }
        let out = map.pixels().create_view(&Default::default());
        let columns = self.columns.texture().create_view(&Default::default());
        let shadow = inputs.shadow.view();
        let resources = [
            (0, inputs.atmosphere.as_entire_binding()),
            (1, inputs.frame.as_entire_binding()),
            (
                COLUMNS_BINDING,
                wgpu::BindingResource::TextureView(&columns),
            ),
            (9, wgpu::BindingResource::TextureView(&shadow)),
            (10, inputs.shadow.params().as_entire_binding()),
            (
                GEOMETRY_BINDING,
                wgpu::BindingResource::TextureView(inputs.geometry),
            ),
            (SUN_MAP_PARAMS_BINDING, map.params().as_entire_binding()),
            (PIXELS_OUT_BINDING, wgpu::BindingResource::TextureView(&out)),
            map.map_binding(),
            self.sampling.sampler_binding(),
        ];
        let pipeline = if inputs.has_surface {
            &self.with_surface
        } else {
            &self.without_surface
        };
        let bind_group = pipeline.bind_group_numbered(gpu, &resources);
        let groups = texel_groups(map.pixels());
        pipeline.dispatch(
            encoder,
            "cloud shadow in the air",
            &bind_group,
            groups,
            timestamps,
        );
    }
}
