//! The `Renderer`: owns the GPU context, the tables and the passes for the life of the
//! program, and renders [`Frame`]s into an HDR target (spectral radiance at 680, 550 and
//! 440 nm, `Rgba16Float`) tone-mapped to an `Rgba8UnormSrgb` image, the renderer's own
//! texture: read back ([`Renderer::read_ldr`]) or sampled by a window
//! ([`Renderer::ldr_texture`], e.g. as an egui image).

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::hydrometeors::render::LitVolume;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::shafts::{MIN_SHAFT_SAMPLES, SHAFT_SAMPLES};

use crate::clouds::cloud_targets::CloudTargets;
use crate::clouds::frame_clouds::{FrameClouds, plan_after_model, plan_clouds};
use crate::clouds::frame_pass::{CloudFramePass, MarchScene};
use crate::clouds::frame_steps::{AfterModel, encode_after_model};
use crate::clouds::frame_sun_map::FrameSunMap;
use crate::clouds::layer_inputs::LayerInputs;
use crate::clouds::sun_map_pass::PixelInputs;

use crate::frame::Frame;
use crate::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::frame::plan::{FramePlan, StepKind};
use crate::frame::surface_buffer::{SurfaceTexel, check_surface};
use crate::frame::uniform::FrameUniform;
use crate::frame_targets::Targets;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::uniform_buffer;
use crate::gpu::readback::read_texture;
use crate::gpu::timer::GpuTimer;
use crate::post::luminance::LuminancePass;
use crate::post::tone_map::ToneMap;
use crate::post::tone_map_pass::ToneMapPass;
use crate::precipitation::in_view::plan_volumes;
use crate::precipitation::volume_uniform::MAX_VOLUMES;
use crate::precipitation::volumes_pass::{VolumesPass, VolumesScene};
use crate::shafts::terrain::frame_map::FrameShadow;
use crate::shafts::terrain::planner::plan_shafts;
use crate::shafts::terrain::shadow_texture::ShadowTexture;
use crate::sky::model_pass::PassIo;
use crate::sky::registry;
use crate::sky::sky_pass::{FrameRecorder, SkyPass};
use crate::terrain::earth_data::EarthData;
use crate::terrain::pass::TerrainPass;

/// Most steps a frame runs (table builds and passes), for the timer.
const MAX_STEPS: u32 = 24;

/// Renders frames; see the module documentation.
#[derive(Debug)]
pub struct Renderer {
    gpu: GpuContext,
    atmosphere: wgpu::Buffer,
    frame: wgpu::Buffer,
    /// Every model used so far, with its tables.
    models: Vec<(ModelId, Box<dyn SkyPass>)>,
    tone_map: ToneMapPass,
    /// The terrain's maps and chunks, loaded when a frame first asks for terrain.
    terrain: Option<TerrainPass>,
    /// Where the terrain's maps come from.
    earth_data: EarthData,
    luminance: LuminancePass,
    targets: Option<Targets>,
    timer: Option<GpuTimer>,
    /// Whether models may spread their table builds over frames.
    progressive: bool,
    /// The cloud layer frames show ([`Renderer::set_clouds`]); `None`: no clouds.
    clouds: Option<FrameClouds>,
    /// The cover and tables on the GPU, and the cover's largest value
    /// ([`Renderer::set_cloud_inputs`]).
    cloud_inputs: Option<(LayerInputs, f64)>,
    /// The cloud steps, compiled when a frame first has clouds.
    cloud_pass: Option<CloudFramePass>,
    /// The clouds' attenuation of the sun, shading the surface.
    sun_map: FrameSunMap,
    /// The terrain's shadow map for light shafts, and its copy on the GPU.
    shadow: FrameShadow,
    shadow_texture: ShadowTexture,
    /// Whether the planner leaves out shafts that cannot change the image.
    prune_shafts: bool,
    /// Rain and ice volumes frames show ([`Renderer::set_volumes`]), and their pass,
    /// compiled when a frame first has one.
    volumes: Vec<LitVolume>,
    volumes_pass: Option<VolumesPass>,
    /// One pixel in N x N of the volumes marched ([`Renderer::set_volumes_divisor`]).
    volumes_divisor: u32,
}

