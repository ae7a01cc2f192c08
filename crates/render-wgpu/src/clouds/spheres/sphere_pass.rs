//! The cloud spheres pass: `shaders/clouds/spheres/image.wgsl` writes each pixel's
//! radiance of the spheres (rgb, at 680, 550, 440 nm) and their transmittance (a) into an
//! `Rgba32Float` image; see atmosphere-core's `clouds/spheres/` for the equations.

use atmosphere_core::clouds::layer::settings::LayerMethod;

use crate::clouds::spheres::sphere_inputs::SphereInputs;
use crate::clouds::spheres::sphere_uniform::SphereUniform;
use crate::clouds::spheres::sphere_variants::SphereVariants;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    read_only_storage_buffer_entry, storage_texture_entry, texel_groups, texture_2d,
    uniform_buffer, uniform_entry,
};
use crate::gpu::readback::read_texture;

const IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The compiled pass and its parameter buffer.
#[derive(Debug)]
pub struct CloudSpherePass {
    pipeline: SphereVariants,
    params: wgpu::Buffer,
}

impl CloudSpherePass {
    pub fn new(gpu: &GpuContext) -> Result<CloudSpherePass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let entries = [
            uniform_entry(20, size_of::<SphereUniform>()),
            read_only_storage_buffer_entry(21, 4),
            read_only_storage_buffer_entry(22, 4),
            read_only_storage_buffer_entry(23, 4),
            storage_texture_entry(24, IMAGE_FORMAT, D2),
        ];
        Ok(CloudSpherePass {
            pipeline: SphereVariants::new(
                gpu,
                ("clouds/spheres/image.wgsl", "main"),
                "cloud spheres",
                &entries,
            )?,
            params: uniform_buffer(&gpu.device, "cloud spheres", size_of::<SphereUniform>()),
        })
    }

    /// Records the pass into `encoder`, writing `image` (`Rgba32Float`, the size of
    /// `params.counts.zw`), the spheres lit as the layer's `method` lights them, timed by
    /// `timestamps` when given.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        (params, method): (&SphereUniform, LayerMethod),
        inputs: &SphereInputs,
        image: &wgpu::Texture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), GpuError> {
        gpu.write_uniform(&self.params, params);
        let view = image.create_view(&Default::default());
        let pipeline = self.pipeline.for_method(gpu, method)?;
        let bind_group = pipeline.bind_group_numbered(
            gpu,
            &[
                (20, self.params.as_entire_binding()),
                (21, inputs.cloud_depths.as_entire_binding()),
                (22, inputs.sun_ratios.as_entire_binding()),
                (23, inputs.single_phase.as_entire_binding()),
                (24, wgpu::BindingResource::TextureView(&view)),
            ],
        );
        pipeline.dispatch(
            encoder,
            "cloud spheres",
            &bind_group,
            texel_groups(image),
            timestamps,
        );
        Ok(())
    }

    /// Renders the image of `params` (lit as `method` lights the spheres) and reads it
    /// back, row by row: [radiance at 680, 550, 440 nm, transmittance] per pixel.
    pub fn render(
        &self,
        gpu: &GpuContext,
        (params, method): (&SphereUniform, LayerMethod),
        inputs: &SphereInputs,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        let image = texture_2d(
            &gpu.device,
            "cloud spheres image",
            (params.counts[2], params.counts[3]),
            IMAGE_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
        );
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.encode(gpu, &mut encoder, (params, method), inputs, &image, None)?;
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_texture(gpu, &image, 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}
