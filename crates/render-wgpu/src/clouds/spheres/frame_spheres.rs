//! The cloud spheres in a renderer frame (`shaders/clouds/spheres/frame_image.wgsl`):
//! each pixel's spheres ended on the frame's surface, blended with the layer's march by
//! the spheres' weight of the hand-over (atmosphere-core's `clouds/spheres/handover.rs`),
//! and where each ray enters the cloud, written where the layer's march writes them so
//! that the model's second run and the composite take the spheres as they take the
//! layer (docs/clouds.md, "Cloud spheres in frames").

use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::spheres::settings::SphereSettings;

use crate::clouds::layer_uniform::LayerCamera;
use crate::clouds::spheres::sphere_cache::SphereCache;
use crate::clouds::spheres::sphere_uniform::SphereUniform;
use crate::frame::surface_buffer::GEOMETRY_FORMAT;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    ComputePipeline, read_only_storage_buffer_entry, storage_texture_entry, texel_groups,
    texture_entry, uniform_buffer, uniform_entry,
};

/// The format of the cloud images the pass reads (the layer's) and writes.
pub const CLOUD_IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// What the spheres of a frame are made of and seen from.
#[derive(Debug)]
pub struct SphereScene<'a> {
    /// The frame's camera (`frame_pass::frame_camera`).
    pub camera: LayerCamera,
    pub layer: &'a LayerSettings,
    pub spheres: &'a SphereSettings,
    /// The light on the clouds; its sun is the attenuation textures'.
    pub light: &'a CloudLight,
    pub bottom_radius_m: f64,
    pub cache: &'a SphereCache,
    /// The frame's surface geometry, read where `has_surface`.
    pub surface: &'a wgpu::TextureView,
    pub has_surface: bool,
    /// The spheres' share, in [0, 1]; the layer's march in `layer_image` takes the rest.
    pub weight: f64,
}

/// The images the pass reads and writes, each the frame's size.
#[derive(Debug)]
pub struct SphereImages<'a> {
    /// The layer's march (read where the weight is below 1).
    pub layer: &'a wgpu::Texture,
    /// The clouds the composite takes: rgb radiance, a transmittance.
    pub out: &'a wgpu::Texture,
    /// Where each ray enters the cloud (`surface_buffer.rs`'s geometry layout).
    pub front: &'a wgpu::Texture,
}

/// The compiled pass and its parameter buffers.
#[derive(Debug)]
pub struct FrameSpherePass {
    pipeline: ComputePipeline,
    params: wgpu::Buffer,
    flags: wgpu::Buffer,
}

impl FrameSpherePass {
    pub fn new(gpu: &GpuContext) -> Result<FrameSpherePass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let entries = [
            uniform_entry(0, size_of::<SphereUniform>()),
            read_only_storage_buffer_entry(1, 4),
            read_only_storage_buffer_entry(2, 4),
            read_only_storage_buffer_entry(3, 4),
            storage_texture_entry(4, CLOUD_IMAGE_FORMAT, D2),
            storage_texture_entry(5, GEOMETRY_FORMAT, D2),
            texture_entry(6, D2),
            uniform_entry(7, 16),
            texture_entry(8, D2),
        ];
        Ok(FrameSpherePass {
            pipeline: ComputePipeline::new(
                gpu,
                "clouds/spheres/frame_image.wgsl",
                "main",
                "cloud spheres in frames",
                &entries,
            )?,
            params: uniform_buffer(
                &gpu.device,
                "cloud spheres in frames",
                size_of::<SphereUniform>(),
            ),
            flags: uniform_buffer(&gpu.device, "cloud spheres in frames flags", 16),
        })
    }

    /// Records the spheres of `scene` into `images`, making them first (on the CPU, for
    /// the scene's sun) unless the cache holds them; timed by `timestamps` when given.
    pub fn encode(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &SphereScene<'_>,
        images: &SphereImages<'_>,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        if !(0.0..=1.0).contains(&scene.weight) {
            return Err(RenderError::Frame(format!(
                "cloud spheres' weight = {} must lie in [0, 1]",
                scene.weight
            )));
        }
        let made = scene.cache.get(
            gpu,
            scene.layer,
            scene.spheres,
            scene.bottom_radius_m,
            scene.light.sun_direction,
        )?;
        let Some(made) = made.as_ref() else {
            return Err(RenderError::Frame("the cloud spheres were not made".into()));
        };
        let params = SphereUniform::new(&scene.camera, scene.light, &made.spheres)?;
        gpu.write_uniform(&self.params, &params);
        let flags = [
            f32::from(u8::from(scene.has_surface)),
            scene.weight as f32,
            0.0,
            0.0,
        ];
        gpu.write_uniform(&self.flags, &flags);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (layer, out, front) = (view(images.layer), view(images.out), view(images.front));
        let bind_group = self.pipeline.bind_group(
            gpu,
            &[
                self.params.as_entire_binding(),
                made.inputs.cloud_depths.as_entire_binding(),
                made.inputs.sun_ratios.as_entire_binding(),
                made.inputs.single_phase.as_entire_binding(),
                wgpu::BindingResource::TextureView(&out),
                wgpu::BindingResource::TextureView(&front),
                wgpu::BindingResource::TextureView(scene.surface),
                self.flags.as_entire_binding(),
                wgpu::BindingResource::TextureView(&layer),
            ],
        );
        self.pipeline.dispatch(
            encoder,
            "cloud spheres in frames",
            &bind_group,
            texel_groups(images.out),
            timestamps,
        );
        Ok(())
    }
}
