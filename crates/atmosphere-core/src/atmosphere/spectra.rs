//! An atmosphere's optical coefficients sampled at the wavelengths a model carries.

use crate::atmosphere::Atmosphere;

/// The coefficients of the atmosphere at each wavelength of a model.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectra {
    pub wavelengths_nm: Vec<f64>,
    /// Extinction per species (Rayleigh, Mie, ozone) at density 1, m^-1.
    pub extinction: Vec<[f64; 3]>,
    pub rayleigh_scattering: Vec<f64>,
    pub mie_scattering: Vec<f64>,
    pub solar_irradiance: Vec<f64>,
}

impl Spectra {
    /// Whether a model must do Mie work: always without pruning
    /// ([`crate::models::settings::ModelSettings::prune`]), else only when aerosols scatter or
    /// absorb at some wavelength.
    pub fn needs_mie(&self, prune: bool) -> bool {
        !prune
            || self.mie_scattering.iter().any(|s| *s != 0.0)
            || self.extinction.iter().any(|e| e[1] != 0.0)
    }

    pub fn new(atmosphere: &Atmosphere, wavelengths_nm: &[f64]) -> Spectra {
        let c: Vec<_> = wavelengths_nm
            .iter()
            .map(|l| atmosphere.coefficients(*l))
            .collect();
        Spectra {
            wavelengths_nm: wavelengths_nm.to_vec(),
            extinction: c.iter().map(|c| c.extinction_per_species()).collect(),
            rayleigh_scattering: c.iter().map(|c| c.rayleigh_scattering_per_m).collect(),
            mie_scattering: c.iter().map(|c| c.mie_scattering_per_m).collect(),
            solar_irradiance: c.iter().map(|c| c.solar_irradiance_w_m2_nm).collect(),
        }
    }
}
