//! Riley et al. 2004's multiple-scattering angular distributions A_n (section 4.2.1,
//! Eq. 20) and forward fractions F_n (section 4.2.2, Eq. 23) of the droplets, for
//! n = 1 to 26, tabulated at [`ANGLES`] scattering angles uniform in 0 to 180 degrees
//! (Riley et al. store them at about 0.18 degree), one table per wavelength: what the
//! march reads and the GPU's texture holds. Between angles, linear interpolation.

use crate::clouds::error::CloudError;
use crate::optics::legendre_series::LegendreSeries;
use crate::optics::multiple_scattering_phase::{MultipleScatteringPhase, RILEY_MAX_ORDER};

/// Angles per table row, 0 and 180 degrees included: a step of 0.176 degree.
pub const ANGLES: usize = 1024;
/// Rows: A_1 to A_26.
pub const ORDERS: usize = RILEY_MAX_ORDER as usize;

/// A_n and F_n at each wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct ScatteringOrders {
    /// `[wavelength][(n - 1) * ANGLES + k]`, sr^-1, at angle k * 180 / (ANGLES - 1).
    distributions: Vec<Vec<f64>>,
    /// `[wavelength][n - 1]`.
    forward: Vec<Vec<f64>>,
}

impl ScatteringOrders {
    /// The tables of the single-scattering phase functions `series`, one per wavelength.
    pub fn new(series: &[LegendreSeries]) -> Result<ScatteringOrders, CloudError> {
        if series.is_empty() {
            return Err(CloudError(
                "cloud phase: no wavelength's phase function given".into(),
            ));
        }
        let mut distributions = Vec::with_capacity(series.len());
        let mut forward = Vec::with_capacity(series.len());
        for single in series {
            let orders = MultipleScatteringPhase::new(single, RILEY_MAX_ORDER);
            let mut table = Vec::with_capacity(ORDERS * ANGLES);
            for n in 1..=RILEY_MAX_ORDER {
                table.extend((0..ANGLES).map(|k| {
                    let angle = (k as f64 * 180.0 / (ANGLES - 1) as f64).to_radians();
                    orders.angular_distribution(n, angle.cos()).max(0.0)
                }));
            }
            distributions.push(table);
            forward.push(
                (1..=RILEY_MAX_ORDER)
                    .map(|n| orders.forward_fraction(n))
                    .collect(),
            );
        }
        Ok(ScatteringOrders {
            distributions,
            forward,
        })
    }

    pub fn wavelengths(&self) -> usize {
        self.distributions.len()
    }

    /// The table of wavelength `w`, row-major as documented on the field.
    pub fn table(&self, w: usize) -> &[f64] {
        &self.distributions[w]
    }

    /// A_n at the scattering angle whose cosine is `nu`, n clamped to 1..=26.
    pub fn distribution(&self, w: usize, n: usize, nu: f64) -> f64 {
        let row = n.clamp(1, ORDERS) - 1;
        let x = nu.clamp(-1.0, 1.0).acos().to_degrees() / 180.0 * (ANGLES - 1) as f64;
        let k = (x.floor() as usize).min(ANGLES - 2);
        let f = x - k as f64;
        let table = &self.distributions[w][row * ANGLES..(row + 1) * ANGLES];
        table[k] * (1.0 - f) + table[k + 1] * f
    }

    /// F_n, n clamped to 1..=26.
    pub fn forward_fraction(&self, w: usize, n: usize) -> f64 {
        self.forward[w][n.clamp(1, ORDERS) - 1]
    }
}
