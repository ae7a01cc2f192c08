//! The transmittance table T(r, mu) from any point in the atmosphere to the top boundary,
//! for rays that do not meet the ground, in the parameterization of Bruneton 2017
//! (`GetTransmittanceTextureUvFromRMu`): the horizontal coordinate is the distance to the
//! top boundary mapped between its minimum and maximum for the row's radius, so that the
//! horizon, where transmittance changes fastest, falls exactly on the table's last column
//! and gets as many texels as the zenith.
//!
//! The table stores columns of matter (wavelength independent), so one table serves every
//! wavelength. This is the CPU twin of `shaders/sky/transmittance_table.wgsl`: texel centres,
//! mapping and quadrature ([`table_column`]) are the same.

use rayon::prelude::*;

use crate::atmosphere::Atmosphere;
use crate::numerics::quadrature::{GAUSS_LEGENDRE_5, mapped};
use crate::optics::column::{densities, optical_depth};
use crate::optics::geometry::{distance_to_exit, radius_at, safe_sqrt};

/// Width (mu) and height (r) of the table used by the Bruneton model (Bruneton 2017).
pub const BRUNETON_TABLE_SIZE: (usize, usize) = (256, 64);

/// Panels of the 5-point Gauss-Legendre rule along each texel's ray. 64 panels bring the
/// Rayleigh and Mie columns within 2e-5 of the converged quadrature at every texel, ozone
/// within 1e-3 (tested below).
pub const TABLE_PANELS: usize = 64;

/// Columns (m) from (r, mu) to the top boundary by 64 equal panels of 5-point
/// Gauss-Legendre: the quadrature the shader runs, in f64.
pub fn table_column(atmosphere: &Atmosphere, r: f64, mu: f64) -> [f64; 3] {
    let d = distance_to_exit(r, mu, atmosphere.top_radius_m);
    let step = d / TABLE_PANELS as f64;
    let mut sum = [0.0; 3];
    for p in 0..TABLE_PANELS {
        let a = step * p as f64;
        for (t, w) in mapped(&GAUSS_LEGENDRE_5, a, a + step) {
            let rho = densities(atmosphere, radius_at(r, mu, t) - atmosphere.bottom_radius_m);
            for k in 0..3 {
                sum[k] += w * rho[k];
            }
        }
    }
    sum
}

/// Texture coordinate in [0, 1] of a value in [0, 1] such that 0 and 1 fall on the
/// centres of the first and last texels (Bruneton 2017 `GetTextureCoordFromUnitRange`).
pub fn coord_from_unit(x: f64, size: usize) -> f64 {
    0.5 / size as f64 + x * (1.0 - 1.0 / size as f64)
}

/// Inverse of [`coord_from_unit`].
pub fn unit_from_coord(u: f64, size: usize) -> f64 {
    (u - 0.5 / size as f64) / (1.0 - 1.0 / size as f64)
}

/// The mapping between (r, mu) and unit coordinates (x_mu, x_r) of the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TransmittanceMapping {
    pub bottom_radius_m: f64,
    pub top_radius_m: f64,
}

impl TransmittanceMapping {
    fn horizon_length(&self) -> f64 {
        safe_sqrt(
            (self.top_radius_m - self.bottom_radius_m) * (self.top_radius_m + self.bottom_radius_m),
        )
    }

    /// (x_mu, x_r) in [0, 1]^2 for a ray from radius r with direction cosine mu.
    pub fn unit_from_r_mu(&self, r: f64, mu: f64) -> (f64, f64) {
        let h = self.horizon_length();
        let rho = safe_sqrt((r - self.bottom_radius_m) * (r + self.bottom_radius_m));
        let d = distance_to_exit(r, mu, self.top_radius_m);
        let d_min = self.top_radius_m - r;
        let d_max = rho + h;
        let x_mu = if d_max > d_min {
            (d - d_min) / (d_max - d_min)
        } else {
            0.0
        };
        (x_mu.clamp(0.0, 1.0), (rho / h).clamp(0.0, 1.0))
    }