impl Renderer {
    /// A renderer on a headless context ([`GpuContext::headless`]).
    pub fn headless() -> Result<Renderer, RenderError> {
        Renderer::new(GpuContext::headless()?)
    }

    /// A renderer on `gpu`: compiles the tone map; each model's passes are compiled
    /// when a frame first uses it.
    pub fn new(gpu: GpuContext) -> Result<Renderer, RenderError> {
        Ok(Renderer {
            atmosphere: uniform_buffer(&gpu.device, "atmosphere", size_of::<AtmosphereUniform>()),
            frame: uniform_buffer(&gpu.device, "frame", size_of::<FrameUniform>()),
            models: Vec::new(),
            tone_map: ToneMapPass::new(&gpu)?,
            terrain: None,
            earth_data: EarthData::default(),
            luminance: LuminancePass::new(&gpu, RGB_WAVELENGTHS_NM)?,
            timer: GpuTimer::new(&gpu, MAX_STEPS),
            targets: None,
            progressive: false,
            clouds: None,
            cloud_inputs: None,
            cloud_pass: None,
            sun_map: FrameSunMap::new(&gpu),
            shadow: FrameShadow::default(),
            shadow_texture: ShadowTexture::new(&gpu),
            prune_shafts: true,
            volumes: Vec::new(),
            volumes_pass: None,
            volumes_divisor: 1,
            gpu,
        })
    }

    /// Whether model `id` can be rendered: an error naming it when it is not on the GPU
    /// (no model silently stands in for another).
    pub fn check_model(id: ModelId) -> Result<(), RenderError> {
        registry::check_model(id)
    }

    /// How the last frame with terrain stood with its chunk meshes (`None` before any):
    /// with `TerrainOptions::wait_for_chunks` off, how many it covered and how many are
    /// still being built.
    pub fn terrain_progress(&self) -> Option<crate::terrain::pass::ChunkProgress> {
        self.terrain.as_ref().map(|t| t.progress())
    }

    /// The terrain's elevation (m above the reference sphere) in a unit direction, as
    /// the last frame with terrain drew it; `None` before any.
    pub fn terrain_elevation_m(&self, direction: glam::DVec3) -> Option<f64> {
        self.terrain.as_ref().map(|t| t.elevation_m(direction))
    }

    /// Takes the Earth's maps from `data` (the built-in ones by default): the next frame
    /// with terrain loads them, and any error naming a map comes from that frame.
    pub fn set_earth_data(&mut self, data: EarthData) {
        if data != self.earth_data {
            self.earth_data = data;
            self.terrain = None;
        }
    }

    /// The GPU context.
    pub fn gpu(&self) -> &GpuContext {
        &self.gpu
    }

    /// On: a model may spread a long table build over frames, each frame showing what is
    /// built so far, [`FramePlan::building`] saying what is not yet (bruneton: single
    /// scattering in the first frame, then its orders; the others build in one frame
    /// anyway), so that a window stays interactive while tables rebuild. Off (the
    /// default, for headless renders and tests): every frame shows complete tables.
    /// Turning it off finishes a build under way at the next frame.
    pub fn set_progressive(&mut self, on: bool) {
        self.progressive = on;
        for (_, model) in &mut self.models {
            model.set_progressive(on);
        }
    }

    /// Uploads the cloud layer's `cover` and its multiple-scattering tables `orders` (at
    /// 680, 550 and 440 nm), which frames with clouds read ([`Renderer::set_clouds`]).
    pub fn set_cloud_inputs(
        &mut self,
        cover: &CoverGrid,
        orders: &ScatteringOrders,
    ) -> Result<(), RenderError> {
        let max_cover = cover.values().iter().fold(0.0f32, |m, &v| m.max(v));
        self.cloud_inputs = Some((
            LayerInputs::new(&self.gpu, cover, orders)?,
            f64::from(max_cover),
        ));
        Ok(())
    }

