//! The cloud layer pass: `shaders/clouds/layer_image.wgsl` writes each pixel's cloud
//! radiance (rgb, at 680, 550, 440 nm) and transmittance (a) into an `Rgba32Float`
//! image; see `atmosphere-core`'s `clouds/layer/` for the equations. With a resolution
//! divisor above 1 it marches a reduced image that `shaders/clouds/layer_upsample.wgsl`
//! brings to full size (`clouds/layer/upsample.rs`).

use crate::clouds::layer_inputs::LayerInputs;
use crate::clouds::layer_uniform::LayerUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    ComputePipeline, read_only_storage_buffer_entry, split_timestamps, storage_texture_entry,
    texel_groups, texture_2d, texture_entry, uniform_buffer, uniform_entry,
};
use crate::gpu::readback::read_texture;
use atmosphere_core::clouds::layer::upsample::reduced_size;

const IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The compiled passes (the march and the upsample) and the parameter buffer.
#[derive(Debug)]
pub struct CloudLayerPass {
    pipeline: ComputePipeline,
    upsample: ComputePipeline,
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
        })
    }

    /// Records the pass into `encoder`, writing `image` (`Rgba32Float`, the size of
    /// `params.sizes.zw`), timed by `timestamps` when given (from the march's start to
    /// the upsample's end when the march is reduced).
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
        let divisor = params.noise[2];
        if divisor <= 1 {
            self.march(gpu, encoder, inputs, image, timestamps);
            return;
        }
        let reduced = texture_2d(
            &gpu.device,
            "cloud layer reduced image",
            reduced_size(params.sizes[2], params.sizes[3], divisor),
            IMAGE_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let (start, end) = split_timestamps(timestamps);
        self.march(gpu, encoder, inputs, &reduced, start);
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
    }

    /// Records the march into `target`, the full or the reduced image.
    fn march(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &LayerInputs,
        target: &wgpu::Texture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let cover = inputs.cover.create_view(&Default::default());
        let view = target.create_view(&Default::default());
        let bind_group = self.pipeline.bind_group(
            gpu,
            &[
                self.params.as_entire_binding(),
                wgpu::BindingResource::TextureView(&cover),
                inputs.orders.as_entire_binding(),
                wgpu::BindingResource::TextureView(&view),
            ],
        );
        self.pipeline.dispatch(
            encoder,
            "cloud layer",
            &bind_group,
            texel_groups(target),
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
