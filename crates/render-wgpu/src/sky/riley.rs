//! The riley model on the GPU: no table, one per-pixel pass
//! (`shaders/sky/riley/pixel.wgsl`) that evaluates the closed form of Riley et al. 2004
//! over the pieces of each ray, with the species atmosphere-core's `models/riley/` fits
//! (one exponential each for Rayleigh, Mie and ozone) and the model's settings, given in
//! [`RileyUniform`].

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::riley::{Riley, RileySettings, Species};
use atmosphere_core::models::sky_model::ModelSettings;
use bytemuck::{Pod, Zeroable};

use crate::frame::atmosphere_uniform::{RGB_WAVELENGTHS_NM, check_wavelengths};
use crate::frame::plan::StepKind;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::uniform_buffer;
use crate::sky::model_pass::{ModelPass, StepContext};
use crate::sky::pixel_pass::{PixelPass, PixelShader};
use crate::sky::steps::{PassStep, SkyPlan};

/// WGSL `RileyParams`, 112 bytes: the fitted species and the settings.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct RileyUniform {
    /// x: Rayleigh, y: Mie, z: ozone scale height, m; w: 0.
    pub scale_heights_m: [f32; 4],
    /// Extinction at the ground per channel (xyz), m^-1; Mie's is zero when pruned,
    /// ozone's when left out (`ozone=false`).
    pub rayleigh_extinction_per_m: [f32; 4],
    pub mie_extinction_per_m: [f32; 4],
    pub ozone_extinction_per_m: [f32; 4],
    /// Scattering / extinction per channel (xyz).
    pub rayleigh_albedo: [f32; 4],
    pub mie_albedo: [f32; 4],
    /// x: `sphere`, y: `shared_extinction` (1 true, 0 false), z: `pieces`, w: 0.
    pub options: [u32; 4],
}

impl RileyUniform {
    /// The species and settings of the CPU model `riley`, prepared at the GPU's
    /// wavelengths.
    pub fn new(riley: &Riley) -> RileyUniform {
        let (rayleigh, mie, ozone) = riley.species();
        let settings = riley.settings();
        let v4 = |v: &[f64]| [v[0] as f32, v[1] as f32, v[2] as f32, 0.0];
        let zero = [0.0; 4];
        let height = |s: Option<&Species>| s.map_or(0.0, |s| s.scale_height_m as f32);
        RileyUniform {
            scale_heights_m: [
                rayleigh.scale_height_m as f32,
                height(mie),
                height(ozone),
                0.0,
            ],
            rayleigh_extinction_per_m: v4(&rayleigh.extinction),
            mie_extinction_per_m: mie.map_or(zero, |m| v4(&m.extinction)),
            ozone_extinction_per_m: ozone.map_or(zero, |o| v4(&o.extinction)),
            rayleigh_albedo: v4(&rayleigh.albedo),
            mie_albedo: mie.map_or(zero, |m| v4(&m.albedo)),
            options: [
                u32::from(settings.sphere),
                u32::from(settings.shared_extinction),
                settings.pieces as u32,
                0,
            ],
        }
    }
}

/// The model's one step: the pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RileyStep {
    Pass,
}

impl PassStep for RileyStep {
    fn name(self) -> &'static str {
        "riley"
    }

    fn kind(self) -> StepKind {
        StepKind::Pass
    }
}

/// Pipeline and uniform, made once; the fit is redone only when the atmosphere, the
/// pruning or the model's settings change.
#[derive(Debug)]
pub struct RileyPass {
    pass: PixelPass,
    params: wgpu::Buffer,
    /// What the uploaded uniform was fitted from.
    fitted_from: Option<(Atmosphere, bool, RileySettings)>,
}

impl RileyPass {
    pub fn new(gpu: &GpuContext) -> Result<RileyPass, GpuError> {
        let pass = PixelPass::new(
            gpu,
            PixelShader {
                path: "sky/riley/pixel.wgsl",
                entry: "main",
                label: "the riley pass",
                params_size: size_of::<RileyUniform>(),
                tables: &[],
                sampling: None,
            },
        )?;
        Ok(RileyPass {
            params: uniform_buffer(&gpu.device, "riley", size_of::<RileyUniform>()),
            pass,
            fitted_from: None,
        })
    }
}

impl ModelPass for RileyPass {
    type Step = RileyStep;

    fn plan(&mut self, plan: &mut SkyPlan<'_, RileyStep>) -> Result<(), RenderError> {
        let (gpu, frame) = (plan.gpu, plan.frame);
        check_wavelengths(&frame.settings.wavelengths_nm)?;
        let riley = RileySettings::from_options(&frame.settings.options)?;
        let key = (frame.atmosphere.clone(), frame.settings.prune, riley);
        if self.fitted_from.as_ref() != Some(&key) {
            let settings = ModelSettings {
                wavelengths_nm: RGB_WAVELENGTHS_NM.to_vec(),
                prune: frame.settings.prune,
                ..ModelSettings::default()
            };
            let uniform = RileyUniform::new(&Riley::prepare(&frame.atmosphere, &settings, riley));
            gpu.write_uniform(&self.params, &uniform);
            self.fitted_from = Some(key);
        }
        plan.run(RileyStep::Pass);
        Ok(())
    }

    fn encode(&mut self, step: RileyStep, cx: StepContext<'_>) {
        match step {
            RileyStep::Pass => self.pass.encode(cx, &self.params, &[]),
        }
    }

    fn table_bytes(&self) -> u64 {
        0
    }
}
