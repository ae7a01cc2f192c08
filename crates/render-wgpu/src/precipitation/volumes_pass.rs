//! The pass that composites a frame's rain and ice volumes over its pixels
//! (`shaders/precipitation/volumes_composite.wgsl`): over the rectangle of pixels the
//! volumes may cover (`screen_rect.rs`) it copies the model's HDR image into its own,
//! reads that and the frame's surface distances, and writes the HDR target; the pixels
//! outside keep the model's. On a software adapter a pass costs about the same per pixel
//! whatever it computes, so the pixels it leaves out are most of what it saves
//! (docs/optics-rendering.md, "Cost"). At a divisor N above 1 a first pass
//! (`volumes_reduced.wgsl`) marches one pixel in N x N over the rectangle's reduced
//! pixels, and the composite upsamples them (atmosphere-core's `hydrometeors/reduced.rs`).

use atmosphere_core::hydrometeors::render::LitVolume;
use wgpu::util::DeviceExt;

use crate::frame::Frame;
use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{
    ComputePipeline, WORKGROUP_SIDE, read_only_storage_buffer_entry, storage_texture_entry,
    texture_2d, texture_entry, uniform_buffer, uniform_entry,
};

use super::screen_rect::volumes_rect;
use super::volume_uniform::{VolumesUniform, pack};

/// The reduced pass's images: terms and spans in f32 (a layer's entry may pass f16's
/// range).
const REDUCED_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

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
    /// One pixel in `divisor` x `divisor` marched, the rest upsampled (1: every pixel).
    pub divisor: u32,
}

/// The composite and reduced pipelines, their uniform, the copy of the model's pixels
/// and the reduced pass's two images.
#[derive(Debug)]
pub struct VolumesPass {
    pipeline: ComputePipeline,
    reduced_pipeline: ComputePipeline,
    params: wgpu::Buffer,
    /// The model's pixels under the volumes (remade when the size changes).
    full: Option<wgpu::Texture>,
    /// The reduced pass's terms and spans ([`reduced_size`]; remade when the size or
    /// the divisor changes; a texel each at divisor 1).
    reduced: Option<[wgpu::Texture; 2]>,
}

