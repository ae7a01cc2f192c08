//! The cloud spheres in a renderer frame (`shaders/clouds/spheres/frame_image.wgsl`):
//! each pixel's spheres ended on the frame's surface, blended with the layer's march by
//! the spheres' weight of the hand-over (atmosphere-core's `clouds/spheres/handover.rs`),
//! and where each ray enters the cloud, written where the layer's march writes them so
//! that the model's second run and the composite take the spheres as they take the
//! layer (docs/clouds.md, "Cloud spheres in frames"). With the spheres' resolution
//! divisor above 1, one ray per divisor x divisor pixels is shaded
//! (`frame_reduced.wgsl`) and brought to full size by the span each ray crossed
//! (`frame_upsample.wgsl`, twin of atmosphere-core's `clouds/spheres/reduced.rs`), the
//! pixels it cannot interpolate listed and shaded by an indirect dispatch; from above the
//! layer, where the model's run in front of the cloud is reduced and needs nothing the
//! spheres write, the upsample and the listed pixels' pass composite each pixel with the
//! model's runs at once (`frame_upsample.wgsl`'s compositing entry points,
//! `clouds/composite_pixel.wgsl`), and the composite is no pass of its own.

use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings};
use atmosphere_core::clouds::spheres::settings::SphereSettings;

use crate::clouds::composite_inputs::CompositeInputs;
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
use crate::gpu::pixel_list::PixelList;
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
    /// What the composite binds, where the upsample composites each pixel with the
    /// model's runs instead of writing `out` and `front` (with `reduced` only).
    pub composite: Option<&'a CompositeInputs>,
}

/// What the reduced spheres' passes bind: the spheres' inputs, and with them the layer's
/// march and what the upsample and the listed pixels' pass write (the images, or the
/// composite's inputs).
struct ReducedRun<'a> {
    method: LayerMethod,
    inputs: &'a [(u32, wgpu::BindingResource<'a>)],
    bindings: &'a [(u32, wgpu::BindingResource<'a>)],
    composite: bool,
    /// The full-size passes' workgroups.
    groups: [u32; 3],
}

/// The compiled passes (every pixel; reduced, upsampled and the listed pixels, the last
/// two also compositing) and their parameter buffers.
#[derive(Debug)]
pub struct FrameSpherePass {
    pipeline: SphereVariants,
    reduced: SphereVariants,
    /// The upsample and the listed pixels' pass, writing the images or (index 1)
    /// compositing.
    upsample: [SphereVariants; 2],
    listed: [SphereVariants; 2],
    params: wgpu::Buffer,
    flags: wgpu::Buffer,
}

