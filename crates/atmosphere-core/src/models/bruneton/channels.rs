//! The three wavelengths one set of Bruneton tables holds, as the coefficients the build
//! and the look-ups need.

use crate::atmosphere::Atmosphere;
use crate::optics::column::optical_depth;
use crate::optics::transmittance_table::TransmittanceTable;

/// The coefficients of three wavelengths (one table channel each). The tables hold
/// radiance and irradiance per unit solar irradiance (W m^-2 nm^-1 at the top of the
/// atmosphere), so the solar spectrum is not among them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Channels {
    /// Extinction per species (Rayleigh, Mie, ozone) at density 1, m^-1.
    pub extinction: [[f64; 3]; 3],
    pub rayleigh_scattering: [f64; 3],
    pub mie_scattering: [f64; 3],
}

impl Channels {
    pub fn new(atmosphere: &Atmosphere, wavelengths_nm: [f64; 3]) -> Channels {
        let c = wavelengths_nm.map(|l| atmosphere.coefficients(l));
        Channels {
            extinction: c.map(|c| c.extinction_per_species()),
            rayleigh_scattering: c.map(|c| c.rayleigh_scattering_per_m),
            mie_scattering: c.map(|c| c.mie_scattering_per_m),
        }
    }

    /// [`Channels::transmittance`] of every texel of a column table.
    pub fn transmittances(&self, table: &TransmittanceTable) -> Vec<[f64; 3]> {
        table
            .columns
            .iter()
            .map(|c| self.transmittance(*c))
            .collect()
    }

    /// exp(-optical depth) of a column at each channel.
    pub fn transmittance(&self, column: [f64; 3]) -> [f64; 3] {
        self.extinction.map(|e| (-optical_depth(column, e)).exp())
    }
}
