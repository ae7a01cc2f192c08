//! The riley model on the GPU: no table, one per-pixel pass (`shaders/sky/riley/pixel.wgsl`) that
//! evaluates Riley et al.'s closed form with the species atmosphere-core's `riley.rs`
//! fits (one exponential each for Rayleigh and Mie), given in [`RileyUniform`].

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::riley::Riley;
use atmosphere_core::models::sky_model::ModelSettings;
use bytemuck::{Pod, Zeroable};

use crate::frame::Frame;
use crate::frame::atmosphere_uniform::check_wavelengths;
use crate::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::frame::plan::{FramePlan, StepKind};
use crate::frame::surface_buffer::SurfaceBuffer;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{
    PixelPipeline, storage_texture_entry, texel_groups, uniform_buffer, uniform_entry,
};
use crate::sky::model_pass::{ModelPass, PassIo};

/// WGSL `RileyParams`, 80 bytes: the fitted species.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct RileyUniform {
    /// x: Rayleigh, y: Mie scale height, m; zw: 0.
    pub scale_heights_m: [f32; 4],
    /// Extinction at the ground per channel (xyz), m^-1; Mie's is zero when pruned.
    pub rayleigh_extinction_per_m: [f32; 4],
    pub mie_extinction_per_m: [f32; 4],
    /// Scattering / extinction per channel (xyz).
    pub rayleigh_albedo: [f32; 4],
    pub mie_albedo: [f32; 4],
}

impl RileyUniform {
    /// The species of the CPU model `riley`, prepared at the GPU's wavelengths.
    pub fn new(riley: &Riley) -> RileyUniform {
        let (rayleigh, mie) = riley.species();
        let v4 = |v: &[f64]| [v[0] as f32, v[1] as f32, v[2] as f32, 0.0];
        let zero = [0.0; 4];
        RileyUniform {
            scale_heights_m: [
                rayleigh.scale_height_m as f32,
                mie.map_or(0.0, |m| m.scale_height_m as f32),
                0.0,
                0.0,
            ],
            rayleigh_extinction_per_m: v4(&rayleigh.extinction),
            mie_extinction_per_m: mie.map_or(zero, |m| v4(&m.extinction)),
            rayleigh_albedo: v4(&rayleigh.albedo),
            mie_albedo: mie.map_or(zero, |m| v4(&m.albedo)),
        }
    }
}

/// Pipeline and uniform, made once; the fit is redone only when the atmosphere or the
/// pruning changes.
#[derive(Debug)]
pub struct RileyPass {
    pipeline: PixelPipeline,
    params: wgpu::Buffer,
    /// What the uploaded uniform was fitted from.
    fitted_from: Option<(Atmosphere, bool)>,
}

impl RileyPass {
    pub fn new(gpu: &GpuContext) -> Result<RileyPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let surface_entries = SurfaceBuffer::layout_entries();
        let pipeline = PixelPipeline::new(
            gpu,
            "sky/riley/pixel.wgsl",
            "main",
            "the riley pass",
            &[
                uniform_entry(0, size_of::<AtmosphereUniform>()),
                uniform_entry(1, size_of::<FrameUniform>()),
                uniform_entry(2, size_of::<RileyUniform>()),
                storage_texture_entry(3, HDR_FORMAT, D2),
                surface_entries[0],
                surface_entries[1],
            ],
        )?;
        Ok(RileyPass {
            params: uniform_buffer(&gpu.device, "riley", size_of::<RileyUniform>()),
            pipeline,
            fitted_from: None,
        })
    }
}

impl ModelPass for RileyPass {
    fn plan(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        plan: &mut FramePlan,
    ) -> Result<(), RenderError> {
        check_wavelengths(&frame.settings.wavelengths_nm)?;
        frame.settings.options.reader("riley").finish()?;
        let key = (frame.atmosphere.clone(), frame.settings.prune);
        if self.fitted_from.as_ref() != Some(&key) {
            let settings = ModelSettings {
                wavelengths_nm: RGB_WAVELENGTHS_NM.to_vec(),
                prune: frame.settings.prune,
                ..ModelSettings::default()
            };
            let uniform = RileyUniform::new(&Riley::prepare(&frame.atmosphere, &settings));
            gpu.queue
                .write_buffer(&self.params, 0, bytemuck::bytes_of(&uniform));
            self.fitted_from = Some(key);
        }
        plan.run("riley", StepKind::Pass);
        Ok(())
    }

    fn encode(
        &mut self,
        step: &'static str,
        gpu: &GpuContext,
        io: &PassIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        assert_eq!(step, "riley", "the riley plan has no step {step}");
        let hdr = io.hdr.create_view(&Default::default());
        let pipeline = self.pipeline.variant(io.has_surface);
        let bind_group = pipeline.pixel_bind_group(
            gpu,
            &[
                io.atmosphere.as_entire_binding(),
                io.frame.as_entire_binding(),
                self.params.as_entire_binding(),
                wgpu::BindingResource::TextureView(&hdr),
            ],
            io.surface,
        );
        let groups = texel_groups(io.hdr);
        pipeline.dispatch(encoder, "riley", &bind_group, groups, timestamps);
    }

    fn table_bytes(&self) -> u64 {
        0
    }
}
