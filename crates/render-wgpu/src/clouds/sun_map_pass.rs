//! The passes of the cloud layer's sun map once a frame: the fill
//! (`shaders/clouds/sun_map_fill.wgsl`, twin of atmosphere-core's
//! `clouds/layer/sun_map.rs`), one invocation per texel and level, each a march towards
//! the sun through the layer's light extinction; then the map read at each pixel's
//! surface (`shaders/clouds/sun_map_pixels.wgsl`).

use crate::clouds::layer_uniform::LayerUniform;
use crate::clouds::sun_map_texture::{
    PIXELS_FORMAT, PIXELS_OUT_BINDING, SUN_MAP_BINDING, SUN_MAP_FORMAT, SunMapTexture,
};
use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::surface_buffer::GEOMETRY_BINDING;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::{
    ComputePipeline, storage_texture_entry, texel_groups, texture_entry, uniform_buffer,
    uniform_entry,
};
use crate::shafts::terrain::shadow_texture::ShadowTexture;

/// The fill and per-pixel pipelines and the layer's parameters the fill reads.
#[derive(Debug)]
pub struct SunMapPass {
    fill: ComputePipeline,
    pixels: ComputePipeline,
    layer: wgpu::Buffer,
}

/// What the per-pixel passes read besides the map: the frame's atmosphere and frame
/// uniforms, its surface geometry and whether it has a surface, and the terrain's
/// shadow map (the cloud's shadow in the air, `air_shadow_pass.rs`).
#[derive(Clone, Copy, Debug)]
pub struct PixelInputs<'a> {
    pub atmosphere: &'a wgpu::Buffer,
    pub frame: &'a wgpu::Buffer,
    pub geometry: &'a wgpu::TextureView,
    pub has_surface: bool,
    pub shadow: &'a ShadowTexture,
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
        let pixels = [
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            texture_entry(GEOMETRY_BINDING, D2),
            params,
            storage_texture_entry(PIXELS_OUT_BINDING, PIXELS_FORMAT, D2),
            texture_entry(SUN_MAP_BINDING, D2),
        ];
        Ok(SunMapPass {
            pixels: ComputePipeline::new(
                gpu,
                "clouds/sun_map_pixels.wgsl",
                "main",
                "cloud sun map pixels",
                &pixels,
            )?,
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

    /// Records the read of `map` (filled) at each pixel's surface into its per-pixel
    /// texture, after the fill.
    pub fn encode_pixels(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        inputs: PixelInputs<'_>,
        map: &SunMapTexture,
    ) {
        self.encode_pixels_into(gpu, encoder, inputs, map, map.pixels());
    }

    /// [`SunMapPass::encode_pixels`] into `out`, a texture of the per-pixel image's size
    /// and format (the cloud's shadow in the air copies it from there).
    pub fn encode_pixels_into(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        inputs: PixelInputs<'_>,
        map: &SunMapTexture,
        out: &wgpu::Texture,
    ) {
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (out, texture) = (view(out), view(map.texture()));
        let bind_group = self.pixels.bind_group_numbered(
            gpu,
            &[
                (0, inputs.atmosphere.as_entire_binding()),
                (1, inputs.frame.as_entire_binding()),
                (
                    GEOMETRY_BINDING,
                    wgpu::BindingResource::TextureView(inputs.geometry),
                ),
                map.bindings()[1].clone(),
                (PIXELS_OUT_BINDING, wgpu::BindingResource::TextureView(&out)),
                (
                    SUN_MAP_BINDING,
                    wgpu::BindingResource::TextureView(&texture),
                ),
            ],
        );
        let groups = texel_groups(map.pixels());
        self.pixels
            .dispatch(encoder, "cloud sun map pixels", &bind_group, groups, None);
    }
}