impl FrameSpherePass {
    pub fn new(gpu: &GpuContext) -> Result<FrameSpherePass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let entries = [
            uniform_entry(20, size_of::<SphereUniform>()),
            read_only_storage_buffer_entry(21, 4),
            read_only_storage_buffer_entry(22, 4),
            read_only_storage_buffer_entry(23, 4),
            storage_texture_entry(24, CLOUD_IMAGE_FORMAT, D2),
            storage_texture_entry(25, GEOMETRY_FORMAT, D2),
            texture_entry(26, D2),
            uniform_entry(27, 16),
            texture_entry(28, D2),
        ];
        let reduced = [
            entries[0],
            entries[1],
            entries[2],
            entries[3],
            entries[4],
            entries[6],
            entries[7],
            storage_texture_entry(29, SPAN_FORMAT, D2),
        ];
        let mut upsample = entries.to_vec();
        upsample.extend([
            texture_entry(29, D2),
            texture_entry(30, D2),
            PixelList::list_entry(31),
            PixelList::dispatch_entry(32),
        ]);
        let mut listed = entries.to_vec();
        listed.extend([
            texture_entry(29, D2),
            texture_entry(30, D2),
            PixelList::list_entry(31),
        ]);
        // The compositing entries write neither the spheres' image nor their front.
        let composited = |entries: &[wgpu::BindGroupLayoutEntry]| {
            let mut out: Vec<_> = entries
                .iter()
                .filter(|e| ![24, 25].contains(&e.binding))
                .copied()
                .collect();
            out.extend(CompositeInputs::layout_entries());
            out
        };
        let pipeline = |shader, label, entries: &[wgpu::BindGroupLayoutEntry]| {
            SphereVariants::new(gpu, shader, label, entries)
        };
        let shader = "clouds/spheres/frame_upsample.wgsl";
        Ok(FrameSpherePass {
            pipeline: pipeline(
                ("clouds/spheres/frame_image.wgsl", "main"),
                "cloud spheres in frames",
                &entries,
            )?,
            reduced: pipeline(
                ("clouds/spheres/frame_reduced.wgsl", "main"),
                "cloud spheres in frames, reduced",
                &reduced,
            )?,
            upsample: [
                pipeline(
                    (shader, "main"),
                    "cloud spheres in frames, upsample",
                    &upsample,
                )?,
                SphereVariants::lazy(
                    (shader, "composite"),
                    "cloud spheres in frames, upsample and composite",
                    &composited(&upsample),
                ),
            ],
            // Compiled on first use: only frames with pixels to list, or from above the
            // layer, take them.
            listed: [
                SphereVariants::lazy(
                    (shader, "listed"),
                    "cloud spheres in frames, listed pixels",
                    &listed,
                ),
                SphereVariants::lazy(
                    (shader, "listed_composite"),
                    "cloud spheres in frames, listed pixels composited",
                    &composited(&listed),
                ),
            ],
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
            (20, self.params.as_entire_binding()),
            (21, made.inputs.cloud_depths.as_entire_binding()),
            (22, made.inputs.sun_ratios.as_entire_binding()),
            (23, made.inputs.single_phase.as_entire_binding()),
            (26, wgpu::BindingResource::TextureView(scene.surface)),
            (27, self.flags.as_entire_binding()),
        ];
        // The layer's march, and what the full-size passes write.
        let mut written = vec![(28, wgpu::BindingResource::TextureView(&layer))];
        match images.composite {
            Some(composite) => written.extend(composite.bindings()),
            None => written.extend([
                (24, wgpu::BindingResource::TextureView(&out)),
                (25, wgpu::BindingResource::TextureView(&front)),
            ]),
        }
        let bindings = [inputs.as_slice(), &written].concat();
        if divisor > 1 {
            let reduced = images.reduced.filter(|r| r.divisor == divisor);
            let Some(reduced) = reduced else {
                return Err(RenderError::Frame(format!(
                    "the cloud spheres' reduced images were not made for resolution \
                     divisor {divisor}"
                )));
            };
            let run = ReducedRun {
                method,
                inputs: &inputs,
                bindings: &bindings,
                composite: images.composite.is_some(),
                groups: texel_groups(images.out),
            };
            return self.encode_reduced(gpu, encoder, &run, reduced, timestamps);
        }
        if images.composite.is_some() {
            return Err(RenderError::Frame(
                "the cloud spheres composite only at a reduced resolution".into(),
            ));
        }
        let pipeline = self.pipeline.for_method(gpu, method)?;
        let bind_group = pipeline.bind_group_numbered(gpu, &bindings);
        pipeline.dispatch(
            encoder,
            "cloud spheres in frames",
            &bind_group,
            texel_groups(images.out),
            timestamps,
        );
        Ok(())
    }

    /// Records the reduced spheres of `run` into `reduced`, their upsample and the listed
    /// pixels' pass (timed from the first's start to the last's end).
    fn encode_reduced(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        run: &ReducedRun<'_>,
        reduced: &ReducedSphereTargets,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        let list = reduced.list.as_ref().map_err(|e| {
            RenderError::Frame(format!(
                "cloud spheres at a reduced resolution: {e}; use the offline quality \
                 (resolution divisor 1) or a smaller frame"
            ))
        })?;
        list.reset(gpu);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (image, spans) = (view(&reduced.image), view(&reduced.spans));
        let (start, end) = split_timestamps(timestamps);
        let written = [
            (24, wgpu::BindingResource::TextureView(&image)),
            (29, wgpu::BindingResource::TextureView(&spans)),
        ];
        let pipeline = self.reduced.for_method(gpu, run.method)?;
        let bind_group = pipeline.bind_group_numbered(gpu, &[run.inputs, &written].concat());
        pipeline.dispatch(
            encoder,
            "cloud spheres in frames, reduced",
            &bind_group,
            texel_groups(&reduced.image),
            start,
        );
        let read = [
            (29, wgpu::BindingResource::TextureView(&image)),
            (30, wgpu::BindingResource::TextureView(&spans)),
            (31, list.list.as_entire_binding()),
            (32, list.dispatch.as_entire_binding()),
        ];
        let variant = usize::from(run.composite);
        let pipeline = self.upsample[variant].for_method(gpu, run.method)?;
        let bind_group = pipeline.bind_group_numbered(gpu, &[run.bindings, &read].concat());
        pipeline.dispatch(
            encoder,
            "cloud spheres in frames, upsample",
            &bind_group,
            run.groups,
            None,
        );
        // The listed pixels' pass reads all but the dispatch it is given.
        let pipeline = self.listed[variant].for_method(gpu, run.method)?;
        let bind_group = pipeline.bind_group_numbered(gpu, &[run.bindings, &read[..3]].concat());
        pipeline.dispatch_indirect(
            encoder,
            "cloud spheres in frames, listed pixels",
            &bind_group,
            &list.dispatch,
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
            composite: None,
        };
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.encode(gpu, &mut encoder, scene, &images, None)?;
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_texture(gpu, &out, 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}
