//! The cloud layer in a renderer frame, on the GPU: the march of every pixel ended on the
//! frame's surface (`shaders/clouds/frame_march.wgsl`), or, with a resolution divisor
//! above 1, of a reduced image (`frame_march_reduced.wgsl`) brought to full size by the
//! segment each ray marched (`frame_upsample.wgsl`, atmosphere-core's
//! `clouds/layer/segment_upsample.rs`), the pixels it cannot interpolate listed and
//! marched by an indirect dispatch (`frame_march_list.wgsl`); either writes where each ray
//! enters the cloud as the surface of the sky model's second run (albedo 0: the model's
//! radiance in front of the cloud, its aerial perspective), and the composite of the
//! cloud with the model's two runs into the HDR target
//! (`shaders/clouds/frame_composite.wgsl`). The compositing is atmosphere-core's
//! `clouds/layer/composite.rs`. Where the camera is inside the layer at a reduced
//! resolution (no second run, no spheres) the upsample and the listed march composite
//! each pixel over the model's as they find it (their `OVER_MODEL` variants,
//! `frame_over_full.wgsl`) and the composite is no pass of its own: on a software
//! rasteriser each full-size pass costs tens of milliseconds even where it does little
//! (docs/clouds.md, "Clouds in frames"). The march therefore runs after the model's
//! pixels. With `sun_light = map` the marches read the frame's sun map
//! (`clouds/frame_sun_map.rs`, filled before them) at 33 and 35. Above the hand-over the
//! cloud spheres (`spheres/frame_spheres.rs`) take the march's place, or blend with it in
//! the band, and the composite reads their image (or, from above the layer at a reduced
//! resolution, their upsample composites). With the model's run in front reduced the
//! composite reads each pixel's air in front from the run's taps and lists the pixels
//! that need more for a pass over the list alone.

use crate::clouds::cloud_targets::{CLOUD_FORMAT, CloudTargets, SEGMENT_FORMAT};
use crate::clouds::composite_inputs::CompositeInputs;
use crate::clouds::frame_clouds::{CloudSteps, FrameClouds};
use crate::clouds::front_targets::TRANSMITTANCE_FORMAT;
use crate::clouds::layer_inputs::LayerInputs;
use crate::clouds::layer_uniform::{LayerCamera, LayerUniform};
use crate::clouds::march_variants::MarchVariants;
use crate::clouds::spheres::frame_spheres::{FrameSpherePass, SphereImages, SphereScene};
use crate::clouds::sun_map_texture::{SUN_MAP_BINDING, SunMapTexture};
use crate::frame::Frame;
use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::surface_buffer::GEOMETRY_FORMAT;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::lazy_pipeline::LazyPipeline;
use crate::gpu::pipeline::{
    ComputePipeline, read_only_storage_buffer_entry, split_timestamps, storage_texture_entry,
    texel_groups, texture_entry, uniform_buffer, uniform_entry,
};
use crate::gpu::pixel_list::PixelList;
use crate::gpu::timer::GpuTimer;

/// The layer's camera for `frame`: the frame's camera, axes and field of view.
pub fn frame_camera(frame: &Frame) -> LayerCamera {
    let [right, up, forward] = frame.axes();
    LayerCamera {
        position_m: frame.camera_position_m,
        forward: forward.normalize(),
        right: right.normalize(),
        up: up.normalize(),
        fov_deg: frame.vertical_fov_deg,
        width: frame.width,
        height: frame.height,
    }
}

/// What the march of a frame reads.
#[derive(Debug)]
pub struct MarchScene<'a> {
    pub frame: &'a Frame,
    pub clouds: &'a FrameClouds,
    /// The cover texture and the multiple-scattering tables.
    pub inputs: &'a LayerInputs,
    /// The frame's surface geometry (`surface_buffer.rs`), read where `has_surface`.
    pub surface: &'a wgpu::TextureView,
    pub has_surface: bool,
    /// Whether the model's second run (`cloud_front`) runs; without it the composite
    /// takes no air in front of the cloud (the camera is inside the layer).
    pub has_front: bool,
    /// The frame's sun map, filled when the layer is lit by it.
    pub sun_map: &'a SunMapTexture,
    /// The model's pixels and the frame's HDR target, which the upsample writes when it
    /// composites ([`CloudSteps::composite_in_upsample`]).
    pub model_pixels: &'a wgpu::Texture,
    pub hdr: &'a wgpu::Texture,
    /// The frame's atmosphere and frame uniforms, which the spheres' upsample binds when
    /// it composites ([`CloudSteps::composite_in_spheres`]).
    pub uniforms: (&'a wgpu::Buffer, &'a wgpu::Buffer),
}

