//! The nishita model (Nishita et al. 1993) on the GPU: the g_l table (the `columns` of
//! the transmittance pass, rebuilt only when the atmosphere's columns or the table size
//! change) and the per-pixel pass of `shaders/sky/nishita/pixel.wgsl`, which writes
//! spectral radiance at the three wavelengths into the HDR target. Its CPU twin is
//! atmosphere-core's `nishita.rs`.

use atmosphere_core::models::nishita::NishitaSettings;
use bytemuck::{Pod, Zeroable};

use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::plan::StepKind;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{texture_entry, uniform_buffer, uniform_entry};
use crate::shafts::terrain::uniform::ShadowMapUniform;
use crate::sky::columns_table::ColumnsTable;
use crate::sky::model_pass::{ModelPass, StepContext, frame_atmosphere};
use crate::sky::pixel_pass::{PixelPass, PixelShader};
use crate::sky::steps::{PassStep, SkyPlan};
use crate::sky::table_limits::table_extent;

/// WGSL `NishitaParams`, 16 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct NishitaUniform {
    pub view_samples: u32,
    pub pad0: u32,
    pub pad1: u32,
    pub pad2: u32,
}

impl NishitaUniform {
    /// The model's settings; fails for a sample count the GPU cannot loop over.
    pub fn new(settings: &NishitaSettings) -> Result<NishitaUniform, RenderError> {
        Ok(NishitaUniform {
            view_samples: u32::try_from(settings.view_samples).map_err(|_| {
                RenderError::Unsupported(format!("{} view samples", settings.view_samples))
            })?,
            ..Default::default()
        })
    }
}

/// The model's steps: the g_l table and the pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NishitaStep {
    GL,
    Pass,
}

impl PassStep for NishitaStep {
    fn name(self) -> &'static str {
        match self {
            NishitaStep::GL => "g_l",
            NishitaStep::Pass => "nishita",
        }
    }

    fn kind(self) -> StepKind {
        match self {
            NishitaStep::GL => StepKind::TableBuild,
            NishitaStep::Pass => StepKind::Pass,
        }
    }
}

/// The table's (width, height) for `settings`: sun angles by heights.
fn table_size(settings: &NishitaSettings) -> (u32, u32) {
    (settings.table_angles as u32, settings.table_heights as u32)
}

/// Pipeline, uniform and table, made once; the table is remade when its size changes.
#[derive(Debug)]
pub struct NishitaPass {
    pass: PixelPass,
    params: wgpu::Buffer,
    g_l: ColumnsTable,
    /// The atmosphere of the frame being planned, in the GPU's layout.
    atmosphere: AtmosphereUniform,
}

impl NishitaPass {
    /// The pipeline and an unbuilt table of the default settings' size.
    pub fn new(gpu: &GpuContext) -> Result<NishitaPass, GpuError> {
        let pass = PixelPass::new(
            gpu,
            PixelShader {
                path: "sky/nishita/pixel.wgsl",
                entry: "main",
                label: "the nishita pass",
                params_size: size_of::<NishitaUniform>(),
                tables: &[
                    texture_entry(3, wgpu::TextureViewDimension::D2),
                    texture_entry(4, wgpu::TextureViewDimension::D2),
                    uniform_entry(5, size_of::<ShadowMapUniform>()),
                ],
                sampling: None,
            },
        )?;
        Ok(NishitaPass {
            params: uniform_buffer(&gpu.device, "nishita", size_of::<NishitaUniform>()),
            pass,
            g_l: ColumnsTable::new(gpu, table_size(&NishitaSettings::default()))?,
            atmosphere: AtmosphereUniform::default(),
        })
    }
}

impl ModelPass for NishitaPass {
    type Step = NishitaStep;

    fn plan(&mut self, plan: &mut SkyPlan<'_, NishitaStep>) -> Result<(), RenderError> {
        let (gpu, frame) = (plan.gpu, plan.frame);
        self.atmosphere = frame_atmosphere(frame)?;
        let settings = NishitaSettings::from_options(&frame.settings.options)?;
        let params = NishitaUniform::new(&settings)?;
        let size = (settings.table_angles, settings.table_heights, 1);
        let sides = "table_angles x table_heights";
        table_extent(gpu, "nishita g_l", sides, wgpu::TextureDimension::D2, size)?;
        self.g_l.fit(gpu, table_size(&settings))?;
        plan.build_if(NishitaStep::GL, self.g_l.plan(&frame.atmosphere));
        plan.run(NishitaStep::Pass);
        gpu.write_uniform(&self.params, &params);
        Ok(())
    }

    fn encode(&mut self, step: NishitaStep, cx: StepContext<'_>) {
        match step {
            NishitaStep::GL => self.g_l.encode(&self.atmosphere, cx),
            NishitaStep::Pass => {
                let table = self.g_l.texture().create_view(&Default::default());
                let shadow = cx.io.shadow.view();
                let tables = [
                    wgpu::BindingResource::TextureView(&table),
                    wgpu::BindingResource::TextureView(&shadow),
                    cx.io.shadow.params().as_entire_binding(),
                ];
                self.pass.encode(cx, &self.params, &tables);
            }
        }
    }

    fn table_bytes(&self) -> u64 {
        self.g_l.bytes()
    }
}
