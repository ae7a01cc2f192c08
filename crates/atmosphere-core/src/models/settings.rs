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

/// How many wavelengths a model computes at: 1 to 100 (every 5 nm over the visible
/// range is 95); the tables' memory budget may allow fewer for large tables.
pub const WAVELENGTH_COUNT: std::ops::RangeInclusive<usize> = 1..=100;
/// Scattering orders: 1 to 1000 (the loops over orders stop there whatever the model).
pub const ORDERS: std::ops::RangeInclusive<u32> = 1..=1000;

/// The stochastic models' target relative error: 1e-6 to 1 (below what a path cap
/// reaches in time the cap stops first, and says so).
pub const TARGET_RELATIVE_ERROR: std::ops::RangeInclusive<f64> = 1e-6..=1.0;

impl ModelSettings {
    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        let count = self.wavelengths_nm.len();
        if !WAVELENGTH_COUNT.contains(&count) {
            return Err(ModelError::Settings(format!(
                "{count} wavelengths is outside {}..={}",
                WAVELENGTH_COUNT.start(),
                WAVELENGTH_COUNT.end()
            )));
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
        if let Some(orders) = self.max_orders.filter(|o| !ORDERS.contains(o)) {
            return Err(ModelError::Settings(format!(
                "orders {orders} is outside {}..={}",
                ORDERS.start(),
                ORDERS.end()
            )));
        }
        if !TARGET_RELATIVE_ERROR.contains(&self.target_relative_error) {
            return Err(ModelError::Settings(format!(
                "target relative error {} is outside {:e}..={}",
                self.target_relative_error,
                TARGET_RELATIVE_ERROR.start(),
                TARGET_RELATIVE_ERROR.end()
            )));
        }
        Ok(())
    }
}
