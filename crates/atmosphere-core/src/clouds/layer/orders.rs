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
    /// The single-scattering phase function's Legendre moments chi_0..=chi_4,
    /// `[wavelength]` (chi_1 = g).
    moments: Vec<[f64; 5]>,
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
        let moments = series
            .iter()
            .map(|single| {
                std::array::from_fn(|l| single.coefficients().get(l).copied().unwrap_or(0.0))
            })
            .collect();
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
            moments,
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

    /// The asymmetry g of the single-scattering phase function at wavelength `w`.
    pub fn asymmetry(&self, w: usize) -> f64 {
        self.moments[w][1]
    }

    /// The Legendre moments chi_0..=chi_4 of the single-scattering phase function at
    /// wavelength `w` (what the four-stream slab keeps of it).
    pub fn moments(&self, w: usize) -> [f64; 5] {
        self.moments[w]
    }

    /// F_n, n clamped to 1..=26.
    pub fn forward_fraction(&self, w: usize, n: usize) -> f64 {
        self.forward[w][n.clamp(1, ORDERS) - 1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::gauss_legendre_rule::gauss_legendre;
    use crate::optics::phase::henyey_greenstein;

    /// Henyey-Greenstein's A_n is Henyey-Greenstein with g^n (its Legendre coefficients
    /// are g^l): the table at its angles, its unit integral (trapezoid in angle) and
    /// F_n = (1 + g) / (2 g) - (1 - g^2) / (2 g sqrt(1 + g^2)) with g = 0.7^n.
    #[test]
    fn henyey_greenstein_tables_are_henyey_greenstein_powers() {
        let rule = gauss_legendre(400);
        let values: Vec<f64> = rule
            .iter()
            .map(|&(nu, _)| henyey_greenstein(0.7, nu))
            .collect();
        let orders =
            ScatteringOrders::new(&[LegendreSeries::from_gauss_rule(&rule, &values, 200)]).unwrap();
        for n in [1usize, 2, 5, 26] {
            let g = 0.7f64.powi(n as i32);
            for nu in [-1.0, -0.3, 0.2, 0.9, 1.0] {
                let table = orders.distribution(0, n, nu);
                let exact = henyey_greenstein(g, nu);
                assert!(
                    (table / exact - 1.0).abs() < 2e-3,
                    "A_{n}({nu}) = {table}, {exact}"
                );
            }
            let row = &orders.table(0)[(n - 1) * ANGLES..n * ANGLES];
            let step = std::f64::consts::PI / (ANGLES - 1) as f64;
            let integral: f64 = row
                .windows(2)
                .enumerate()
                .map(|(k, a)| {
                    let (t0, t1) = (k as f64 * step, (k + 1) as f64 * step);
                    0.5 * step * (a[0] * t0.sin() + a[1] * t1.sin())
                })
                .sum::<f64>()
                * 2.0
                * std::f64::consts::PI;
            assert!((integral - 1.0).abs() < 1e-3, "A_{n}: integral {integral}");
            let forward = (1.0 + g) / (2.0 * g) - (1.0 - g * g) / (2.0 * g * (1.0 + g * g).sqrt());
            assert!(
                (orders.forward_fraction(0, n) - forward).abs() < 1e-6,
                "F_{n}"
            );
        }
        assert!(ScatteringOrders::new(&[]).is_err());
    }
}