    /// (r, mu) of unit coordinates (x_mu, x_r).
    pub fn r_mu_from_unit(&self, x_mu: f64, x_r: f64) -> (f64, f64) {
        let h = self.horizon_length();
        let rho = h * x_r;
        let r = (rho * rho + self.bottom_radius_m * self.bottom_radius_m).sqrt();
        let d_min = self.top_radius_m - r;
        let d_max = rho + h;
        let d = d_min + x_mu * (d_max - d_min);
        let mu = if d == 0.0 {
            1.0
        } else {
            ((h * h - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
        };
        (r, mu)
    }
}

/// Columns to the top boundary on a grid of (r, mu).
#[derive(Clone, Debug)]
pub struct TransmittanceTable {
    pub width: usize,
    pub height: usize,
    pub mapping: TransmittanceMapping,
    /// Row-major, `width * height` texels, each the columns of (Rayleigh, Mie, ozone).
    pub columns: Vec<[f64; 3]>,
}

impl TransmittanceTable {
    /// Builds the table with [`table_column`] at every texel centre.
    pub fn build(atmosphere: &Atmosphere, width: usize, height: usize) -> TransmittanceTable {
        let mapping = TransmittanceMapping {
            bottom_radius_m: atmosphere.bottom_radius_m,
            top_radius_m: atmosphere.top_radius_m,
        };
        let columns = (0..width * height)
            .into_par_iter()
            .map(|index| {
                let (r, mu) =
                    Self::texel_r_mu_of(&mapping, width, height, index % width, index / width);
                table_column(atmosphere, r, mu)
            })
            .collect();
        TransmittanceTable {
            width,
            height,
            mapping,
            columns,
        }
    }

    fn texel_r_mu_of(
        mapping: &TransmittanceMapping,
        width: usize,
        height: usize,
        i: usize,
        j: usize,
    ) -> (f64, f64) {
        let u = (i as f64 + 0.5) / width as f64;
        let v = (j as f64 + 0.5) / height as f64;
        mapping.r_mu_from_unit(unit_from_coord(u, width), unit_from_coord(v, height))
    }

    /// (r, mu) at the centre of texel (i, j).
    pub fn texel_r_mu(&self, i: usize, j: usize) -> (f64, f64) {
        Self::texel_r_mu_of(&self.mapping, self.width, self.height, i, j)
    }

    /// Transmittance stored at texel (i, j) for extinctions per species.
    pub fn texel_transmittance(&self, i: usize, j: usize, extinction_per_species: [f64; 3]) -> f64 {
        (-optical_depth(self.columns[j * self.width + i], extinction_per_species)).exp()
    }

    /// Bilinearly interpolated columns from (r, mu) to the top boundary; the ray must not
    /// meet the ground.
    pub fn column(&self, r: f64, mu: f64) -> [f64; 3] {
        self.interpolate(&self.columns, r, mu)
    }

    /// Columns of the segment of length d from (r, mu), the difference of two table
    /// look-ups (Bruneton and Neyret 2008, section 4; for a ray that meets the ground,
    /// `ground`, both are read looking up, from the segment's far end and from its start).
    pub fn segment_column(&self, r: f64, mu: f64, d: f64, ground: bool) -> [f64; 3] {
        let (bottom, top) = (self.mapping.bottom_radius_m, self.mapping.top_radius_m);
        let r_d = radius_at(r, mu, d).clamp(bottom, top);
        let mu_d = ((r * mu + d) / r_d).clamp(-1.0, 1.0);
        let (a, b) = if ground {
            (self.column(r_d, -mu_d), self.column(r, -mu))
        } else {
            (self.column(r, mu), self.column(r_d, mu_d))
        };
        [0, 1, 2].map(|k| (a[k] - b[k]).max(0.0))
    }

    /// Bilinear interpolation at (r, mu) of `values`, one per texel of this table (the
    /// columns, or a quantity derived from them such as transmittances).
    pub fn interpolate(&self, values: &[[f64; 3]], r: f64, mu: f64) -> [f64; 3] {
        let (x_mu, x_r) = self.mapping.unit_from_r_mu(r, mu);
        let fx = (coord_from_unit(x_mu, self.width) * self.width as f64 - 0.5)
            .clamp(0.0, (self.width - 1) as f64);
        let fy = (coord_from_unit(x_r, self.height) * self.height as f64 - 0.5)
            .clamp(0.0, (self.height - 1) as f64);
        let i0 = (fx as usize).min(self.width.saturating_sub(2));
        let j0 = (fy as usize).min(self.height.saturating_sub(2));
        let (ax, ay) = (fx - i0 as f64, fy - j0 as f64);
        let at = |i: usize, j: usize| values[j * self.width + i];
        let (c00, c10, c01, c11) = (
            at(i0, j0),
            at(i0 + 1, j0),
            at(i0, j0 + 1),
            at(i0 + 1, j0 + 1),
        );
        let mut out = [0.0; 3];
        for k in 0..3 {
            let bottom = c00[k] + ax * (c10[k] - c00[k]);
            let top = c01[k] + ax * (c11[k] - c01[k]);
            out[k] = bottom + ay * (top - bottom);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::column::column;

    #[test]
    fn mapping_round_trips() {
        let earth = Atmosphere::preset("earth").unwrap();
        let m = TransmittanceMapping {
            bottom_radius_m: earth.bottom_radius_m,
            top_radius_m: earth.top_radius_m,
        };
        for &(x_mu, x_r) in &[(0.0, 0.0), (0.3, 0.5), (1.0, 1.0), (0.99, 0.01), (0.5, 1.0)] {
            let (r, mu) = m.r_mu_from_unit(x_mu, x_r);
            let (x_mu2, x_r2) = m.unit_from_r_mu(r, mu);
            assert!(
                (x_mu - x_mu2).abs() < 1e-9 && (x_r - x_r2).abs() < 1e-9,
                "{x_mu} {x_r}"
            );
        }
        // The last column is the horizon.
        let (r, mu) = m.r_mu_from_unit(1.0, 0.5);
        let horizon = crate::optics::geometry::horizon_mu(r, earth.bottom_radius_m);
        assert!((mu - horizon).abs() < 1e-9, "{mu} vs {horizon}");
    }

    /// Rayleigh and Mie columns within 2e-5 of the converged quadrature; ozone within
    /// 1e-3, since equal panels straddle the kinks of its tent profile (an optical depth
    /// error below 1e-5 per air mass).
    #[test]
    fn table_quadrature_is_close_to_the_converged_columns() {
        let earth = Atmosphere::preset("earth").unwrap();
        let table = TransmittanceTable::build(&earth, 32, 16);
        let mut worst = [0.0f64; 3];
        for j in 0..table.height {
            for i in 0..table.width {
                let (r, mu) = table.texel_r_mu(i, j);
                let exact = column(&earth, r, mu, distance_to_exit(r, mu, earth.top_radius_m));
                let got = table.columns[j * table.width + i];
                for k in 0..3 {
                    if exact[k] > 1.0 {
                        worst[k] = worst[k].max((got[k] - exact[k]).abs() / exact[k]);
                    }
                }
            }
        }
        assert!(
            worst[0] < 2e-5 && worst[1] < 2e-5 && worst[2] < 1e-3,
            "worst relative errors {worst:?}"
        );
    }

    #[test]
    fn interpolation_is_exact_at_texel_centres_and_close_between() {
        let earth = Atmosphere::preset("earth").unwrap();
        let table = TransmittanceTable::build(&earth, 256, 64);
        let (r, mu) = table.texel_r_mu(100, 20);
        let c = table.column(r, mu);
        assert!((c[0] / table.columns[20 * 256 + 100][0] - 1.0).abs() < 1e-9);
        // Between texels, within 1e-3 of the converged column for the ozone-free species
        // at moderate angles.
        let r = earth.bottom_radius_m + 1234.0;
        let mu = 0.4321;
        let exact = column(&earth, r, mu, distance_to_exit(r, mu, earth.top_radius_m));
        let got = table.column(r, mu);
        for k in 0..2 {
            assert!(
                (got[k] / exact[k] - 1.0).abs() < 1e-3,
                "{k}: {} vs {}",
                got[k],
                exact[k]
            );
        }
    }
}