/// The march (full or reduced, and the upsample) and composite pipelines and their
/// parameter buffers.
#[derive(Debug)]
pub struct CloudFramePass {
    march: MarchVariants,
    march_reduced: MarchVariants,
    upsample: ComputePipeline,
    march_list: MarchVariants,
    /// The upsample and the listed march that composite over the model's pixels.
    upsample_over: ComputePipeline,
    march_list_over: MarchVariants,
    /// The composite by the whole rule.
    composite: ComputePipeline,
    /// The composite from the reduced run's taps, listing the pixels that need more, and
    /// of the listed pixels: compiled on first use, by frames from above the layer.
    composite_from_taps: [LazyPipeline; 2],
    /// The rays of the model's reduced run in front of the cloud (`frame_front.rs`).
    pub front_rays: ComputePipeline,
    spheres: FrameSpherePass,
    params: wgpu::Buffer,
    flags: wgpu::Buffer,
}

impl CloudFramePass {
    pub fn new(gpu: &GpuContext) -> Result<CloudFramePass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let march = [
            uniform_entry(0, size_of::<LayerUniform>()),
            texture_entry(1, D2),
            read_only_storage_buffer_entry(2, 4),
            storage_texture_entry(3, CLOUD_FORMAT, D2),
            texture_entry(4, D2),
            storage_texture_entry(5, GEOMETRY_FORMAT, D2),
            uniform_entry(6, 16),
            SunMapTexture::layout_entries()[1],
            texture_entry(SUN_MAP_BINDING, D2),
        ];
        let reduced = [
            march[0],
            march[1],
            march[2],
            march[3],
            march[4],
            march[6],
            march[7],
            march[8],
            storage_texture_entry(7, SEGMENT_FORMAT, D2),
        ];
        // Both variants of the upsample and the listed march bind the model's pixels and
        // the HDR target (11, 12), which `OVER_MODEL` writes.
        let over = [
            texture_entry(11, D2),
            storage_texture_entry(12, HDR_FORMAT, D2),
        ];
        let mut upsample = march.to_vec();
        upsample.extend([
            texture_entry(7, D2),
            texture_entry(8, D2),
            PixelList::list_entry(9),
            PixelList::dispatch_entry(10),
        ]);
        upsample.extend(over);
        let mut list = march.to_vec();
        list.push(PixelList::list_entry(9));
        list.extend(over);
        let upsample_variant = |over_model: bool, label| {
            ComputePipeline::with_constants(
                gpu,
                "clouds/frame_upsample.wgsl",
                "main",
                label,
                &upsample,
                &[("OVER_MODEL", f64::from(u8::from(over_model)))],
            )
        };
        let list_variant = |over_model: bool, label| {
            MarchVariants::new("clouds/frame_march_list.wgsl", label, &list)
                .with_constant("OVER_MODEL", f64::from(u8::from(over_model)))
        };
        let mut composite = CompositeInputs::layout_entries().to_vec();
        composite.extend([texture_entry(4, D2), texture_entry(5, D2)]);
        let mut from_taps = composite.clone();
        from_taps.extend([PixelList::list_entry(10), PixelList::dispatch_entry(11)]);
        let mut composite_listed = composite.clone();
        composite_listed.push(PixelList::list_entry(10));
        let composite_shader = "clouds/frame_composite.wgsl";
        let front_rays = [
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            uniform_entry(2, 16),
            storage_texture_entry(3, GEOMETRY_FORMAT, D2),
            storage_texture_entry(4, TRANSMITTANCE_FORMAT, D2),
        ];
        Ok(CloudFramePass {
            march: MarchVariants::new("clouds/frame_march.wgsl", "cloud frame march", &march),
            march_reduced: MarchVariants::new(
                "clouds/frame_march_reduced.wgsl",
                "cloud frame reduced march",
                &reduced,
            ),
            upsample: upsample_variant(false, "cloud frame upsample")?,
            march_list: list_variant(false, "cloud frame listed march"),
            upsample_over: upsample_variant(true, "cloud frame upsample over the model")?,
            march_list_over: list_variant(true, "cloud frame listed march over the model"),
            composite: ComputePipeline::new(
                gpu,
                composite_shader,
                "main",
                "cloud composite",
                &composite,
            )?,
            composite_from_taps: [
                LazyPipeline::new(
                    (composite_shader, "from_taps"),
                    "cloud composite from taps",
                    &from_taps,
                ),
                LazyPipeline::new(
                    (composite_shader, "listed"),
                    "cloud composite, listed pixels",
                    &composite_listed,
                ),
            ],
            front_rays: ComputePipeline::new(
                gpu,
                "clouds/front_rays.wgsl",
                "main",
                "cloud front reduced rays",
                &front_rays,
            )?,
            spheres: FrameSpherePass::new(gpu)?,
            params: uniform_buffer(&gpu.device, "cloud frame", size_of::<LayerUniform>()),
            flags: uniform_buffer(&gpu.device, "cloud frame flags", 16),
        })
    }

    /// Records the cloud steps of `scene` planned in `steps`: the march, then the spheres
    /// (which read the march where they blend with it), each timed by `timer` in its
    /// step's slot.
    pub fn encode_clouds(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &MarchScene<'_>,
        targets: &CloudTargets,
        (steps, timer): (&CloudSteps, Option<&GpuTimer>),
    ) -> Result<(), RenderError> {
        let flags = [
            u32::from(scene.has_surface),
            u32::from(scene.has_front),
            steps.front_divisor,
            0,
        ];
        gpu.write_uniform(&self.flags, &flags);
        if let Some(march) = steps.march {
            let writes = timer.map(|t| t.compute_writes(march));
            let over = steps.composite_in_upsample;
            self.encode_march(gpu, encoder, (scene, over), targets, writes)?;
        }
        let Some(step) = steps.spheres else {
            return Ok(());
        };
        let frame = scene.frame;
        let spheres = SphereScene {
            camera: frame_camera(frame),
            layer: &scene.clouds.settings,
            spheres: &scene.clouds.spheres,
            light: &scene.clouds.light,
            bottom_radius_m: frame.atmosphere.bottom_radius_m,
            cache: &scene.inputs.spheres,
            surface: scene.surface,
            has_surface: scene.has_surface,
            weight: steps.weight,
        };
        let composite = steps.composite_in_spheres.then(|| {
            let textures = targets.composite_textures(steps.front_divisor, scene.hdr);
            CompositeInputs::new(scene.uniforms, &self.flags, textures)
        });
        let images = SphereImages {
            layer: &targets.cloud,
            out: &targets.spheres,
            front: &targets.front_geometry,
            reduced: targets.spheres_reduced.as_ref(),
            composite: composite.as_ref(),
        };
        let writes = timer.map(|t| t.compute_writes(step));
        self.spheres.encode(gpu, encoder, &spheres, &images, writes)
    }

    /// Records the march of `scene`'s pixels into `targets.cloud` and
    /// `targets.front_geometry`: at full resolution, or reduced and brought to full size
    /// when the settings' resolution divisor is above 1 (timed from the march's start to
    /// the listed pixels' end), composited over the model's pixels into the HDR target
    /// instead when `over`.
    fn encode_march(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        (scene, over): (&MarchScene<'_>, bool),
        targets: &CloudTargets,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        let frame = scene.frame;
        let params = LayerUniform::new(
            &frame_camera(frame),
            &scene.clouds.light,
            &scene.clouds.settings,
            frame.atmosphere.bottom_radius_m,
            scene.inputs.cover_size,
        )?;
        gpu.write_uniform(&self.params, &params);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let cover = view(&scene.inputs.cover);
        let cloud = view(&targets.cloud);
        let front = view(&targets.front_geometry);
        let map = view(scene.sun_map.texture());
        let shared = [
            (0, self.params.as_entire_binding()),
            (1, wgpu::BindingResource::TextureView(&cover)),
            (2, scene.inputs.orders.as_entire_binding()),
            (4, wgpu::BindingResource::TextureView(scene.surface)),
            (6, self.flags.as_entire_binding()),
            scene.sun_map.bindings()[1].clone(),
            (SUN_MAP_BINDING, wgpu::BindingResource::TextureView(&map)),
        ];
        let full = [
            (3, wgpu::BindingResource::TextureView(&cloud)),
            (5, wgpu::BindingResource::TextureView(&front)),
        ];
        let divisor = scene.clouds.settings.resolution_divisor;
        if divisor <= 1 {
            let march = self.march.for_params(gpu, &params)?;
            let bind_group = march.bind_group_numbered(gpu, &[shared.as_slice(), &full].concat());
            march.dispatch(
                encoder,
                "cloud frame march",
                &bind_group,
                texel_groups(&targets.cloud),
                timestamps,
            );
            return Ok(());
        }
        let Some([image, segments]) = targets
            .reduced
            .as_ref()
            .filter(|_| targets.divisor == divisor)
        else {
            return Err(RenderError::Frame(format!(
                "the cloud targets were made for resolution divisor {}, not {divisor}",
                targets.divisor
            )));
        };
        let groups = texel_groups(image);
        let (image, segments) = (view(image), view(segments));
        let (start, end) = split_timestamps(timestamps);
        let reduced = [
            (3, wgpu::BindingResource::TextureView(&image)),
            (7, wgpu::BindingResource::TextureView(&segments)),
        ];
        let march_reduced = self.march_reduced.for_params(gpu, &params)?;
        let bind_group =
            march_reduced.bind_group_numbered(gpu, &[shared.as_slice(), &reduced].concat());
        march_reduced.dispatch(
            encoder,
            "cloud frame reduced march",
            &bind_group,
            groups,
            start,
        );
        let kept = targets.march_list.as_ref().map_err(|e| {
            RenderError::Frame(format!(
                "clouds at a reduced resolution: {e}; use the offline quality \
                 (resolution divisor 1) or a smaller frame"
            ))
        })?;
        kept.reset(gpu);
        let PixelList { list, dispatch, .. } = kept;
        let (model_pixels, hdr) = (view(scene.model_pixels), view(scene.hdr));
        let read = [
            (7, wgpu::BindingResource::TextureView(&image)),
            (8, wgpu::BindingResource::TextureView(&segments)),
            (9, list.as_entire_binding()),
            (10, dispatch.as_entire_binding()),
        ];
        let composited = [
            (11, wgpu::BindingResource::TextureView(&model_pixels)),
            (12, wgpu::BindingResource::TextureView(&hdr)),
        ];
        let (upsample, march_list) = match over {
            true => (&self.upsample_over, &self.march_list_over),
            false => (&self.upsample, &self.march_list),
        };
        let bind_group = upsample.bind_group_numbered(
            gpu,
            &[shared.as_slice(), &full, &read, &composited].concat(),
        );
        upsample.dispatch(
            encoder,
            "cloud frame upsample",
            &bind_group,
            texel_groups(&targets.cloud),
            None,
        );
        let listed = [(9, list.as_entire_binding())];
        let march_list = march_list.for_params(gpu, &params)?;
        let bind_group = march_list.bind_group_numbered(
            gpu,
            &[shared.as_slice(), &full, &listed, &composited].concat(),
        );
        march_list.dispatch_indirect(
            encoder,
            "cloud frame listed march",
            &bind_group,
            dispatch,
            end,
        );
        Ok(())
    }

    /// Records the composite of `targets` into `hdr`, with the frame's `atmosphere` and
    /// `frame` uniforms (after [`CloudFramePass::encode_clouds`], whose flags it reads),
    /// taking the spheres' image when `steps` ran them and the model's reduced run in
    /// front of the cloud when it ran reduced (`frame_front.rs`): from its taps, the
    /// pixels that need more listed for a pass of their own (timed from the first's
    /// start to the second's end).
    pub fn encode_composite(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        uniforms: (&wgpu::Buffer, &wgpu::Buffer),
        (targets, steps): (&CloudTargets, &CloudSteps),
        hdr: &wgpu::Texture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        let textures = targets.composite_textures(steps.front_divisor, hdr);
        let inputs = CompositeInputs::new(uniforms, &self.flags, textures);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let cloud = view(match steps.spheres {
            Some(_) => &targets.spheres,
            None => &targets.cloud,
        });
        let geometry = view(&targets.front_geometry);
        let read = [
            (4, wgpu::BindingResource::TextureView(&cloud)),
            (5, wgpu::BindingResource::TextureView(&geometry)),
        ];
        let bindings = [inputs.bindings().as_slice(), &read].concat();
        let list = targets.composite_list.as_ref().ok();
        let Some(list) = list.filter(|_| steps.front_divisor > 1) else {
            let bind_group = self.composite.bind_group_numbered(gpu, &bindings);
            self.composite.dispatch(
                encoder,
                "cloud composite",
                &bind_group,
                texel_groups(hdr),
                timestamps,
            );
            return Ok(());
        };
        let [from_taps, listed] = &self.composite_from_taps;
        let (from_taps, listed) = (from_taps.get(gpu)?, listed.get(gpu)?);
        list.reset(gpu);
        let (start, end) = split_timestamps(timestamps);
        let lists = [
            (10, list.list.as_entire_binding()),
            (11, list.dispatch.as_entire_binding()),
        ];
        let bind_group =
            from_taps.bind_group_numbered(gpu, &[bindings.as_slice(), &lists].concat());
        from_taps.dispatch(
            encoder,
            "cloud composite from taps",
            &bind_group,
            texel_groups(hdr),
            start,
        );
        let bind_group =
            listed.bind_group_numbered(gpu, &[bindings.as_slice(), &lists[..1]].concat());
        listed.dispatch_indirect(
            encoder,
            "cloud composite, listed pixels",
            &bind_group,
            &list.dispatch,
            end,
        );
        Ok(())
    }
}
