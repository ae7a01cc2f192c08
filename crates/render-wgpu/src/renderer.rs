//! The `Renderer`: owns the GPU context, the tables and the passes for the life of the
//! program, and renders [`Frame`]s into an HDR target (spectral radiance at 680, 550 and
//! 440 nm, `Rgba16Float`) tone-mapped to an `Rgba8UnormSrgb` image. Headless for now: the
//! tone map writes into the renderer's own texture; a window's surface view can take its
//! place (`ToneMapPass::encode` takes any view).

use atmosphere_core::model::MODEL_IDS;
use atmosphere_core::nishita::NishitaSettings;

use crate::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::device::GpuContext;
use crate::error::{GpuError, RenderError};
use crate::frame::Frame;
use crate::frame_plan::FramePlan;
use crate::frame_uniform::FrameUniform;
use crate::gpu_timer::GpuTimer;
use crate::nishita_pass::{HDR_FORMAT, NishitaInputs, NishitaPass, NishitaUniform};
use crate::readback::read_texture;
use crate::tone_map::ToneMap;
use crate::tone_map_pass::{LDR_FORMAT, ToneMapPass};
use crate::transmittance_pass::{TableOutput, TransmittancePass};

/// The models the GPU renders.
pub const GPU_MODELS: &[&str] = &["nishita"];

/// Most steps a frame runs (table builds and passes), for the timer.
const MAX_STEPS: u32 = 8;

/// The g_l table and the atmosphere it was last built from (`None`: not yet built).
#[derive(Debug)]
struct BuiltTable {
    pass: TransmittancePass,
    built_from: Option<AtmosphereUniform>,
}

impl BuiltTable {
    fn size(&self) -> (u32, u32) {
        (self.pass.texture().width(), self.pass.texture().height())
    }
}

/// The HDR and display targets of one image size.
#[derive(Debug)]
struct Targets {
    hdr: wgpu::Texture,
    ldr: wgpu::Texture,
}

/// Renders frames; see the module documentation.
#[derive(Debug)]
pub struct Renderer {
    gpu: GpuContext,
    atmosphere: wgpu::Buffer,
    g_l: Option<BuiltTable>,
    nishita: NishitaPass,
    tone_map: ToneMapPass,
    targets: Option<Targets>,
    timer: Option<GpuTimer>,
}

