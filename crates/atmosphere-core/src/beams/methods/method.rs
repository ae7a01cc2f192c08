//! What every beam method answers, and the settings it is prepared with.

use crate::beams::error::BeamError;
use crate::beams::ray::SceneRay;
use crate::models::options::ModelOptions;

/// Settings shared by the beam methods.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamSettings {
    /// Wavelengths (nm) at which radiance is computed.
    pub wavelengths_nm: Vec<f64>,
    /// The method's own settings as `key=value` (docs/beams/<method>.md lists them);
    /// its paper's values where a key is absent.
    pub options: ModelOptions,
}

impl Default for BeamSettings {
    fn default() -> Self {
        BeamSettings {
            wavelengths_nm: vec![680.0, 550.0, 440.0],
            options: ModelOptions::default(),
        }
    }
}

/// A beam method prepared for one scene: the radiance of view rays.
pub trait BeamMethod: Send + Sync + std::fmt::Debug {
    /// The radiance scattered toward the ray's origin along it, one value per
    /// wavelength of the settings, W m^-2 sr^-1 nm^-1.
    fn radiance(&self, ray: &SceneRay) -> Result<Vec<f64>, BeamError>;
}
