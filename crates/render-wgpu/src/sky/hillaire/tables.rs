//! The hillaire model's tables (Hillaire 2020, section 5): their textures, the inputs
//! each depends on (those of the CPU's `Hillaire::update`) and what each was last built
//! from.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::table_inputs::Inputs;
use atmosphere_core::models::hillaire::{
    HillaireSettings, VIEW_INPUTS, multiple_scattering_inputs,
};

use atmosphere_core::models::hillaire::moments::blocks;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::sky::hillaire::uniform::count;
use crate::sky::table_limits::table_extent;
use crate::sky::transmittance::{TABLE_FORMAT, TableOutput, TransmittancePass};

/// The model's tables, by step name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Table {
    /// The columns of matter T(r, mu) (section 5.1; transmittance is exp(-tau) of them).
    Transmittance,
    /// Psi_ms, the multiple-scattering transfer (section 5.5).
    MultipleScattering,
    /// E_sky, the ground's irradiance by the sky.
    GroundIrradiance,
    /// The sky-view table of one view (section 5.3).
    SkyView,
    /// The aerial-perspective volume of one view (section 5.4): radiance, with its
    /// transmittance in a second texture.
    AerialPerspective,
}

impl Table {
    pub const ALL: [Table; 5] = [
        Table::Transmittance,
        Table::MultipleScattering,
        Table::GroundIrradiance,
        Table::SkyView,
        Table::AerialPerspective,
    ];

    /// The step's name in the plan.
    pub fn name(self) -> &'static str {
        match self {
            Table::Transmittance => "transmittance",
            Table::MultipleScattering => "multiple_scattering",
            Table::GroundIrradiance => "ground_irradiance",
            Table::SkyView => "sky_view",
            Table::AerialPerspective => "aerial_perspective",
        }
    }

    /// The atmosphere's inputs it depends on under `settings` (`Hillaire::update`).
    fn inputs(self, settings: &HillaireSettings) -> Inputs {
        match self {
            Table::Transmittance => Inputs::COLUMNS,
            Table::MultipleScattering => multiple_scattering_inputs(settings),
            Table::GroundIrradiance | Table::SkyView | Table::AerialPerspective => VIEW_INPUTS,
        }
    }

    /// Whether it depends on the view and on whether orders two and up are on.
    fn per_view(self) -> bool {
        matches!(self, Table::SkyView | Table::AerialPerspective)
    }
}

/// What a table was built from.
#[derive(Clone, Debug, PartialEq)]
pub struct Source {
    pub atmosphere: Atmosphere,
    pub view: (f64, f64),
    pub multiple_on: bool,
}

impl Source {
    /// Whether `table` built from `self` under `settings` is out of date for `new`.
    pub fn stale_for(&self, table: Table, settings: &HillaireSettings, new: &Source) -> bool {
        Inputs::changed(&self.atmosphere, &new.atmosphere).intersects(table.inputs(settings))
            || (table.per_view() && (self.view != new.view || self.multiple_on != new.multiple_on))
    }
}

/// A texture for a table, written by one shader and read by the next, of `size` texels
/// from `settings`, or why this GPU cannot hold it.
fn table_texture(
    gpu: &GpuContext,
    label: &str,
    settings: &str,
    dimension: wgpu::TextureDimension,
    size: (usize, usize, usize),
) -> Result<wgpu::Texture, RenderError> {
    let extent = table_extent(gpu, &format!("hillaire {label}"), settings, dimension, size)?;
    Ok(gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: extent,
        mip_level_count: 1,
        sample_count: 1,
        dimension,
        format: TABLE_FORMAT,
        usage: wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    }))
}

/// The tables of one `HillaireSettings`, and what each was last built from.
#[derive(Debug)]
pub struct Tables {
    pub settings: HillaireSettings,
    pub transmittance: TransmittancePass,
    pub multiple_scattering: wgpu::Texture,
    pub ground_irradiance: wgpu::Texture,
    pub sky_view: wgpu::Texture,
    pub aerial_radiance: wgpu::Texture,
    pub aerial_transmittance: wgpu::Texture,
    /// What each table (by [`Table`] as index) was last built from.
    pub built: [Option<Source>; 5],
}

impl Tables {
    /// Unbuilt tables of the sizes of `settings`, or why this GPU cannot hold them.
    pub fn new(gpu: &GpuContext, settings: HillaireSettings) -> Result<Tables, RenderError> {
        use wgpu::TextureDimension::{D2, D3};
        const MS: &str = "ms_width x ms_height";
        const SKY_VIEW: &str = "sky_view_width x sky_view_height";
        const AP: &str = "ap_width x ap_height x ap_slices";
        let (tw, th) = settings.transmittance_size;
        let (mw, mh) = settings.multiple_scattering_size;
        let (sw, sh) = settings.sky_view_size;
        let (aw, ah, slices) = settings.aerial_size;
        Ok(Tables {
            settings,
            transmittance: TransmittancePass::with(
                gpu,
                TableOutput::Columns,
                count("transmittance_width", tw)?,
                count("transmittance_height", th)?,
            )?,
            // Psi_0..Psi_order stacked as blocks of rows (`MultipleScattering::values`).
            multiple_scattering: table_texture(
                gpu,
                "Psi_ms",
                MS,
                D2,
                (mw, mh * blocks(settings.multiple_scattering_order), 1),
            )?,
            ground_irradiance: table_texture(
                gpu,
                "E_sky",
                "ground_size",
                D2,
                (settings.ground_size, 1, 1),
            )?,
            sky_view: table_texture(gpu, "sky view", SKY_VIEW, D2, (sw, sh, 1))?,
            aerial_radiance: table_texture(gpu, "aerial radiance", AP, D3, (aw, ah, slices))?,
            aerial_transmittance: table_texture(
                gpu,
                "aerial transmittance",
                AP,
                D3,
                (aw, ah, slices),
            )?,
            built: Default::default(),
        })
    }

    /// The texture `table` writes (the volume's radiance for the aerial perspective).
    pub fn texture(&self, table: Table) -> &wgpu::Texture {
        match table {
            Table::Transmittance => self.transmittance.texture(),
            Table::MultipleScattering => &self.multiple_scattering,
            Table::GroundIrradiance => &self.ground_irradiance,
            Table::SkyView => &self.sky_view,
            Table::AerialPerspective => &self.aerial_radiance,
        }
    }

    /// Bytes of GPU memory held.
    pub fn bytes(&self) -> u64 {
        Table::ALL
            .iter()
            .map(|&table| self.texture(table))
            .chain([&self.aerial_transmittance])
            .map(|texture| {
                u64::from(texture.width())
                    * u64::from(texture.height())
                    * u64::from(texture.depth_or_array_layers())
                    * 16
            })
            .sum()
    }
}
