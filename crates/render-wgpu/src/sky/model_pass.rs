//! One sky model on the GPU ([`ModelPass`]): its tables (kept between frames, rebuilt only
//! when an input they depend on changed) and its per-pixel pass into the HDR target, each
//! a typed step. The [`crate::Renderer`] keeps one per model used, so switching models
//! and back rebuilds nothing. Every model's shader binds the atmosphere at binding 0 and
//! the frame at binding 1 (`common/atmosphere_params.wgsl`, `common/frame_params.wgsl`);
//! its own resources follow, and its pixel pass reads the frame's surface at bindings 30
//! and 31 (`common/surface.wgsl`; `crate::sky::pixel_pass`).

use crate::clouds::sun_map_texture::SunMapTexture;
use crate::frame::Frame;
use crate::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM, check_wavelengths};
use crate::frame::surface_buffer::SurfaceBuffer;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::uniform_buffer;
use crate::shafts::terrain::shadow_texture::ShadowTexture;
use crate::sky::steps::{PassStep, SkyPlan};

/// The frame's atmosphere in the GPU's layout, once the frame's wavelengths are checked
/// to be the GPU's channels.
pub fn frame_atmosphere(frame: &Frame) -> Result<AtmosphereUniform, RenderError> {
    check_wavelengths(&frame.settings.wavelengths_nm)?;
    Ok(AtmosphereUniform::new(
        &frame.atmosphere,
        RGB_WAVELENGTHS_NM,
    )?)
}

/// What a model's steps read and write besides their own tables.
#[derive(Debug)]
pub struct PassIo<'a> {
    /// `AtmosphereUniform` (binding 0 of every model shader).
    pub atmosphere: &'a wgpu::Buffer,
    /// `FrameUniform` (binding 1).
    pub frame: &'a wgpu::Buffer,
    /// The HDR target, of [`crate::gpu::formats::HDR_FORMAT`].
    pub hdr: &'a wgpu::Texture,
    /// Views of the frame's surface buffer (`surface_buffer.rs`), bound by every pixel
    /// pass at bindings 30 and 31.
    pub surface: &'a [wgpu::TextureView; 2],
    /// Whether the frame has a surface: which variant of a `PixelPipeline` runs.
    pub has_surface: bool,
    /// Whether that surface holds sea (`shaders/common/sea_surface.wgsl`).
    pub has_sea: bool,
    /// The terrain's shadow map for light shafts (a placeholder with them off).
    pub shadow: &'a ShadowTexture,
    /// The clouds' sun map, bound by every pixel pass at bindings 32 and 33 (a
    /// placeholder without clouds).
    pub sun_map: &'a SunMapTexture,
}

/// Where one step of a model records its work: the GPU, what the frame's steps read and
/// write ([`PassIo`]), the frame's command encoder, and the timestamps to write around
/// the step's compute pass when the frame is timed.
#[derive(Debug)]
pub struct StepContext<'a> {
    pub gpu: &'a GpuContext,
    pub io: &'a PassIo<'a>,
    pub encoder: &'a mut wgpu::CommandEncoder,
    pub timestamps: Option<wgpu::ComputePassTimestampWrites<'a>>,
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
    shadow: ShadowTexture,
    sun_map: SunMapTexture,
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
            shadow: ShadowTexture::new(gpu),
            sun_map: SunMapTexture::new(gpu),
        };
        gpu.write_uniform(&inputs.atmosphere, atmosphere);
        let frame_uniform = FrameUniform::new(frame, RGB_WAVELENGTHS_NM);
        gpu.write_uniform(&inputs.frame, &frame_uniform);
        inputs
    }

    pub fn io(&self) -> PassIo<'_> {
        PassIo {
            atmosphere: &self.atmosphere,
            frame: &self.frame,
            hdr: &self.hdr,
            surface: &self.surface,
            has_surface: false,
            has_sea: false,
            shadow: &self.shadow,
            sun_map: &self.sun_map,
        }
    }
}

/// A sky model on the GPU, its steps typed ([`PassStep`]); see the module documentation.
/// The renderer holds it behind [`crate::sky::sky_pass::SkyPass`].
pub trait ModelPass: std::fmt::Debug {
    /// The model's table builds and passes.
    type Step: PassStep;

    /// Takes the atmosphere and model settings of the plan's frame ([`SkyPlan::frame`]):
    /// checks them (an error names what the GPU cannot follow), remakes tables whose size
    /// changed, uploads the model's uniforms, and adds to `plan` the table builds this
    /// frame needs (those never built or whose inputs changed), those it skips with why,
    /// and the per-pixel pass.
    fn plan(&mut self, plan: &mut SkyPlan<'_, Self::Step>) -> Result<(), RenderError>;

    /// Records `step`, one that the last [`ModelPass::plan`] listed, into `cx`.
    fn encode(&mut self, step: Self::Step, cx: StepContext<'_>);

    /// Whether the model may spread its table builds over frames
    /// ([`crate::Renderer::set_progressive`]); off until set. A model whose tables build
    /// quickly builds them in one frame either way.
    fn set_progressive(&mut self, _on: bool) {}

    /// Bytes of GPU memory held by the model's tables.
    fn table_bytes(&self) -> u64;
}
