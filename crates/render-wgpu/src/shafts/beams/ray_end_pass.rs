//! Where each pixel's ray ends (`shaders/shafts/beams/ray_end.wgsl`): at the first
//! occluder or where the medium has extinguished the light, as the march's rays end.
//! The passes that draw planes (`planes_pass.rs`, `qtable_pass.rs`) test their planes
//! against it as a rasteriser tests a depth buffer. CPU twin: atmosphere-core's
//! `InScattering::ray_end_m`.

use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::{ComputePipeline, storage_texture_entry, texel_groups, texture_2d};
use crate::shafts::beams::scene_buffers::{SceneBuffers, scene_entries};

/// Where each pixel's ray ends, m.
const RAY_END_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// The ray-end pipeline, made once per device.
#[derive(Debug)]
pub struct RayEndPass {
    pipeline: ComputePipeline,
}

impl RayEndPass {
    pub fn new(gpu: &GpuContext) -> Result<RayEndPass, GpuError> {
        let mut entries = scene_entries();
        entries.push(storage_texture_entry(
            10,
            RAY_END_FORMAT,
            wgpu::TextureViewDimension::D2,
        ));
        let pipeline = ComputePipeline::new(
            gpu,
            "shafts/beams/ray_end.wgsl",
            "main",
            "beams ray end",
            &entries,
        )?;
        Ok(RayEndPass { pipeline })
    }

    /// Records the pass for the scene of `buffers` at `size` into `encoder`; returns
    /// the texture it writes.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        buffers: &SceneBuffers,
        size: (u32, u32),
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> wgpu::Texture {
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let ray_end = texture_2d(&gpu.device, "beams ray end", size, RAY_END_FORMAT, usage);
        let view = ray_end.create_view(&Default::default());
        let mut resources: Vec<(u32, wgpu::BindingResource<'_>)> = buffers
            .resources()
            .into_iter()
            .enumerate()
            .map(|(b, r)| (b as u32, r))
            .collect();
        resources.push((10, wgpu::BindingResource::TextureView(&view)));
        let group = self.pipeline.bind_group_numbered(gpu, &resources);
        self.pipeline.dispatch(
            encoder,
            "beams ray end",
            &group,
            texel_groups(&ray_end),
            timestamps,
        );
        ray_end
    }
}
