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
//! the band, and the composite reads their image.

use crate::clouds::frame_clouds::{CloudSteps, FRONT_GRID_SCALE, FrameClouds};
use crate::clouds::front_targets::{ReducedFrontTargets, TRANSMITTANCE_FORMAT};
use crate::clouds::layer_inputs::LayerInputs;
use crate::clouds::layer_uniform::{LayerCamera, LayerUniform};
use crate::clouds::march_variants::MarchVariants;
use crate::clouds::spheres::frame_spheres::{FrameSpherePass, SphereImages, SphereScene};
use crate::clouds::spheres::reduced_targets::ReducedSphereTargets;
use crate::clouds::sun_map_texture::{SUN_MAP_BINDING, SunMapTexture};
use crate::frame::Frame;
use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::surface_buffer::{GEOMETRY_FORMAT, black_albedo};
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{
    ComputePipeline, read_only_storage_buffer_entry, split_timestamps, storage_texture_entry,
    texel_groups, texture_2d, texture_entry, uniform_buffer, uniform_entry,
};
use crate::gpu::pixel_list::PixelList;
use crate::gpu::timer::GpuTimer;
use atmosphere_core::clouds::layer::upsample::reduced_size;

const CLOUD_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// The reduced march's segments, (t0, t1) per ray.
const SEGMENT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Float;

/// The images (and the list of pixels to march) of one frame size the cloud steps write
/// and read.
#[derive(Debug)]
pub struct CloudTargets {
    /// The model's pixels, whole (L_full).
    pub full: wgpu::Texture,
    /// The model's pixels ended at the cloud (L_front).
    pub front: wgpu::Texture,
    /// The cloud's radiance (rgb) and transmittance (a) of the layer's march.
    pub cloud: wgpu::Texture,
    /// The same of the spheres (blended with the march in the hand-over band).
    pub spheres: wgpu::Texture,
    /// The second run's surface: the cloud's entry (`surface_buffer.rs`'s layout).
    pub front_geometry: wgpu::Texture,
    /// Its albedo: 0, Lambertian.
    pub front_albedo: wgpu::Texture,
    /// The pixels a reduced march's upsample leaves to the listed march, or why the
    /// device cannot hold a list of this size.
    pub march_list: Result<PixelList, String>,
    /// The resolution divisor these were made for, and above 1 the reduced march's
    /// image and segments.
    pub divisor: u32,
    reduced: Option<[wgpu::Texture; 2]>,
    /// The spheres' reduced images, where their resolution divisor is above 1.
    pub spheres_reduced: Option<ReducedSphereTargets>,
    /// The model's reduced runs in front of the cloud (`frame_front.rs`), one for each
    /// of the layer's and the spheres' divisors above 1.
    pub front_reduced: Vec<ReducedFrontTargets>,
}

impl CloudTargets {
    /// The targets of a frame of `width` x `height` whose layer is marched at one pixel
    /// in `divisor` x `divisor` and whose spheres are shaded at one in
    /// `spheres_divisor` x `spheres_divisor`.
    pub fn new(
        gpu: &GpuContext,
        (width, height): (u32, u32),
        (divisor, spheres_divisor): (u32, u32),
    ) -> CloudTargets {
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let image = |label, format| texture_2d(&gpu.device, label, (width, height), format, usage);
        let front_albedo = black_albedo(gpu, "cloud front albedo", (width, height));
        let mut targets = CloudTargets {
            full: image("cloud full", HDR_FORMAT),
            front: image("cloud front", HDR_FORMAT),
            cloud: image("cloud image", CLOUD_FORMAT),
            spheres: image("cloud spheres image", CLOUD_FORMAT),
            front_geometry: image("cloud front geometry", GEOMETRY_FORMAT),
            front_albedo,
            march_list: PixelList::new(gpu, "cloud frame", (width, height)),
            divisor,
            reduced: (divisor > 1).then(|| {
                let size = reduced_size(width, height, divisor);
                [
                    texture_2d(
                        &gpu.device,
                        "cloud reduced image",
                        size,
                        CLOUD_FORMAT,
                        usage,
                    ),
                    texture_2d(
                        &gpu.device,
                        "cloud reduced segments",
                        size,
                        SEGMENT_FORMAT,
                        usage,
                    ),
                ]
            }),
            spheres_reduced: (spheres_divisor > 1)
                .then(|| ReducedSphereTargets::new(gpu, (width, height), spheres_divisor)),
            front_reduced: Vec::new(),
        };
        for cloud_divisor in [divisor, spheres_divisor] {
            let d = FRONT_GRID_SCALE * cloud_divisor;
            if cloud_divisor > 1 && targets.front_reduced(d).is_none() {
                let run = ReducedFrontTargets::new(gpu, (width, height), d);
                targets.front_reduced.push(run);
            }
        }
        targets
    }

