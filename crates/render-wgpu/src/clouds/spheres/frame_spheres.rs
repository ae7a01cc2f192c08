//! The cloud spheres in a renderer frame (`shaders/clouds/spheres/frame_image.wgsl`):
//! each pixel's spheres ended on the frame's surface, blended with the layer's march by
//! the spheres' weight of the hand-over (atmosphere-core's `clouds/spheres/handover.rs`),
//! and where each ray enters the cloud, written where the layer's march writes them so
//! that the model's second run and the composite take the spheres as they take the
//! layer (docs/clouds.md, "Cloud spheres in frames"). With the spheres' resolution
//! divisor above 1, one ray per divisor x divisor pixels is shaded
//! (`frame_reduced.wgsl`) and brought to full size by the span each ray crossed
//! (`frame_upsample.wgsl`, twin of atmosphere-core's `clouds/spheres/reduced.rs`).

use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::spheres::settings::SphereSettings;

use crate::clouds::layer_uniform::LayerCamera;
use crate::clouds::spheres::image_formats::{CLOUD_IMAGE_FORMAT, SPAN_FORMAT};
use crate::clouds::spheres::reduced_targets::ReducedSphereTargets;
use crate::clouds::spheres::sphere_cache::SphereCache;
use crate::clouds::spheres::sphere_uniform::SphereUniform;
use crate::clouds::spheres::sphere_variants::SphereVariants;
use crate::frame::surface_buffer::GEOMETRY_FORMAT;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    read_only_storage_buffer_entry, split_timestamps, storage_texture_entry, texel_groups,
    texture_2d, texture_entry, uniform_buffer, uniform_entry,
};
use crate::gpu::readback::read_texture;

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
    /// The reduced images, needed where the spheres' resolution divisor is above 1.
    pub reduced: Option<&'a ReducedSphereTargets>,
}

/// The compiled passes (every pixel; reduced and upsampled) and their parameter buffers.
#[derive(Debug)]
pub struct FrameSpherePass {
    pipeline: SphereVariants,
    reduced: SphereVariants,
    upsample: SphereVariants,
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
        let reduced = [
            entries[0],
            entries[1],
            entries[2],
            entries[3],
            entries[4],
            entries[6],
            entries[7],
            storage_texture_entry(9, SPAN_FORMAT, D2),
        ];
        let mut upsample = entries.to_vec();
        upsample.extend([texture_entry(9, D2), texture_entry(10, D2)]);
        let pipeline = |shader, label, entries: &[wgpu::BindGroupLayoutEntry]| {
            SphereVariants::new(gpu, shader, label, entries)
        };
        Ok(FrameSpherePass {
            pipeline: pipeline(
                "clouds/spheres/frame_image.wgsl",
                "cloud spheres in frames",
                &entries,
            )?,
            reduced: pipeline(
                "clouds/spheres/frame_reduced.wgsl",
                "cloud spheres in frames, reduced",
                &reduced,
            )?,
            upsample: pipeline(
                "clouds/spheres/frame_upsample.wgsl",
                "cloud spheres in frames, upsample",
                &upsample,
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
        scene
            .spheres
            .check()
            .map_err(|e| RenderError::Frame(e.to_string()))?;
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
        let divisor = scene.spheres.resolution_divisor;
        let flags = [
            f32::from(u8::from(scene.has_surface)),
            scene.weight as f32,
            divisor as f32,
            scene.layer.extinction_per_m as f32,
        ];
        gpu.write_uniform(&self.flags, &flags);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (layer, out, front) = (view(images.layer), view(images.out), view(images.front));
        let method = made.spheres.method();
        let inputs = [
            (0, self.params.as_entire_binding()),
            (1, made.inputs.cloud_depths.as_entire_binding()),
            (2, made.inputs.sun_ratios.as_entire_binding()),
            (3, made.inputs.single_phase.as_entire_binding()),
            (6, wgpu::BindingResource::TextureView(scene.surface)),
            (7, self.flags.as_entire_binding()),
        ];
        let written = [
            (4, wgpu::BindingResource::TextureView(&out)),
            (5, wgpu::BindingResource::TextureView(&front)),
            (8, wgpu::BindingResource::TextureView(&layer)),
        ];
        if divisor <= 1 {
            let pipeline = self.pipeline.for_method(gpu, method)?;
            let bind_group =
                pipeline.bind_group_numbered(gpu, &[inputs.as_slice(), &written].concat());
            pipeline.dispatch(
                encoder,
                "cloud spheres in frames",
                &bind_group,
                texel_groups(images.out),
                timestamps,
            );
            return Ok(());
        }
        let Some(reduced) = images.reduced.filter(|r| r.divisor == divisor) else {
            return Err(RenderError::Frame(format!(
                "the cloud spheres' reduced images were not made for resolution divisor \
                 {divisor}"
            )));
        };
        let (image, spans) = (&reduced.image, &reduced.spans);
        let groups = texel_groups(image);
        let (image, spans) = (view(image), view(spans));
        let (start, end) = split_timestamps(timestamps);
        let reduced = [
            (4, wgpu::BindingResource::TextureView(&image)),
            (9, wgpu::BindingResource::TextureView(&spans)),
        ];
        let pipeline = self.reduced.for_method(gpu, method)?;
        let bind_group = pipeline.bind_group_numbered(gpu, &[inputs.as_slice(), &reduced].concat());
        pipeline.dispatch(
            encoder,
            "cloud spheres in frames, reduced",
            &bind_group,
            groups,
            start,
        );
        let read = [
            (9, wgpu::BindingResource::TextureView(&image)),
            (10, wgpu::BindingResource::TextureView(&spans)),
        ];
        let pipeline = self.upsample.for_method(gpu, method)?;
        let bind_group =
            pipeline.bind_group_numbered(gpu, &[inputs.as_slice(), &written, &read].concat());
        pipeline.dispatch(
            encoder,
            "cloud spheres in frames, upsample",
            &bind_group,
            texel_groups(images.out),
            end,
        );
        Ok(())
    }

    /// The spheres of `scene` alone, as the composite would take them with the layer's
    /// weight 0 (`scene.weight` must be 1), read back row by row: [radiance at 680, 550,
    /// 440 nm, transmittance] per pixel of its camera. For tests and benches.
    pub fn render(
        &self,
        gpu: &GpuContext,
        scene: &SphereScene<'_>,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        if scene.weight != 1.0 {
            return Err(RenderError::Frame(format!(
                "cloud spheres alone: weight = {} must be 1 (no layer to blend with)",
                scene.weight
            )));
        }
        let size = (scene.camera.width, scene.camera.height);
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let layer = texture_2d(&gpu.device, "no layer", (1, 1), CLOUD_IMAGE_FORMAT, usage);
        let out = texture_2d(
            &gpu.device,
            "cloud spheres alone",
            size,
            CLOUD_IMAGE_FORMAT,
            usage | wgpu::TextureUsages::COPY_SRC,
        );
        let front = texture_2d(
            &gpu.device,
            "cloud spheres' front",
            size,
            GEOMETRY_FORMAT,
            usage,
        );
        let divisor = scene.spheres.resolution_divisor;
        let reduced = (divisor > 1).then(|| ReducedSphereTargets::new(gpu, size, divisor));
        let images = SphereImages {
            layer: &layer,
            out: &out,
            front: &front,
            reduced: reduced.as_ref(),
        };
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.encode(gpu, &mut encoder, scene, &images, None)?;
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_texture(gpu, &out, 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}
