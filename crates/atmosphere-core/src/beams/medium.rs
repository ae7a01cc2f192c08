//! The homogeneous medium of a beams scene at a method's wavelengths (Dobashi et al.
//! 2000 Eq. 2: constant density, so attenuation is exp(-sigma_t t)).

use crate::atmosphere::spectral::Spectral;
use crate::optics::phase::PhaseFunction;

/// The medium as given: coefficients as functions of wavelength, and a phase function.
#[derive(Clone, Debug, PartialEq)]
pub struct Medium {
    pub scattering_per_m: Spectral,
    pub absorption_per_m: Spectral,
    pub phase: PhaseFunction,
}

/// Scattering and extinction coefficients at given wavelengths, m^-1.
#[derive(Clone, Debug, PartialEq)]
pub struct MediumSpectra {
    pub scattering_per_m: Vec<f64>,
    pub extinction_per_m: Vec<f64>,
}

impl Medium {
    /// The coefficients at `wavelengths_nm`.
    pub fn at(&self, wavelengths_nm: &[f64]) -> MediumSpectra {
        let scattering_per_m: Vec<f64> = wavelengths_nm
            .iter()
            .map(|&w| self.scattering_per_m.at(w))
            .collect();
        let extinction_per_m = wavelengths_nm
            .iter()
            .zip(&scattering_per_m)
            .map(|(&w, s)| s + self.absorption_per_m.at(w))
            .collect();
        MediumSpectra {
            scattering_per_m,
            extinction_per_m,
        }
    }
}

impl MediumSpectra {
    /// The smallest positive extinction over the wavelengths, m^-1 (infinite where no
    /// wavelength is attenuated): the one that carries light farthest.
    pub fn thinnest_extinction_per_m(&self) -> f64 {
        self.extinction_per_m
            .iter()
            .copied()
            .filter(|&e| e > 0.0)
            .fold(f64::INFINITY, f64::min)
    }
}
