//! The latitude-longitude mapping of directions around a camera inside the atmosphere
//! (Hillaire 2020 section 5.3, sky-view LUT): longitude is the azimuth from the sun's
//! vertical plane, 0 to pi (the sky is symmetric about that plane), in equal steps;
//! latitude is measured from the horizon and mapped non-linearly,
//! v = 1/2 + 1/2 sign(l) sqrt(|l| / (pi / 2)), so that texels crowd where the sky changes
//! fastest.
//!
//! Two departures, both so that interpolation stays on one side of the horizon: the
//! horizon is the geometric horizon of the camera's altitude (zenith angle
//! theta_h = acos(-sqrt(r^2 - R^2) / r)), the latitude being scaled to theta_h above it
//! and to pi - theta_h below; and the rows are two halves of `height / 2` rows each (sky,
//! ground), the first row of each half on the horizon, so that no texel mixes rays that
//! end in space with rays that end on the ground.

use std::f64::consts::PI;

use glam::DVec3;

use crate::optics::geometry::horizon_mu;

/// Zenith angle of the geometric horizon at radius `r`.
pub fn horizon_zenith(r: f64, bottom: f64) -> f64 {
    horizon_mu(r, bottom).acos()
}

/// A width x height latitude-longitude grid (height even: two halves).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatLong {
    pub width: usize,
    pub height: usize,
}

/// Where a direction falls in a [`LatLong`] grid: the texel below and the weights of the
/// next column and row (rows counted from the horizon within the half).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridPosition {
    pub column: usize,
    pub column_weight: f64,
    pub row: usize,
    pub row_weight: f64,
}

impl LatLong {
    /// Rows in each half.
    pub fn half(&self) -> usize {
        self.height / 2
    }

    /// Row index in storage of row `k` (from the horizon) of the ground (`ground`) or sky
    /// half: the ground half first, nadir at row 0, then the sky half, zenith last.
    pub fn storage_row(&self, ground: bool, k: usize) -> usize {
        let h = self.half();
        if ground { h - 1 - k } else { h + k }
    }

    /// View zenith cosine and azimuth from the sun of texel (i, storage row j) for a camera
    /// at radius `r`; also whether the texel is in the ground half.
    pub fn texel_direction(&self, r: f64, bottom: f64, i: usize, j: usize) -> (f64, f64, bool) {
        let h = self.half();
        let (ground, k) = if j < h {
            (true, h - 1 - j)
        } else {
            (false, j - h)
        };
        let s = k as f64 / (h - 1) as f64;
        let theta_h = horizon_zenith(r, bottom);
        let theta = if ground {
            theta_h + (PI - theta_h) * s * s
        } else {
            theta_h * (1.0 - s * s)
        };
        let mu = if k == 0 {
            // Exactly the horizon's cosine, without the round trip through acos.
            horizon_mu(r, bottom)
        } else {
            theta.cos()
        };
        let phi = PI * i as f64 / (self.width - 1) as f64;
        (mu, phi, ground)
    }

    /// The grid position of a direction with zenith cosine `mu` and azimuth `phi` from the
    /// sun, in the `ground` or sky half, for a camera at radius `r`.
    pub fn position(&self, r: f64, bottom: f64, mu: f64, phi: f64, ground: bool) -> GridPosition {
        let theta_h = horizon_zenith(r, bottom);
        let theta = mu.clamp(-1.0, 1.0).acos();
        let s = if ground {
            if PI - theta_h > 0.0 {
                ((theta - theta_h) / (PI - theta_h)).clamp(0.0, 1.0).sqrt()
            } else {
                0.0
            }
        } else {
            (1.0 - theta / theta_h).clamp(0.0, 1.0).sqrt()
        };
        let h = self.half();
        let fy = s * (h - 1) as f64;
        let row = (fy as usize).min(h - 2);
        let fx = (phi.clamp(0.0, PI) / PI) * (self.width - 1) as f64;
        let column = (fx as usize).min(self.width - 2);
        GridPosition {
            column,
            column_weight: fx - column as f64,
            row,
            row_weight: fy - row as f64,
        }
    }

    /// Bilinear interpolation at a grid position in the `ground` or sky half, into `out`,
    /// of `values` stored by row, column, then `stride` values of which `out.len()` from
    /// `offset` are read.
    pub fn interpolate(
        &self,
        values: &[f32],
        stride: usize,
        offset: usize,
        p: &GridPosition,
        ground: bool,
        out: &mut [f64],
    ) {
        let j0 = self.storage_row(ground, p.row);
        let j1 = self.storage_row(ground, p.row + 1);
        let at = |i: usize, j: usize| (j * self.width + i) * stride + offset;
        let (a, b, c, d) = (
            at(p.column, j0),
            at(p.column + 1, j0),
            at(p.column, j1),
            at(p.column + 1, j1),
        );
        for (w, o) in out.iter_mut().enumerate() {
            let v = |k: usize| values[k + w] as f64;
            let low = v(a) + p.column_weight * (v(b) - v(a));
            let high = v(c) + p.column_weight * (v(d) - v(c));
            *o = low + p.row_weight * (high - low);
        }
    }
}

/// The view's zenith cosine and azimuth from the sun's vertical plane at a camera whose
/// local zenith is `up`; 0 where the azimuth is undefined (view or sun vertical).
pub fn view_angles(up: DVec3, direction: DVec3, sun: DVec3) -> (f64, f64) {
    let mu = direction.dot(up).clamp(-1.0, 1.0);
    let view_h = direction - up * mu;
    let sun_h = sun - up * sun.dot(up);
    let norms = view_h.length() * sun_h.length();
    let phi = if norms > 1e-12 {
        (view_h.dot(sun_h) / norms).clamp(-1.0, 1.0).acos()
    } else {
        0.0
    };
    (mu, phi)
}

/// View-sun cosine of a direction with zenith cosine `mu` and azimuth `phi` from a sun at
/// zenith cosine `mu_s`.
pub fn view_sun_cosine(mu: f64, phi: f64, mu_s: f64) -> f64 {
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let sin_s = (1.0 - mu_s * mu_s).max(0.0).sqrt();
    (mu * mu_s + sin_v * sin_s * phi.cos()).clamp(-1.0, 1.0)
}
