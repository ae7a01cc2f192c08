//! The nishita model on the GPU: the g_l table (the `columns` of the transmittance
//! pass, rebuilt only when the atmosphere's columns or the table size change) and the
//! per-pixel pass of `shaders/sky/nishita/pixel.wgsl`, which writes spectral radiance at the three
//! wavelengths into the HDR target. Its CPU twin is atmosphere-core's `nishita.rs`.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::table_inputs::Inputs;
use atmosphere_core::models::nishita::NishitaSettings;
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
    PixelPipeline, storage_texture_entry, texel_groups, texture_entry, uniform_buffer,
    uniform_entry,
};
use crate::sky::model_pass::{ModelPass, PassIo};
use crate::sky::transmittance::{TableOutput, TransmittancePass};

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

/// The g_l table and the atmosphere it was built from (`None`: not yet built).
#[derive(Debug)]
struct GlTable {
    pass: TransmittancePass,
    built_from: Option<Atmosphere>,
}

/// Pipeline, uniform and table, made once; the table is remade when its size changes.
#[derive(Debug)]
pub struct NishitaPass {
    pipeline: PixelPipeline,
    params: wgpu::Buffer,
    g_l: Option<GlTable>,
    /// The atmosphere of the frame being planned, in the GPU's layout.
    atmosphere: AtmosphereUniform,
    pending: Option<Atmosphere>,
}

impl NishitaPass {
    pub fn new(gpu: &GpuContext) -> Result<NishitaPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let surface_entries = SurfaceBuffer::layout_entries();
        let pipeline = PixelPipeline::new(
            gpu,
            "sky/nishita/pixel.wgsl",
            "main",
            "the nishita pass",
            &[
                uniform_entry(0, size_of::<AtmosphereUniform>()),
                uniform_entry(1, size_of::<FrameUniform>()),
                uniform_entry(2, size_of::<NishitaUniform>()),
                texture_entry(3, D2),
                storage_texture_entry(4, HDR_FORMAT, D2),
                surface_entries[0],
                surface_entries[1],
            ],
        )?;
        Ok(NishitaPass {
            params: uniform_buffer(&gpu.device, "nishita", size_of::<NishitaUniform>()),
            pipeline,
            g_l: None,
            atmosphere: AtmosphereUniform::default(),
            pending: None,
        })
    }
}

impl ModelPass for NishitaPass {
    fn plan(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        plan: &mut FramePlan,
    ) -> Result<(), RenderError> {
        check_wavelengths(&frame.settings.wavelengths_nm)?;
        let settings = NishitaSettings::from_options(&frame.settings.options)?;
        let params = NishitaUniform::new(&settings)?;
        let size = (settings.table_angles as u32, settings.table_heights as u32);
        self.atmosphere = AtmosphereUniform::new(&frame.atmosphere, RGB_WAVELENGTHS_NM)?;
        let same_size = self
            .g_l
            .as_ref()
            .is_some_and(|t| (t.pass.texture().width(), t.pass.texture().height()) == size);
        if !same_size {
            self.g_l = Some(GlTable {
                pass: TransmittancePass::with(gpu, TableOutput::Columns, size.0, size.1)?,
                built_from: None,
            });
        }
        let stale = self.g_l.as_ref().is_none_or(|t| {
            t.built_from.as_ref().is_none_or(|old| {
                Inputs::changed(old, &frame.atmosphere).intersects(Inputs::COLUMNS)
            })
        });
        self.pending = stale.then(|| frame.atmosphere.clone());
        plan.build_if("g_l", stale);
        plan.run("nishita", StepKind::Pass);
        gpu.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
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
        let Some(g_l) = self.g_l.as_mut() else {
            unreachable!("plan makes the g_l table before any step");
        };
        match step {
            "g_l" => {
                g_l.pass.encode(gpu, &self.atmosphere, encoder, timestamps);
                g_l.built_from = self.pending.take();
            }
            "nishita" => {
                let table = g_l.pass.texture().create_view(&Default::default());
                let hdr = io.hdr.create_view(&Default::default());
                let pipeline = self.pipeline.variant(io.has_surface);
                let bind_group = pipeline.pixel_bind_group(
                    gpu,
                    &[
                        io.atmosphere.as_entire_binding(),
                        io.frame.as_entire_binding(),
                        self.params.as_entire_binding(),
                        wgpu::BindingResource::TextureView(&table),
                        wgpu::BindingResource::TextureView(&hdr),
                    ],
                    io.surface,
                );
                let groups = texel_groups(io.hdr);
                pipeline.dispatch(encoder, "nishita", &bind_group, groups, timestamps);
            }
            other => unreachable!("the nishita plan has no step {other}"),
        }
    }

    fn table_bytes(&self) -> u64 {
        self.g_l.as_ref().map_or(0, |t| {
            let texture = t.pass.texture();
            u64::from(texture.width()) * u64::from(texture.height()) * 16
        })
    }
}