    /// The cloud layer of the frames that follow, composited with every model
    /// (docs/clouds.md, "Clouds in frames"); `None`: no clouds. The settings are checked
    /// here, by name.
    pub fn set_clouds(&mut self, clouds: Option<FrameClouds>) -> Result<(), RenderError> {
        if let Some(c) = &clouds {
            c.settings
                .check()
                .map_err(|e| RenderError::Frame(e.to_string()))?;
        }
        self.clouds = clouds;
        Ok(())
    }

    /// Whether the planner leaves out light shafts that cannot change the image (on by
    /// default; off only to show that leaving them out changes nothing).
    pub fn set_prune_shafts(&mut self, prune: bool) {
        self.prune_shafts = prune;
    }

    /// The terrain's shadow map of the last frame with light shafts (`None` before any).
    pub fn shadow_map(&self) -> Option<&atmosphere_core::shafts::ShadowMap> {
        self.shadow.map()
    }

    /// The rain shafts and cirrus layers of the frames that follow (at most two), lit and
    /// with their phase tables at the frame's wavelengths, composited over every model
    /// (docs/optics-rendering.md); empty: none.
    pub fn set_volumes(&mut self, volumes: Vec<LitVolume>) -> Result<(), RenderError> {
        if volumes.len() > MAX_VOLUMES {
            return Err(RenderError::Frame(format!(
                "{} rain and ice volumes; a frame holds at most {MAX_VOLUMES}",
                volumes.len()
            )));
        }
        self.volumes = volumes;
        Ok(())
    }

    /// The volumes of the frames that follow marched for one pixel in `divisor` x
    /// `divisor` and upsampled where the rays' paths through them agree
    /// (atmosphere-core's `hydrometeors/reduced.rs`): 1 (every pixel, the default) to 4.
    pub fn set_volumes_divisor(&mut self, divisor: u32) -> Result<(), RenderError> {
        self.volumes_divisor = atmosphere_core::hydrometeors::reduced::check_divisor(divisor)
            .map_err(|e| RenderError::Frame(e.to_string()))?;
        Ok(())
    }

    /// Bytes of GPU memory held by the tables of the models used so far.
    pub fn table_bytes(&self) -> u64 {
        self.models.iter().map(|(_, m)| m.table_bytes()).sum()
    }

    /// Renders `frame` and waits for the GPU; returns the plan with each step's GPU time.
    /// The images stay on the GPU until [`Renderer::read_hdr`] or [`Renderer::read_ldr`].
    pub fn render(&mut self, frame: &Frame) -> Result<FramePlan, RenderError> {
        self.render_over(frame, None)
    }

    /// Renders `frame` with its rays ending on `surface` (one texel per pixel,
    /// row-major): geometry drawn elsewhere, lit and seen through the atmosphere by the
    /// frame's model (`surface_buffer.rs`).
    pub fn render_with_surface(
        &mut self,
        frame: &Frame,
        surface: &[SurfaceTexel],
    ) -> Result<FramePlan, RenderError> {
        check_surface(surface, frame.width as usize * frame.height as usize)?;
        self.render_over(frame, Some(surface))
    }

