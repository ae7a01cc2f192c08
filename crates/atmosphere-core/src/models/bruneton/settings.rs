//! The sizes and sample counts of the Bruneton tables, from the command line's options.

use crate::models::bruneton::parameterization::ScatteringSize;
use crate::models::error::ModelError;
use crate::models::options::ModelOptions;
use crate::optics::transmittance_table::BRUNETON_TABLE_SIZE;

/// The model's settings. `Default` gives the paper's sizes (section 6) and the sample
/// counts of its published implementation.
#[derive(Clone, Debug, PartialEq)]
pub struct BrunetonSettings {
    /// S over (r, mu, mu_s, nu): 32 x 128 x 32 x 8 in the paper. mu must be even (half
    /// for rays that meet the ground); every size at least 2.
    pub scattering_size: ScatteringSize,
    /// E over (mu_s, r): 64 x 16 in the paper.
    pub irradiance_size: (usize, usize),
    /// T over (mu, r): 256 x 64 (the paper has 256 x 64 too, in another mapping; this is
    /// the shared table of Bruneton 2017's mapping).
    pub transmittance_size: (usize, usize),
    /// Trapezoid intervals along each texel's ray for single scattering and each
    /// Delta S: 50 (INSCATTER_INTEGRAL_SAMPLES of the paper's code); fewer miss the thin
    /// hazy boundary layer. Unlike that code, nodes are spaced quadratically towards the
    /// dense end of climbing and descending rays, where evenly spaced nodes overestimate
    /// Mie scattering on vertical rays.
    pub view_samples: usize,
    /// Directions (zenith angle, azimuth) of the sphere integrals for Delta J and
    /// Delta E: 16 x 32 (INSCATTER_SPHERICAL_INTEGRAL_SAMPLES). The zenith angle is
    /// integrated by 8-point Gauss-Legendre panels on each side of the horizon, one pair
    /// of panels per 16 directions.
    pub sphere_samples: (usize, usize),
    /// Stop after an order whose share of all the table's radiance (sum over texels, worst
    /// channel) is below this: 0.02 (on Earth the loop stops after a few orders; those
    /// left out add less than the last one).
    pub order_threshold: f64,
    /// The most orders when `ModelSettings::max_orders` is `None` (a guard for thick
    /// atmospheres whose orders fade slowly): 32.
    pub order_limit: u32,
}

impl Default for BrunetonSettings {
    fn default() -> Self {
        BrunetonSettings {
            scattering_size: ScatteringSize {
                r: 32,
                mu: 128,
                mu_s: 32,
                nu: 8,
            },
            irradiance_size: (64, 16),
            transmittance_size: BRUNETON_TABLE_SIZE,
            view_samples: 50,
            sphere_samples: (16, 32),
            order_threshold: 0.02,
            order_limit: 32,
        }
    }
}

impl BrunetonSettings {
    /// The settings from `key=value` options: `r`, `mu`, `mu_s`, `nu` (S's size),
    /// `view_samples`, `sphere_zenith`, `sphere_azimuth`, `order_threshold`,
    /// `order_limit`; the paper's values where absent.
    pub fn from_options(options: &ModelOptions) -> Result<BrunetonSettings, ModelError> {
        options.read_settings("bruneton", BrunetonSettings::validate, |o, d| {
            Ok(BrunetonSettings {
                scattering_size: ScatteringSize {
                    r: o.count("r", d.scattering_size.r)?,
                    mu: o.count("mu", d.scattering_size.mu)?,
                    mu_s: o.count("mu_s", d.scattering_size.mu_s)?,
                    nu: o.count("nu", d.scattering_size.nu)?,
                },
                view_samples: o.count("view_samples", d.view_samples)?,
                sphere_samples: (
                    o.count("sphere_zenith", d.sphere_samples.0)?,
                    o.count("sphere_azimuth", d.sphere_samples.1)?,
                ),
                order_threshold: o.number("order_threshold", d.order_threshold)?,
                order_limit: o.count("order_limit", d.order_limit as usize)? as u32,
                ..d
            })
        })
    }

    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        let s = self.scattering_size;
        if s.r < 2 || s.mu < 4 || !s.mu.is_multiple_of(2) || s.mu_s < 2 || s.nu < 2 {
            return Err(ModelError::Settings(format!(
                "scattering table size {s:?}: each axis needs 2 texels, mu an even count of 4 or more"
            )));
        }
        if self.irradiance_size.0 < 2 || self.irradiance_size.1 < 2 {
            return Err(ModelError::Settings(
                "irradiance table needs 2 x 2 texels".into(),
            ));
        }
        if self.transmittance_size.0 < 2 || self.transmittance_size.1 < 2 {
            return Err(ModelError::Settings(
                "transmittance table needs 2 x 2 texels".into(),
            ));
        }
        if self.view_samples == 0 || self.sphere_samples.0 == 0 || self.sphere_samples.1 < 2 {
            return Err(ModelError::Settings(
                "sample counts must be positive".into(),
            ));
        }
        if !(self.order_threshold.is_finite() && self.order_threshold >= 0.0) {
            return Err(ModelError::Settings("order threshold must be >= 0".into()));
        }
        if self.order_limit == 0 {
            return Err(ModelError::Settings(
                "order limit must be at least 1".into(),
            ));
        }
        Ok(())
    }
}
