//! The pass that fills the cloud layer's sun map once a frame
//! (`shaders/clouds/sun_map_fill.wgsl`, twin of atmosphere-core's
//! `clouds/layer/sun_map.rs`): one invocation per texel and level, each a march towards
//! the sun through the layer's light extinction.

use crate::clouds::layer_uniform::LayerUniform;
use crate::clouds::sun_map_texture::{SUN_MAP_FORMAT, SunMapTexture};
use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::{
    ComputePipeline, storage_texture_entry, texture_entry, uniform_buffer, uniform_entry,
};

/// The fill pipeline and the layer's parameters it reads.
#[derive(Debug)]
pub struct SunMapPass {
    fill: ComputePipeline,
    layer: wgpu::Buffer,
}

impl SunMapPass {
    pub fn new(gpu: &GpuContext) -> Result<SunMapPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let [_, params] = SunMapTexture::layout_entries();
        let entries = [
            uniform_entry(0, size_of::<LayerUniform>()),
            texture_entry(1, D2),
            storage_texture_entry(4, SUN_MAP_FORMAT, D2),
            params,
        ];
        Ok(SunMapPass {
            fill: ComputePipeline::new(
                gpu,
                "clouds/sun_map_fill.wgsl",
                "main",
                "cloud sun map",
                &entries,
            )?,
            layer: uniform_buffer(
                &gpu.device,
                "cloud sun map layer",
                size_of::<LayerUniform>(),
            ),
        })
    }

    /// Records the fill of `map` (its parameters set, [`SunMapTexture::set`]) for the
    /// layer of `layer` over the cover texture `cover`.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        layer: &LayerUniform,
        cover: &wgpu::Texture,
        map: &SunMapTexture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        gpu.write_uniform(&self.layer, layer);
        let cover = cover.create_view(&Default::default());
        let out = map.texture().create_view(&Default::default());
        let [_, params] = map.bindings();
        let bind_group = self.fill.bind_group_numbered(
            gpu,
            &[
                (0, self.layer.as_entire_binding()),
                (1, wgpu::BindingResource::TextureView(&cover)),
                (4, wgpu::BindingResource::TextureView(&out)),
                params,
            ],
        );
        let n = map.texture().width();
        let levels = map.texture().height() / n;
        self.fill.dispatch(
            encoder,
            "cloud sun map",
            &bind_group,
            [n.div_ceil(8), n.div_ceil(8), levels],
            timestamps,
        );
    }
}
