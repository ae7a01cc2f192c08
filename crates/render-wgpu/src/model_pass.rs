//! One sky model on the GPU: its tables (kept between frames, rebuilt only when an input
//! they depend on changed) and its per-pixel pass into the HDR target. The
//! [`crate::Renderer`] keeps one per model used, so switching models and back rebuilds
//! nothing. Every model's shader binds the atmosphere at binding 0 and the frame at
//! binding 1 (`atmosphere_params.wgsl`, `frame_params.wgsl`); its own resources follow,
//! and its pixel pass reads the frame's surface at bindings 30 and 31 (`surface.wgsl`).

use atmosphere_core::model::MODEL_IDS;

use crate::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::bruneton_pass::BrunetonPass;
use crate::device::GpuContext;
use crate::dobashi_pass::DobashiPass;
use crate::error::RenderError;
use crate::frame::Frame;
use crate::frame_plan::FramePlan;
use crate::frame_uniform::FrameUniform;
use crate::hillaire_pass::HillairePass;
use crate::nishita_pass::HDR_FORMAT;
use crate::nishita_pass::NishitaPass;
use crate::oneil_pass::OneilPass;
use crate::pipeline::uniform_buffer;
use crate::riley_pass::RileyPass;
use crate::surface_buffer::SurfaceBuffer;

/// The models the GPU renders, by id.
pub const GPU_MODELS: &[&str] = &[
    "bruneton", "dobashi", "hillaire", "nishita", "oneil", "riley",
];

/// What a model's steps read and write besides their own tables.
#[derive(Debug)]
pub struct PassIo<'a> {
    /// `AtmosphereUniform` (binding 0 of every model shader).
    pub atmosphere: &'a wgpu::Buffer,
    /// `FrameUniform` (binding 1).
    pub frame: &'a wgpu::Buffer,
    /// The HDR target, of [`crate::nishita_pass::HDR_FORMAT`].
    pub hdr: &'a wgpu::Texture,
    /// Views of the frame's surface buffer (`surface_buffer.rs`), bound by every pixel
    /// pass at bindings 30 and 31.
    pub surface: &'a [wgpu::TextureView; 2],
    /// Whether the frame has a surface: which variant of a `PixelPipeline` runs.
    pub has_surface: bool,
}

/// What a model's table steps read when they run outside a `Renderer` frame (tests and
/// profiling): the uniforms of a frame, and a 1x1 HDR target and surface, which they do
/// not touch.
#[derive(Debug)]
pub struct StandaloneInputs {
    atmosphere: wgpu::Buffer,
    frame: wgpu::Buffer,
    hdr: wgpu::Texture,
    surface: [wgpu::TextureView; 2],
}

impl StandaloneInputs {
    pub fn new(gpu: &GpuContext, atmosphere: &AtmosphereUniform, frame: &Frame) -> Self {
        let inputs = StandaloneInputs {
            atmosphere: uniform_buffer(&gpu.device, "atmosphere", size_of::<AtmosphereUniform>()),
            frame: uniform_buffer(&gpu.device, "frame", size_of::<FrameUniform>()),
            hdr: gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("unused"),
                size: wgpu::Extent3d::default(),
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: HDR_FORMAT,
                usage: wgpu::TextureUsages::STORAGE_BINDING,
                view_formats: &[],
            }),
            surface: SurfaceBuffer::new(gpu, 1, 1).views(),
        };
        gpu.queue
            .write_buffer(&inputs.atmosphere, 0, bytemuck::bytes_of(atmosphere));
        let frame_uniform = FrameUniform::new(frame, RGB_WAVELENGTHS_NM);
        gpu.queue
            .write_buffer(&inputs.frame, 0, bytemuck::bytes_of(&frame_uniform));
        inputs
    }

    pub fn io(&self) -> PassIo<'_> {
        PassIo {
            atmosphere: &self.atmosphere,
            frame: &self.frame,
            hdr: &self.hdr,
            surface: &self.surface,
            has_surface: false,
        }
    }
}

/// A sky model's tables and passes on the GPU; see the module documentation.
pub trait ModelPass: std::fmt::Debug {
    /// Takes the frame's atmosphere and model settings: checks them (an error names what
    /// the GPU cannot follow), remakes tables whose size changed, uploads the model's
    /// uniforms, and adds to `plan` the table builds this frame needs (those never built
    /// or whose inputs changed), those it skips with why, and the per-pixel pass.
    fn plan(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        plan: &mut FramePlan,
    ) -> Result<(), RenderError>;

    /// Records `step`, one that the last [`ModelPass::plan`] listed, timed by `timestamps`
    /// when given.
    fn encode(
        &mut self,
        step: &'static str,
        gpu: &GpuContext,
        io: &PassIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    );

    /// Whether the model may spread its table builds over frames
    /// ([`crate::Renderer::set_progressive`]); off until set. A model whose tables build
    /// in milliseconds builds them in one frame either way.
    fn set_progressive(&mut self, _on: bool) {}

    /// Bytes of GPU memory held by the model's tables.
    fn table_bytes(&self) -> u64;
}

/// Whether model `id` can be rendered: an error naming it when it is unknown or not yet
/// on the GPU (no model silently stands in for another).
pub fn check_model(id: &str) -> Result<(), RenderError> {
    if GPU_MODELS.contains(&id) {
        Ok(())
    } else if MODEL_IDS.contains(&id) {
        Err(RenderError::NotOnGpu {
            model: id.to_string(),
            on_gpu: GPU_MODELS.join(", "),
        })
    } else {
        Err(atmosphere_core::model::ModelError::UnknownModel(id.to_string()).into())
    }
}

/// The GPU twin of model `id`, its pipelines compiled, no table built yet.
pub fn create(id: &str, gpu: &GpuContext) -> Result<Box<dyn ModelPass>, RenderError> {
    check_model(id)?;
    match id {
        "dobashi" => Ok(Box::new(DobashiPass::new(gpu)?)),
        "nishita" => Ok(Box::new(NishitaPass::new(gpu)?)),
        "bruneton" => Ok(Box::new(BrunetonPass::new(gpu)?)),
        "hillaire" => Ok(Box::new(HillairePass::new(gpu)?)),
        "oneil" => Ok(Box::new(OneilPass::new(gpu)?)),
        "riley" => Ok(Box::new(RileyPass::new(gpu)?)),
        other => unreachable!("GPU_MODELS lists {other} without a pass"),
    }
}
