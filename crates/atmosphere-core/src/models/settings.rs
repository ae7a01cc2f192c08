//! The settings every model is prepared with: its wavelengths, how many scattering
//! orders, the stochastic models' error and seed, pruning, and the model's own options.

use crate::models::error::ModelError;
use crate::models::options::ModelOptions;

/// Settings shared by the models.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelSettings {
    /// Wavelengths (nm) at which radiance is computed.
    pub wavelengths_nm: Vec<f64>,
    /// Highest scattering order (1 = single scattering); `None` for all orders.
    pub max_orders: Option<u32>,
    /// For stochastic models: the relative standard error to reach per ray and wavelength.
    pub target_relative_error: f64,
    /// For stochastic models: the seed of the random sequence (results are reproducible).
    pub seed: u64,
    /// The model's own settings (samples, table sizes, ...) as `key=value`; the paper's
    /// values where a key is absent. Each model's page in docs/models lists its keys.
    pub options: ModelOptions,
    /// Leave out work that adds nothing: at zero aerosol no Mie table or Mie term is
    /// computed. Answers equal those with `prune = false` (the full path), which tests
    /// compare against.
    pub prune: bool,
}

impl Default for ModelSettings {
    fn default() -> Self {
        ModelSettings {
            wavelengths_nm: vec![680.0, 550.0, 440.0],
            max_orders: None,
            target_relative_error: 0.0025,
            seed: 1,
            options: ModelOptions::default(),
            prune: true,
        }
    }
}

impl ModelSettings {
    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        if self.wavelengths_nm.is_empty() {
            return Err(ModelError::Settings(
                "at least one wavelength is needed".into(),
            ));
        }
        if let Some(w) = self
            .wavelengths_nm
            .iter()
            .find(|w| !(w.is_finite() && (360.0..=830.0).contains(*w)))
        {
            return Err(ModelError::Settings(format!(
                "wavelength {w} nm is outside the visible range 360..830 nm"
            )));
        }
        if self.max_orders == Some(0) {
            return Err(ModelError::Settings("orders must be at least 1".into()));
        }
        if !(self.target_relative_error.is_finite() && self.target_relative_error > 0.0) {
            return Err(ModelError::Settings(format!(
                "target relative error {} must be > 0",
                self.target_relative_error
            )));
        }
        Ok(())
    }
}
