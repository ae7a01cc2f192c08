//! The cloud layer pass: `shaders/clouds/layer_image.wgsl` writes each pixel's cloud
//! radiance (rgb, at 680, 550, 440 nm) and transmittance (a) into an `Rgba32Float`
//! image; see `atmosphere-core`'s `clouds/layer/` for the equations.

use crate::clouds::layer_inputs::LayerInputs;
use crate::clouds::layer_uniform::LayerUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    ComputePipeline, read_only_storage_buffer_entry, storage_texture_entry, texel_groups,
    texture_2d, texture_entry, uniform_buffer, uniform_entry,
};
use crate::gpu::readback::read_texture;

const IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The compiled pass and its parameter buffer.
#[derive(Debug)]
pub struct CloudLayerPass {
    pipeline: ComputePipeline,
    params: wgpu::Buffer,
}

impl CloudLayerPass {
    pub fn new(gpu: &GpuContext) -> Result<CloudLayerPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let entries = [
            uniform_entry(0, size_of::<LayerUniform>()),
            texture_entry(1, D2),
            read_only_storage_buffer_entry(2, 4),
            storage_texture_entry(3, IMAGE_FORMAT, D2),
        ];
        Ok(CloudLayerPass {
            pipeline: ComputePipeline::new(
                gpu,
                "clouds/layer_image.wgsl",
                "main",
                "cloud layer",
                &entries,
            )?,
            params: uniform_buffer(&gpu.device, "cloud layer", size_of::<LayerUniform>()),
        })
    }

    /// Records the pass into `encoder`, writing `image` (`Rgba32Float`, the size of
    /// `params.sizes.zw`), timed by `timestamps` when given.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        params: &LayerUniform,
        inputs: &LayerInputs,
        image: &wgpu::Texture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        gpu.write_uniform(&self.params, params);
        let cover = inputs.cover.create_view(&Default::default());
        let target = image.create_view(&Default::default());
        let bind_group = self.pipeline.bind_group(
            gpu,
            &[
                self.params.as_entire_binding(),
                wgpu::BindingResource::TextureView(&cover),
                inputs.orders.as_entire_binding(),
                wgpu::BindingResource::TextureView(&target),
            ],
        );
        self.pipeline.dispatch(
            encoder,
            "cloud layer",
            &bind_group,
            texel_groups(image),
            timestamps,
        );
    }

    /// Renders the image of `params` and reads it back, row by row: [radiance at 680,
    /// 550, 440 nm, transmittance] per pixel.
    pub fn render(
        &self,
        gpu: &GpuContext,
        params: &LayerUniform,
        inputs: &LayerInputs,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        let image = texture_2d(
            &gpu.device,
            "cloud layer image",
            (params.sizes[2], params.sizes[3]),
            IMAGE_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
        );
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.encode(gpu, &mut encoder, params, inputs, &image, None);
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_texture(gpu, &image, 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}
