//! The pass that composites a frame's rain and ice volumes over its pixels
//! (`shaders/precipitation/volumes_composite.wgsl`): it reads the model's HDR image,
//! which the model writes into this pass's own image in frames with volumes, and the
//! frame's surface distances, and writes the HDR target.

use atmosphere_core::hydrometeors::render::LitVolume;
use wgpu::util::DeviceExt;

use crate::frame::Frame;
use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{
    ComputePipeline, read_only_storage_buffer_entry, storage_texture_entry, texel_groups,
    texture_2d, texture_entry, uniform_buffer, uniform_entry,
};

use super::volume_uniform::{VolumesUniform, pack};

/// What one frame's pass reads and writes.
#[derive(Debug)]
pub struct VolumesScene<'a> {
    pub frame: &'a Frame,
    pub volumes: &'a [LitVolume],
    /// The frame's atmosphere and frame uniforms.
    pub uniforms: (&'a wgpu::Buffer, &'a wgpu::Buffer),
    /// The frame's surface geometry (distance in w), read where `has_surface`.
    pub surface: &'a wgpu::TextureView,
    pub has_surface: bool,
}

/// The composite pipeline, its uniform and the image of the model's pixels it reads.
#[derive(Debug)]
pub struct VolumesPass {
    pipeline: ComputePipeline,
    params: wgpu::Buffer,
    /// The model's pixels (remade when the size changes).
    full: Option<wgpu::Texture>,
}

impl VolumesPass {
    pub fn new(gpu: &GpuContext) -> Result<VolumesPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let entries = [
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            uniform_entry(2, size_of::<VolumesUniform>()),
            read_only_storage_buffer_entry(3, 16),
            texture_entry(4, D2),
            texture_entry(5, D2),
            storage_texture_entry(6, HDR_FORMAT, D2),
        ];
        Ok(VolumesPass {
            pipeline: ComputePipeline::new(
                gpu,
                "precipitation/volumes_composite.wgsl",
                "main",
                "rain and ice volumes",
                &entries,
            )?,
            params: uniform_buffer(&gpu.device, "volumes", size_of::<VolumesUniform>()),
            full: None,
        })
    }

    /// Makes the image the model's pixels go to ([`VolumesPass::full`]) for frames of
    /// `size`, unless it has that size.
    pub fn fit(&mut self, gpu: &GpuContext, size: (u32, u32)) {
        if self.full.as_ref().map(|t| (t.width(), t.height())) != Some(size) {
            self.full = Some(texture_2d(
                &gpu.device,
                "volumes full",
                size,
                HDR_FORMAT,
                wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
            ));
        }
    }

    /// The image the frame's model (or its cloud composite) writes for this pass to read,
    /// made by [`VolumesPass::fit`]; `None` before it.
    pub fn full(&self) -> Option<&wgpu::Texture> {
        self.full.as_ref()
    }

    /// Records the composite of `scene`'s volumes over [`VolumesPass::full`] into `hdr`.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &VolumesScene<'_>,
        hdr: &wgpu::Texture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        let frame = scene.frame;
        let (uniform, bins) = pack(scene.volumes, frame.camera_position_m, scene.has_surface)?;
        gpu.write_uniform(&self.params, &uniform);
        let phase = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("volume phase tables"),
                contents: bytemuck::cast_slice(&bins),
                usage: wgpu::BufferUsages::STORAGE,
            });
        let full = self.full.as_ref().ok_or_else(|| {
            RenderError::Frame("the volumes pass has no image of the frame's size".into())
        })?;
        let full_view = full.create_view(&Default::default());
        let out = hdr.create_view(&Default::default());
        let bind_group = self.pipeline.bind_group(
            gpu,
            &[
                scene.uniforms.0.as_entire_binding(),
                scene.uniforms.1.as_entire_binding(),
                self.params.as_entire_binding(),
                phase.as_entire_binding(),
                wgpu::BindingResource::TextureView(&full_view),
                wgpu::BindingResource::TextureView(scene.surface),
                wgpu::BindingResource::TextureView(&out),
            ],
        );
        self.pipeline.dispatch(
            encoder,
            "rain and ice volumes",
            &bind_group,
            texel_groups(hdr),
            timestamps,
        );
        Ok(())
    }
}
