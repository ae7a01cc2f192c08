//! The beams march on the GPU (`shaders/shafts/beams/march.wgsl`): one compute
//! invocation per pixel runs the ray march with shadow maps of atmosphere-core's
//! `beams/methods/march.rs`, its CPU twin, and writes the radiance at the three
//! wavelengths into an `Rgba32Float` image ([`BeamImage`]).

use wgpu::util::DeviceExt;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::{
    ComputePipeline, read_only_storage_buffer_entry, storage_texture_entry, texel_groups,
    uniform_entry,
};
use crate::gpu::timer::GpuTimer;
use crate::shafts::beams::gpu_scene::{BeamsUniform, GpuScene};
use crate::shafts::beams::image::{BeamImage, RADIANCE_FORMAT};
use crate::shafts::beams::limits;

/// The march's pipeline, made once per device.
#[derive(Debug)]
pub struct MarchPass {
    pipeline: ComputePipeline,
}

impl MarchPass {
    pub fn new(gpu: &GpuContext) -> Result<MarchPass, RenderError> {
        let mut entries = vec![uniform_entry(0, size_of::<BeamsUniform>())];
        entries.extend((1..=8).map(|binding| read_only_storage_buffer_entry(binding, 0)));
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
        let device = &gpu.device;
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("beams params"),
            contents: bytemuck::bytes_of(&scene.uniform),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let storage = |label: &str, bytes: &[u8]| {
            // A binding holds at least one element: empty lists get a zeroed one.
            let contents = if bytes.is_empty() {
                &[0u8; 256][..]
            } else {
                bytes
            };
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        let buffers = [
            storage("beams lights", bytemuck::cast_slice(&scene.lights)),
            storage(
                "beams light maps",
                bytemuck::cast_slice(&scene.light_texels),
            ),
            storage("beams shadow views", bytemuck::cast_slice(&scene.views)),
            storage("beams shadow maps", bytemuck::cast_slice(&scene.depths)),
            storage("beams primitives", bytemuck::cast_slice(&scene.primitives)),
            storage("beams BVH nodes", bytemuck::cast_slice(&scene.nodes)),
            storage("beams triangles", bytemuck::cast_slice(&scene.triangles)),
            storage(
                "beams phase table",
                bytemuck::cast_slice(&scene.phase_table),
            ),
        ];
        let view = image.radiance.create_view(&Default::default());
        let mut resources = vec![uniform.as_entire_binding()];
        resources.extend(buffers.iter().map(|b| b.as_entire_binding()));
        resources.push(wgpu::BindingResource::TextureView(&view));
        let bind_group = self.pipeline.bind_group(gpu, &resources);
        let timer = GpuTimer::new(gpu, 1);
        let mut encoder = device.create_command_encoder(&Default::default());
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