    fn render_over(
        &mut self,
        frame: &Frame,
        surface: Option<&[SurfaceTexel]>,
    ) -> Result<FramePlan, RenderError> {
        frame.validate()?;
        Renderer::check_model(frame.model)?;
        frame
            .atmosphere
            .validate()
            .map_err(atmosphere_core::models::error::ModelError::from)?;
        frame.settings.validate()?;
        let atmosphere = AtmosphereUniform::new(&frame.atmosphere, RGB_WAVELENGTHS_NM)?;
        let mut plan = FramePlan::default();
        // Terrain draws the surface first (step 0), unless the caller gives one.
        let draws_terrain = match (frame.terrain, surface) {
            (Some(options), None) => {
                let terrain = match self.terrain.take() {
                    Some(terrain) => terrain,
                    None => TerrainPass::new(
                        &self.gpu,
                        frame.atmosphere.bottom_radius_m,
                        &self.earth_data,
                    )?,
                };
                let terrain = self.terrain.insert(terrain);
                let chunks = terrain.prepare(&self.gpu, frame, &options)?;
                if chunks == 0 {
                    plan.skip("terrain", "no terrain in view");
                } else {
                    plan.run("terrain", StepKind::Pass);
                }
                chunks > 0
            }
            _ => false,
        };
        let has_surface = surface.is_some() || draws_terrain;
        // Light shafts (docs/shafts.md): the shadow map of the drawn terrain.
        let relief = self
            .terrain
            .as_ref()
            .filter(|_| draws_terrain)
            .map(|t| t.surface());
        let shadow = plan_shafts(
            frame,
            relief,
            &mut self.shadow,
            self.prune_shafts,
            &mut plan,
        )?;
        let shaft_samples = (SHAFT_SAMPLES as u32, MIN_SHAFT_SAMPLES as u32);
        self.shadow_texture.upload(&self.gpu, shadow, shaft_samples);
        // The cloud layer's march (docs/clouds.md, "Clouds in frames"): run unless the
        // planner shows it cannot change the image.
        let max_cover = self.cloud_inputs.as_ref().map(|(_, max)| *max);
        let (clouds_step, front_needed) =
            plan_clouds(frame, self.clouds.as_ref(), max_cover, &mut plan)?;
        if clouds_step.is_some() && self.cloud_pass.is_none() {
            self.cloud_pass = Some(CloudFramePass::new(&self.gpu)?);
        }
        let clouds_run = self.clouds.as_ref().map(|c| (c, clouds_step.is_some()));
        (self.sun_map).plan(&self.gpu, frame, clouds_run, has_surface, &mut plan)?;
        // The model's second run ends on the cloud: a surface, whose passes it needs.
        plan.surface = has_surface || front_needed;
        // The sea's variant of the pixel passes only where the surface holds sea.
        let has_sea = match surface {
            Some(texels) => texels.iter().any(|t| t.water && t.distance_m > 0.0),
            None => draws_terrain && self.terrain.as_ref().is_some_and(|t| t.water_in_view()),
        };
        let frame_uniform = FrameUniform::new(frame, RGB_WAVELENGTHS_NM);
        let tone_map = ToneMap::new(RGB_WAVELENGTHS_NM, frame.exposure_ev100)?.uniform();
        let mut targets = match self.targets.take() {
            Some(t) if (t.hdr.width(), t.hdr.height()) == (frame.width, frame.height) => t,
            _ => Targets::new(&self.gpu, frame.width, frame.height),
        };
        if let (Some(_), Some(clouds)) = (clouds_step, &self.clouds) {
            let divisors = (
                clouds.settings.resolution_divisor,
                clouds.spheres.resolution_divisor,
            );
            if targets
                .clouds
                .as_ref()
                .is_none_or(|c| !c.made_for(divisors.0, divisors.1))
            {
                let size = (frame.width, frame.height);
                targets.clouds = Some(CloudTargets::new(&self.gpu, size, divisors));
            }
        }
        if let Some(texels) = surface {
            targets.surface.upload(&self.gpu, texels);
        }
        let gpu = &self.gpu;
        gpu.write_uniform(&self.atmosphere, &atmosphere);
        gpu.write_uniform(&self.frame, &frame_uniform);

        // The model's passes, made on first use.
        let model = {
            let index = match self.models.iter().position(|(m, _)| *m == frame.model) {
                Some(i) => i,
                None => {
                    let mut pass = registry::create(frame.model, gpu)?;
                    pass.set_progressive(self.progressive);
                    self.models.push((frame.model, pass));
                    self.models.len() - 1
                }
            };
            &mut self.models[index].1
        };
        let planned = model.plan(gpu, frame, &mut plan);
        if let Err(e) = planned {
            self.targets = Some(targets);
            return Err(e);
        }
        // (march, the second run's first step, the composite).
        let cloud_steps = clouds_step.map(|steps| plan_after_model(steps, front_needed, &mut plan));
        let volumes_step = plan_volumes(frame, &self.volumes, &mut plan);
        if volumes_step.is_some() && self.volumes_pass.is_none() {
            match VolumesPass::new(gpu) {
                Ok(pass) => self.volumes_pass = Some(pass),
                Err(e) => {
                    self.targets = Some(targets);
                    return Err(e.into());
                }
            }
        }
        if let (Some(_), Some(pass)) = (volumes_step, self.volumes_pass.as_mut()) {
            pass.fit(gpu, (frame.width, frame.height), self.volumes_divisor);
        }
        let tone_map_step = plan.steps.len() as u32;
        plan.run("tone_map", StepKind::Pass);

        let timer = self.timer.as_ref();
        let surface_views = targets.surface.views();
        // With clouds, the model's pixels go to the cloud steps' `full` image and the
        // composite writes the HDR target.
        let cloud_targets = targets.clouds.as_ref().filter(|_| cloud_steps.is_some());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        if let Some(terrain) = self.terrain.as_ref().filter(|_| draws_terrain) {
            terrain.encode(
                gpu,
                &targets.surface,
                &mut encoder,
                timer.map(|t| t.render_writes(0)),
            );
        }
        // The clouds' shadows first, which the model's passes read.
        if let (Some(_), Some(clouds), Some((inputs, _))) =
            (cloud_steps, &self.clouds, &self.cloud_inputs)
        {
            let pixels = PixelInputs {
                atmosphere: &self.atmosphere,
                frame: &self.frame,
                geometry: &surface_views[0],
                has_surface,
                shadow: &self.shadow_texture,
            };
            let scene = (frame, clouds, inputs);
            let mapped = (self.sun_map).encode(gpu, &mut encoder, scene, pixels, timer);
            if let Err(e) = mapped {
                self.targets = Some(targets);
                return Err(e);
            }
        }
        let io = PassIo {
            atmosphere: &self.atmosphere,
            frame: &self.frame,
            hdr: cloud_targets.map_or(&targets.hdr, |c| &c.full),
            surface: &surface_views,
            has_surface,
            has_sea,
            shadow: &self.shadow_texture,
            sun_map: self.sun_map.texture(),
        };
        model.encode_planned(&mut FrameRecorder {
            gpu,
            io: &io,
            encoder: &mut encoder,
            timer,
        });
        // The cloud over the model's pixels.
        if let (
            Some((steps, front, composite)),
            Some(c),
            Some(pass),
            Some(clouds),
            Some((inputs, _)),
        ) = (
            cloud_steps,
            cloud_targets,
            &self.cloud_pass,
            &self.clouds,
            &self.cloud_inputs,
        ) {
            let scene = MarchScene {
                frame,
                clouds,
                inputs,
                surface: &surface_views[0],
                has_surface,
                has_front: front_needed,
                sun_map: self.sun_map.texture(),
                model_pixels: &c.full,
                hdr: &targets.hdr,
                uniforms: (&self.atmosphere, &self.frame),
            };
            let after = AfterModel {
                pass,
                scene: &scene,
                targets: c,
                io: &io,
                uniform: frame_uniform,
                steps: (steps, front, composite),
            };
            let encoded = encode_after_model(model.as_mut(), gpu, (&mut encoder, timer), &after);
            if let Err(e) = encoded {
                self.targets = Some(targets);
                return Err(e);
            }
        }
        if let (Some(step), Some(pass)) = (volumes_step, self.volumes_pass.as_ref()) {
            let scene = VolumesScene {
                frame,
                volumes: &self.volumes,
                uniforms: (&self.atmosphere, &self.frame),
                surface: &surface_views[0],
                has_surface,
                divisor: self.volumes_divisor,
            };
            let encoded = pass.encode(
                gpu,
                &mut encoder,
                &scene,
                &targets.hdr,
                timer.map(|t| t.compute_writes(step)),
            );
            if let Err(e) = encoded {
                self.targets = Some(targets);
                return Err(e);
            }
        }
        self.tone_map.encode(
            gpu,
            &tone_map,
            &targets.hdr,
            &targets.ldr.create_view(&Default::default()),
            &mut encoder,
            timer.map(|t| t.render_writes(tone_map_step)),
        );
        let steps = plan.steps.len() as u32;
        if let Some(timer) = timer {
            timer.resolve(&mut encoder, steps);
        }
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        gpu.queue.submit([encoder.finish()]);
        self.targets = Some(targets);
        if let Some(source) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation {
                what: "the frame's commands",
                source,
            }
            .into());
        }
        if let Some(timer) = timer {
            let times = timer.read(gpu, steps)?;
            for (step, ms) in plan.steps.iter_mut().zip(times) {
                step.gpu_ms = Some(ms);
            }
        } else {
            gpu.device
                .poll(wgpu::PollType::wait_indefinitely())
                .map_err(GpuError::from)?;
        }
        Ok(plan)
    }

    /// The last frame's HDR image, row-major: spectral radiance (W m^-2 sr^-1 nm^-1) at
    /// 680, 550 and 440 nm as stored in f16, alpha 1.
    pub fn read_hdr(&self) -> Result<Vec<[f32; 4]>, RenderError> {
        let targets = self.last_targets()?;
        let bytes = read_texture(&self.gpu, &targets.hdr, 8)?;
        let halves: Vec<u16> = bytemuck::pod_collect_to_vec(&bytes);
        Ok(halves
            .chunks_exact(4)
            .map(|h| std::array::from_fn(|c| half::f16::from_bits(h[c]).to_f32()))
            .collect())
    }

    /// The last frame's log-average luminance in cd/m^2 over its lit pixels, for
    /// automatic exposure (a small compute pass; see [`crate::post::luminance`]).
    pub fn average_luminance(&self) -> Result<f64, RenderError> {
        let targets = self.last_targets()?;
        self.luminance.measure(&self.gpu, &targets.hdr)
    }

    /// The last frame's surface buffer, row-major: what its rays ended on (drawn terrain,
    /// or the caller's surface; unspecified for a frame with neither).
    pub fn read_surface(&self) -> Result<Vec<SurfaceTexel>, RenderError> {
        let targets = self.last_targets()?;
        let geometry: Vec<[f32; 4]> =
            bytemuck::pod_collect_to_vec(&read_texture(&self.gpu, &targets.surface.geometry, 16)?);
        let albedo = read_texture(&self.gpu, &targets.surface.albedo, 4)?;
        Ok(geometry
            .iter()
            .zip(albedo.chunks_exact(4))
            .map(|(g, a)| SurfaceTexel {
                normal: [g[0], g[1], g[2]],
                distance_m: g[3],
                albedo: [a[0], a[1], a[2]].map(|v| f32::from(v) / 255.0),
                water: a[3] < 128,
            })
            .collect())
    }

    /// The last frame's display image, row-major, 8-bit sRGB with alpha 255.
    pub fn read_ldr(&self) -> Result<Vec<[u8; 4]>, RenderError> {
        let targets = self.last_targets()?;
        let bytes = read_texture(&self.gpu, &targets.ldr, 4)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// The last frame's display image on the GPU (`Rgba8UnormSrgb`, sampleable), if a
    /// frame has been rendered. A frame of another size replaces the texture.
    pub fn ldr_texture(&self) -> Option<&wgpu::Texture> {
        self.targets.as_ref().map(|t| &t.ldr)
    }

    fn last_targets(&self) -> Result<&Targets, RenderError> {
        self.targets
            .as_ref()
            .ok_or_else(|| RenderError::Frame("no frame has been rendered yet".into()))
    }
}