/// The reduced images' size for frames of `size` at `divisor`: a reduced pixel past the
/// frame's last one on each axis.
pub fn reduced_size((width, height): (u32, u32), divisor: u32) -> (u32, u32) {
    if divisor <= 1 {
        return (1, 1);
    }
    ((width - 1) / divisor + 2, (height - 1) / divisor + 2)
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
            texture_entry(9, D2),
            texture_entry(10, D2),
        ];
        let reduced_entries = [
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            uniform_entry(2, size_of::<VolumesUniform>()),
            read_only_storage_buffer_entry(3, 16),
            texture_entry(5, D2),
            storage_texture_entry(7, REDUCED_FORMAT, D2),
            storage_texture_entry(8, REDUCED_FORMAT, D2),
        ];
        Ok(VolumesPass {
            pipeline: ComputePipeline::new(
                gpu,
                "precipitation/volumes_composite.wgsl",
                "main",
                "rain and ice volumes",
                &entries,
            )?,
            reduced_pipeline: ComputePipeline::new(
                gpu,
                "precipitation/volumes_reduced.wgsl",
                "main",
                "rain and ice volumes, reduced",
                &reduced_entries,
            )?,
            params: uniform_buffer(&gpu.device, "volumes", size_of::<VolumesUniform>()),
            full: None,
            reduced: None,
        })
    }

    /// Makes the image the model's pixels are copied to for frames of `size`, and the
    /// reduced images for `divisor`, unless they have those sizes.
    pub fn fit(&mut self, gpu: &GpuContext, size: (u32, u32), divisor: u32) {
        if self.full.as_ref().map(|t| (t.width(), t.height())) != Some(size) {
            self.full = Some(texture_2d(
                &gpu.device,
                "volumes full",
                size,
                HDR_FORMAT,
                wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            ));
        }
        let want = reduced_size(size, divisor);
        if self.reduced.as_ref().map(|[a, _]| (a.width(), a.height())) != Some(want) {
            let image = |label| {
                texture_2d(
                    &gpu.device,
                    label,
                    want,
                    REDUCED_FORMAT,
                    wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::STORAGE_BINDING,
                )
            };
            self.reduced = Some([
                image("volumes reduced terms"),
                image("volumes reduced light"),
            ]);
        }
    }

    /// Records the composite of `scene`'s volumes over the model's pixels in `hdr` (of
    /// the size given to [`VolumesPass::fit`]), in place.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &VolumesScene<'_>,
        hdr: &wgpu::Texture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        let frame = scene.frame;
        let Some(rect) = volumes_rect(frame, scene.volumes) else {
            return Ok(());
        };
        let (mut uniform, bins) = pack(scene.volumes, frame.camera_position_m, scene.has_surface)?;
        uniform.count[2..].copy_from_slice(&rect.origin);
        let divisor = scene.divisor;
        let fitted = (frame.width, frame.height);
        let Some([reduced_a, reduced_b]) = self
            .reduced
            .as_ref()
            .filter(|[a, _]| (a.width(), a.height()) == reduced_size(fitted, divisor))
        else {
            return Err(RenderError::Frame(format!(
                "the volumes pass has no reduced images for {}x{} at divisor {divisor}",
                frame.width, frame.height
            )));
        };
        // The reduced pixels the rectangle's pixels read: from the one at or before its
        // first pixel to the one at or past its last.
        let first = rect.origin.map(|o| o / divisor);
        let last: [u32; 2] =
            std::array::from_fn(|a| (rect.origin[a] + rect.size[a] - 1) / divisor + 1);
        uniform.reduction = [divisor, first[0], first[1], 0];
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
        // Whole workgroups over the rectangle, within the frame: the pixels the pass writes.
        let groups = rect.size.map(|n| n.div_ceil(WORKGROUP_SIDE));
        let extent = |axis: usize, limit: u32| {
            (WORKGROUP_SIDE * groups[axis]).min(limit - rect.origin[axis])
        };
        let origin = wgpu::Origin3d {
            x: rect.origin[0],
            y: rect.origin[1],
            z: 0,
        };
        let at = |texture| wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin,
            aspect: wgpu::TextureAspect::All,
        };
        encoder.copy_texture_to_texture(
            at(hdr),
            at(full),
            wgpu::Extent3d {
                width: extent(0, hdr.width()),
                height: extent(1, hdr.height()),
                depth_or_array_layers: 1,
            },
        );
        let full_view = full.create_view(&Default::default());
        let out = hdr.create_view(&Default::default());
        let reduced_views = [reduced_a, reduced_b].map(|t| t.create_view(&Default::default()));
        if divisor > 1 {
            let bind_group = self.reduced_pipeline.bind_group_numbered(
                gpu,
                &[
                    (0, scene.uniforms.0.as_entire_binding()),
                    (1, scene.uniforms.1.as_entire_binding()),
                    (2, self.params.as_entire_binding()),
                    (3, phase.as_entire_binding()),
                    (5, wgpu::BindingResource::TextureView(scene.surface)),
                    (7, wgpu::BindingResource::TextureView(&reduced_views[0])),
                    (8, wgpu::BindingResource::TextureView(&reduced_views[1])),
                ],
            );
            let reduced_groups: [u32; 2] =
                std::array::from_fn(|a| (last[a] - first[a] + 1).div_ceil(WORKGROUP_SIDE));
            self.reduced_pipeline.dispatch(
                encoder,
                "rain and ice volumes, reduced",
                &bind_group,
                [reduced_groups[0], reduced_groups[1], 1],
                None,
            );
        }
        let bind_group = self.pipeline.bind_group_numbered(
            gpu,
            &[
                (0, scene.uniforms.0.as_entire_binding()),
                (1, scene.uniforms.1.as_entire_binding()),
                (2, self.params.as_entire_binding()),
                (3, phase.as_entire_binding()),
                (4, wgpu::BindingResource::TextureView(&full_view)),
                (5, wgpu::BindingResource::TextureView(scene.surface)),
                (6, wgpu::BindingResource::TextureView(&out)),
                (9, wgpu::BindingResource::TextureView(&reduced_views[0])),
                (10, wgpu::BindingResource::TextureView(&reduced_views[1])),
            ],
        );
        self.pipeline.dispatch(
            encoder,
            "rain and ice volumes",
            &bind_group,
            [groups[0], groups[1], 1],
            timestamps,
        );
        Ok(())
    }
}
