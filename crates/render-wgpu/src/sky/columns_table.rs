//! A table of the columns of matter T(r, mu) (the transmittance pass's
//! [`TableOutput::Columns`]; nishita's g_l, Nishita et al. 1993) kept between frames:
//! remade when its size changes, rebuilt only when the atmosphere's columns change.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::table_inputs::Inputs;

use crate::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::sky::model_pass::StepContext;
use crate::sky::transmittance::{TableOutput, TransmittancePass};

/// The table, the atmosphere it was built from and the one the planned build is for.
#[derive(Debug)]
pub struct ColumnsTable {
    pass: TransmittancePass,
    built_from: Option<Atmosphere>,
    pending: Option<Atmosphere>,
}

impl ColumnsTable {
    /// An unbuilt table of `width` sun angles by `height` radii.
    pub fn new(gpu: &GpuContext, (width, height): (u32, u32)) -> Result<ColumnsTable, GpuError> {
        Ok(ColumnsTable {
            pass: TransmittancePass::with(gpu, TableOutput::Columns, width, height)?,
            built_from: None,
            pending: None,
        })
    }

    /// Remakes the table, unbuilt, unless it has `size` (width, height) already.
    pub fn fit(&mut self, gpu: &GpuContext, size: (u32, u32)) -> Result<(), GpuError> {
        let texture = self.pass.texture();
        if (texture.width(), texture.height()) != size {
            *self = ColumnsTable::new(gpu, size)?;
        }
        Ok(())
    }

    /// Whether the table must be built for `now` (never built, or the columns changed);
    /// remembers `now` for the build when it must.
    pub fn plan(&mut self, now: &Atmosphere) -> bool {
        let stale = Inputs::COLUMNS.stale(self.built_from.as_ref(), now);
        self.pending = stale.then(|| now.clone());
        stale
    }

    /// Records into `cx` the build planned by [`ColumnsTable::plan`], from `atmosphere`
    /// (the planned atmosphere in the GPU's layout).
    pub fn encode(&mut self, atmosphere: &AtmosphereUniform, cx: StepContext<'_>) {
        self.build(cx.gpu, atmosphere, cx.encoder, cx.timestamps);
    }

    /// [`ColumnsTable::encode`] outside a model's steps, from the atmosphere planned (the
    /// columns of matter do not depend on the wavelengths): into `encoder` on `gpu`; nothing
    /// when no build is planned.
    pub fn build_planned(
        &mut self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), GpuError> {
        if let Some(now) = &self.pending {
            let atmosphere = AtmosphereUniform::new(now, RGB_WAVELENGTHS_NM)?;
            self.build(gpu, &atmosphere, encoder, None);
        }
        Ok(())
    }

    fn build(
        &mut self,
        gpu: &GpuContext,
        atmosphere: &AtmosphereUniform,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.pass.encode(gpu, atmosphere, encoder, timestamps);
        if let Some(now) = self.pending.take() {
            self.built_from = Some(now);
        }
    }

    /// The table's texture.
    pub fn texture(&self) -> &wgpu::Texture {
        self.pass.texture()
    }

    /// Bytes of GPU memory held.
    pub fn bytes(&self) -> u64 {
        let texture = self.texture();
        u64::from(texture.width()) * u64::from(texture.height()) * 16
    }
}