    /// The model's reduced run in front of the cloud at `divisor`, if these hold one.
    pub fn front_reduced(&self, divisor: u32) -> Option<&ReducedFrontTargets> {
        self.front_reduced.iter().find(|r| r.divisor == divisor)
    }

    /// Whether these were made for a layer's `divisor` and the spheres'
    /// `spheres_divisor`.
    pub fn made_for(&self, divisor: u32, spheres_divisor: u32) -> bool {
        let spheres = self.spheres_reduced.as_ref().map_or(1, |r| r.divisor);
        self.divisor == divisor && spheres == spheres_divisor.max(1)
    }

    /// Views of the second run's surface, for its `PassIo`.
    pub fn front_surface(&self) -> [wgpu::TextureView; 2] {
        [
            self.front_geometry.create_view(&Default::default()),
            self.front_albedo.create_view(&Default::default()),
        ]
    }
}

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
    composite: ComputePipeline,
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
        let composite = [
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            texture_entry(2, D2),
            texture_entry(3, D2),
            texture_entry(4, D2),
            texture_entry(5, D2),
            storage_texture_entry(6, HDR_FORMAT, D2),
            uniform_entry(7, 16),
            texture_entry(8, D2),
            texture_entry(9, D2),
        ];
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
                "clouds/frame_composite.wgsl",
                "main",
                "cloud composite",
                &composite,
            )?,
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
        let images = SphereImages {
            layer: &targets.cloud,
            out: &targets.spheres,
            front: &targets.front_geometry,
            reduced: targets.spheres_reduced.as_ref(),
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
    /// front of the cloud when it ran reduced (`frame_front.rs`).
    pub fn encode_composite(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        uniforms: (&wgpu::Buffer, &wgpu::Buffer),
        (targets, steps): (&CloudTargets, &CloudSteps),
        hdr: &wgpu::Texture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let reduced = targets.front_reduced(steps.front_divisor);
        let views = [
            view(&targets.full),
            view(reduced.map_or(&targets.front, |r| &r.radiance)),
            view(match steps.spheres {
                Some(_) => &targets.spheres,
                None => &targets.cloud,
            }),
            view(&targets.front_geometry),
            view(hdr),
            view(reduced.map_or(&targets.front_geometry, |r| &r.entries)),
            view(reduced.map_or(&targets.front_geometry, |r| &r.transmittance)),
        ];
        let [full, front, cloud, geometry, out, entries, transmittance] = &views;
        let bind_group = self.composite.bind_group(
            gpu,
            &[
                uniforms.0.as_entire_binding(),
                uniforms.1.as_entire_binding(),
                wgpu::BindingResource::TextureView(full),
                wgpu::BindingResource::TextureView(front),
                wgpu::BindingResource::TextureView(cloud),
                wgpu::BindingResource::TextureView(geometry),
                wgpu::BindingResource::TextureView(out),
                self.flags.as_entire_binding(),
                wgpu::BindingResource::TextureView(entries),
                wgpu::BindingResource::TextureView(transmittance),
            ],
        );
        self.composite.dispatch(
            encoder,
            "cloud composite",
            &bind_group,
            texel_groups(hdr),
            timestamps,
        );
    }
}
