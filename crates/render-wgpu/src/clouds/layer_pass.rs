//! The cloud layer pass: `shaders/clouds/layer_image.wgsl` writes each pixel's cloud
//! radiance (rgb, at 680, 550, 440 nm) and transmittance (a) into an `Rgba32Float`
//! image; see `atmosphere-core`'s `clouds/layer/` for the equations. With a resolution
//! divisor above 1 it marches a reduced image that `shaders/clouds/layer_upsample.wgsl`
//! brings to full size (`clouds/layer/upsample.rs`). With `sun_light = map` the march
//! reads the sun's optical depth from a sun map filled before it
//! (`clouds/sun_map_pass.rs`), bound at 33 and 35 as the per-pixel pass binds it.

use crate::clouds::layer_inputs::LayerInputs;
use crate::clouds::layer_uniform::LayerUniform;
use crate::clouds::march_variants::MarchVariants;
use crate::clouds::sun_map_texture::{SUN_MAP_BINDING, SunMapTexture};
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    ComputePipeline, read_only_storage_buffer_entry, split_timestamps, storage_texture_entry,
    texel_groups, texture_2d, texture_entry, uniform_buffer, uniform_entry,
};
use crate::gpu::readback::read_texture;
use atmosphere_core::clouds::layer::upsample::reduced_size;

const IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The compiled passes (the march and the upsample), the parameter buffer and the
/// empty sun map of marches without one.
#[derive(Debug)]
pub struct CloudLayerPass {
    march: MarchVariants,
    upsample: ComputePipeline,
    params: wgpu::Buffer,
    no_map: SunMapTexture,
}

impl CloudLayerPass {
    pub fn new(gpu: &GpuContext) -> Result<CloudLayerPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let entries = [
            uniform_entry(0, size_of::<LayerUniform>()),
            texture_entry(1, D2),
            read_only_storage_buffer_entry(2, 4),
            storage_texture_entry(3, IMAGE_FORMAT, D2),
            SunMapTexture::layout_entries()[1],
            texture_entry(SUN_MAP_BINDING, D2),
        ];
        Ok(CloudLayerPass {
            march: MarchVariants::new("clouds/layer_image.wgsl", "cloud layer", &entries),
            upsample: ComputePipeline::new(
                gpu,
                "clouds/layer_upsample.wgsl",
                "main",
                "cloud layer upsample",
                &[
                    texture_entry(0, D2),
                    storage_texture_entry(1, IMAGE_FORMAT, D2),
                ],
            )?,
            params: uniform_buffer(&gpu.device, "cloud layer", size_of::<LayerUniform>()),
            no_map: SunMapTexture::new(gpu),
        })
    }

    /// Records the pass into `encoder`, writing `image` (`Rgba32Float`, the size of
    /// `params.sizes.zw`), timed by `timestamps` when given (from the march's start to
    /// the upsample's end when the march is reduced). `sun_map` (filled before) lights
    /// the layer when its settings say `sun_light = map`; an error says when it is
    /// missing.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        (params, inputs): (&LayerUniform, &LayerInputs),
        sun_map: Option<&SunMapTexture>,
        image: &wgpu::Texture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        if params.noise[3] == 1 && sun_map.is_none() {
            return Err(RenderError::Frame(
                "cloud layer: sun_light = map needs a sun map; none was given".into(),
            ));
        }
        let sun_map = sun_map.unwrap_or(&self.no_map);
        gpu.write_uniform(&self.params, params);
        let divisor = params.noise[2];
        if divisor <= 1 {
            return self.march(gpu, encoder, (params, inputs, sun_map), image, timestamps);
        }
        let reduced = texture_2d(
            &gpu.device,
            "cloud layer reduced image",
            reduced_size(params.sizes[2], params.sizes[3], divisor),
            IMAGE_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let (start, end) = split_timestamps(timestamps);
        self.march(gpu, encoder, (params, inputs, sun_map), &reduced, start)?;
        let source = reduced.create_view(&Default::default());
        let target = image.create_view(&Default::default());
        let bind_group = self.upsample.bind_group(
            gpu,
            &[
                wgpu::BindingResource::TextureView(&source),
                wgpu::BindingResource::TextureView(&target),
            ],
        );
        self.upsample.dispatch(
            encoder,
            "cloud layer upsample",
            &bind_group,
            texel_groups(image),
            end,
        );
        Ok(())
    }

    /// Records the march of `params`' method and sun light into `target`, the full or
    /// the reduced image.
    fn march(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        (params, inputs, sun_map): (&LayerUniform, &LayerInputs, &SunMapTexture),
        target: &wgpu::Texture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        let pipeline = self.march.for_params(gpu, params)?;
        let cover = inputs.cover.create_view(&Default::default());
        let view = target.create_view(&Default::default());
        let map = sun_map.texture().create_view(&Default::default());
        let bind_group = pipeline.bind_group_numbered(
            gpu,
            &[
                (0, self.params.as_entire_binding()),
                (1, wgpu::BindingResource::TextureView(&cover)),
                (2, inputs.orders.as_entire_binding()),
                (3, wgpu::BindingResource::TextureView(&view)),
                sun_map.bindings()[1].clone(),
                (SUN_MAP_BINDING, wgpu::BindingResource::TextureView(&map)),
            ],
        );
        pipeline.dispatch(
            encoder,
            "cloud layer",
            &bind_group,
            texel_groups(target),
            timestamps,
        );
        Ok(())
    }

    /// Renders the image of `params` (lit through `sun_map` where its settings say so)
    /// and reads it back, row by row: [radiance at 680, 550, 440 nm, transmittance] per
    /// pixel.
    pub fn render(
        &self,
        gpu: &GpuContext,
        (params, inputs): (&LayerUniform, &LayerInputs),
        sun_map: Option<&SunMapTexture>,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        let image = texture_2d(
            &gpu.device,
            "cloud layer image",
            (params.sizes[2], params.sizes[3]),
            IMAGE_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
        );
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.encode(gpu, &mut encoder, (params, inputs), sun_map, &image, None)?;
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_texture(gpu, &image, 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}
