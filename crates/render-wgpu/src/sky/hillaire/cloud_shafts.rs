//! Hillaire's light shafts with the cloud layer's shadow in the air, per pixel
//! (`shaders/sky/hillaire/cloud_shafts.wgsl`; CPU twin: atmosphere-core's
//! `clouds/layer/air_shadow.rs`): run before the hillaire pass in frames whose sun map
//! shades the air below the layer's base ([`crate::frame::plan::FramePlan::cloud_shafts`]),
//! it writes each pixel's shafts beside the surface's cloud transmittance into the sun
//! map's per-pixel image, which the pass reads instead of marching its own. The map is
//! read here rather than inside the hillaire pass, which crashed lavapipe (Mesa 22.3.6)
//! with it (docs/clouds.md, "Cloud shadows in the air").

use crate::clouds::sun_map_texture::{
    PIXELS_FORMAT, PIXELS_OUT_BINDING, SUN_MAP_BINDING, SUN_MAP_PARAMS_BINDING, SunMapUniform,
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
use crate::sky::hillaire::uniform::HillaireUniform;
use crate::sky::model_pass::StepContext;
use crate::sky::table_sampling::TableSampling;

/// The pass in two variants: with the frame's surface and without (the buffer unread).
#[derive(Debug)]
pub struct CloudShaftsPass {
    with_surface: ComputePipeline,
    without_surface: ComputePipeline,
}

impl CloudShaftsPass {
    /// Compiles both variants, reading the transmittance table as `sampling` says.
    pub fn new(gpu: &GpuContext, sampling: &TableSampling) -> Result<CloudShaftsPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let entries = [
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            uniform_entry(2, size_of::<HillaireUniform>()),
            sampling.texture_entry(3, D2),
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
                "sky/hillaire/cloud_shafts.wgsl",
                "main",
                "hillaire's cloud shafts",
                &entries,
                &[("SURFACE", surface), sampling.constant()],
            )
        };
        Ok(CloudShaftsPass {
            with_surface: variant(1.0)?,
            without_surface: variant(0.0)?,
        })
    }

    /// Records the pass over every pixel of `cx`'s frame, with the model's `params` and
    /// `transmittance` table, into the sun map's per-pixel image.
    pub fn encode(
        &self,
        cx: &mut StepContext<'_>,
        (params, transmittance): (&wgpu::Buffer, &wgpu::TextureView),
        sampling: &TableSampling,
    ) {
        let io = cx.io;
        let map = io.sun_map;
        let out = map.pixels().create_view(&Default::default());
        let shadow = io.shadow.view();
        let resources = [
            (0, io.atmosphere.as_entire_binding()),
            (1, io.frame.as_entire_binding()),
            (2, params.as_entire_binding()),
            (3, wgpu::BindingResource::TextureView(transmittance)),
            (9, wgpu::BindingResource::TextureView(&shadow)),
            (10, io.shadow.params().as_entire_binding()),
            (
                GEOMETRY_BINDING,
                wgpu::BindingResource::TextureView(&io.surface[0]),
            ),
            (SUN_MAP_PARAMS_BINDING, map.params().as_entire_binding()),
            (PIXELS_OUT_BINDING, wgpu::BindingResource::TextureView(&out)),
            map.map_binding(),
            sampling.sampler_binding(),
        ];
        let pipeline = if io.has_surface {
            &self.with_surface
        } else {
            &self.without_surface
        };
        let bind_group = pipeline.bind_group_numbered(cx.gpu, &resources);
        let groups = texel_groups(map.pixels());
        pipeline.dispatch(
            cx.encoder,
            "hillaire's cloud shafts",
            &bind_group,
            groups,
            None,
        );
    }
}
