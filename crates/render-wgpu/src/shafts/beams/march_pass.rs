//! The beams march on the GPU (`shaders/shafts/beams/march.wgsl`): one compute
//! invocation per pixel runs the ray march with shadow maps of atmosphere-core's
//! `beams/methods/march.rs`, its CPU twin, and writes the radiance at the three
//! wavelengths into an `Rgba32Float` image ([`BeamImage`]).

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::{ComputePipeline, storage_texture_entry, texel_groups};
use crate::gpu::timer::GpuTimer;
use crate::shafts::beams::gpu_scene::GpuScene;
use crate::shafts::beams::image::{BeamImage, RADIANCE_FORMAT};
use crate::shafts::beams::limits;
use crate::shafts::beams::scene_buffers::{SceneBuffers, scene_entries};

/// The march's pipeline, made once per device.
#[derive(Debug)]
pub struct MarchPass {
    pipeline: ComputePipeline,
}

impl MarchPass {
    pub fn new(gpu: &GpuContext) -> Result<MarchPass, RenderError> {
        let mut entries = scene_entries();
        entries.push(storage_texture_entry(
            9,
            RADIANCE_FORMAT,
            wgpu::TextureViewDimension::D2,
        ));
        let pipeline = ComputePipeline::new(
            gpu,
            "shafts/beams/march.wgsl",
            "main",
            "beams march",
            &entries,
        )?;
        Ok(MarchPass { pipeline })
    }

    /// Renders `scene` after checking it against the device's limits; the pass's GPU
    /// time in milliseconds comes with the image where the device has timestamps.
    pub fn render(
        &self,
        gpu: &GpuContext,
        scene: &GpuScene,
    ) -> Result<(BeamImage, Option<f64>), RenderError> {
        limits::check(scene, &gpu.device.limits())?;
        let [width, height, ..] = scene.uniform.size_steps_lights;
        let image = BeamImage::new(gpu, width, height);
        let buffers = SceneBuffers::new(gpu, scene);
        let view = image.radiance.create_view(&Default::default());
        let mut resources = buffers.resources();
        resources.push(wgpu::BindingResource::TextureView(&view));
        let bind_group = self.pipeline.bind_group(gpu, &resources);
        let timer = GpuTimer::new(gpu, 1);
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.pipeline.dispatch(
            &mut encoder,
            "beams march",
            &bind_group,
            texel_groups(&image.radiance),
            timer.as_ref().map(|t| t.compute_writes(0)),
        );
        if let Some(t) = &timer {
            t.resolve(&mut encoder, 1);
        }
        gpu.queue.submit([encoder.finish()]);
        let ms = match &timer {
            Some(t) => Some(t.read(gpu, 1)?[0]),
            None => None,
        };
        Ok((image, ms))
    }
}