fn target(
    gpu: &GpuContext,
    label: &str,
    format: wgpu::TextureFormat,
    frame: &Frame,
) -> wgpu::Texture {
    let usage = if format == HDR_FORMAT {
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING
    } else {
        wgpu::TextureUsages::RENDER_ATTACHMENT
    };
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: frame.width,
            height: frame.height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: usage | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

impl Renderer {
    /// A renderer on a headless context ([`GpuContext::headless`]).
    pub fn headless() -> Result<Renderer, RenderError> {
        Renderer::new(GpuContext::headless()?)
    }

    /// A renderer on `gpu`: compiles every pass.
    pub fn new(gpu: GpuContext) -> Result<Renderer, RenderError> {
        let atmosphere = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("atmosphere"),
            size: size_of::<AtmosphereUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Ok(Renderer {
            nishita: NishitaPass::new(&gpu)?,
            tone_map: ToneMapPass::new(&gpu)?,
            timer: GpuTimer::new(&gpu, MAX_STEPS),
            atmosphere,
            g_l: None,
            targets: None,
            gpu,
        })
    }

    /// Whether model `id` can be rendered: an error naming it when it is unknown or not
    /// yet on the GPU (no model silently stands in for another).
    pub fn check_model(id: &str) -> Result<(), RenderError> {
        if GPU_MODELS.contains(&id) {
            Ok(())
        } else if MODEL_IDS.contains(&id) {
            Err(RenderError::NotOnGpu(id.to_string()))
        } else {
            Err(atmosphere_core::model::ModelError::UnknownModel(id.to_string()).into())
        }
    }

    /// The GPU context.
    pub fn gpu(&self) -> &GpuContext {
        &self.gpu
    }

    /// Renders `frame` and waits for the GPU; returns the plan with each step's GPU time.
    /// The images stay on the GPU until [`Renderer::read_hdr`] or [`Renderer::read_ldr`].
    pub fn render(&mut self, frame: &Frame) -> Result<FramePlan, RenderError> {
        frame.validate()?;
        Renderer::check_model(&frame.model)?;
        frame
            .atmosphere
            .validate()
            .map_err(atmosphere_core::model::ModelError::from)?;
        frame.settings.validate()?;
        let settings = NishitaSettings::from_options(&frame.settings.options)?;
        let nishita = NishitaUniform::new(&frame.atmosphere, &frame.settings, &settings)?;
        let atmosphere = AtmosphereUniform::new(&frame.atmosphere, RGB_WAVELENGTHS_NM)?;
        let tone_map = ToneMap::new(RGB_WAVELENGTHS_NM, frame.exposure_ev100)?.uniform();
        let table_size = (settings.table_angles as u32, settings.table_heights as u32);

        let mut g_l = match self.g_l.take() {
            Some(built) if built.size() == table_size => built,
            _ => BuiltTable {
                pass: TransmittancePass::with(
                    &self.gpu,
                    TableOutput::Columns,
                    table_size.0,
                    table_size.1,
                )?,
                built_from: None,
            },
        };
        let mut plan = FramePlan::nishita(g_l.built_from != Some(atmosphere));
        let targets = match self.targets.take() {
            Some(t) if (t.hdr.width(), t.hdr.height()) == (frame.width, frame.height) => t,
            _ => Targets {
                hdr: target(&self.gpu, "hdr", HDR_FORMAT, frame),
                ldr: target(&self.gpu, "ldr", LDR_FORMAT, frame),
            },
        };

        let gpu = &self.gpu;
        let timer = self.timer.as_ref();
        gpu.queue
            .write_buffer(&self.atmosphere, 0, bytemuck::bytes_of(&atmosphere));
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        let mut index = 0;
        for step in &plan.steps {
            match step.name {
                "g_l" => {
                    g_l.pass.encode(
                        gpu,
                        &atmosphere,
                        &mut encoder,
                        timer.map(|t| t.compute_writes(index)),
                    );
                    g_l.built_from = Some(atmosphere);
                }
                "nishita" => self.nishita.encode(
                    gpu,
                    &NishitaInputs {
                        atmosphere: &self.atmosphere,
                        frame: &FrameUniform::new(frame),
                        params: &nishita,
                        table: g_l.pass.texture(),
                        hdr: &targets.hdr,
                    },
                    &mut encoder,
                    timer.map(|t| t.compute_writes(index)),
                ),
                "tone_map" => self.tone_map.encode(
                    gpu,
                    &tone_map,
                    &targets.hdr,
                    &targets.ldr.create_view(&Default::default()),
                    &mut encoder,
                    timer.map(|t| t.render_writes(index)),
                ),
                other => unreachable!("the nishita plan has no step {other}"),
            }
            index += 1;
        }
        if let Some(timer) = timer {
            timer.resolve(&mut encoder, index);
        }
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        gpu.queue.submit([encoder.finish()]);
        self.g_l = Some(g_l);
        self.targets = Some(targets);
        if let Some(source) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation {
                what: "the frame's commands",
                source,
            }
            .into());
        }
        if let Some(timer) = timer {
            let times = timer.read(gpu, index)?;
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

    /// The last frame's display image, row-major, 8-bit sRGB with alpha 255.
    pub fn read_ldr(&self) -> Result<Vec<[u8; 4]>, RenderError> {
        let targets = self.last_targets()?;
        let bytes = read_texture(&self.gpu, &targets.ldr, 4)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    fn last_targets(&self) -> Result<&Targets, RenderError> {
        self.targets
            .as_ref()
            .ok_or_else(|| RenderError::Frame("no frame has been rendered yet".into()))
    }
}
