//! Storage and interpolation of the model's tables: the 4D scattering tables S and
//! Delta J over (r, mu, mu_s, nu), the 2D irradiance table E(r, mu_s), and a fine 1D
//! table of the species' densities over altitude used while building. Values are three
//! wavelengths at once, stored in f32 and interpolated (multi)linearly in f64.

use crate::atmosphere::Atmosphere;
use crate::models::bruneton::parameterization::{
    IrradianceMapping, Radii, ScatteringSize, axis, table_position,
};
use crate::optics::column::densities;

/// A 4D table of three channels.
#[derive(Clone, Debug)]
pub struct Table4 {
    pub size: ScatteringSize,
    pub data: Vec<[f32; 3]>,
}

impl Table4 {
    pub fn zeros(size: ScatteringSize) -> Table4 {
        Table4 {
            size,
            data: vec![[0.0; 3]; size.texels()],
        }
    }

    /// Trilinear interpolation over (r, mu, mu_s) in nu slice `inu`: eight texels (the
    /// next texel of each axis exists, see [`axis`]); along mu_s geometric instead where
    /// `geometric` ([`along_mu_s`]).
    fn slice(&self, p: &[(usize, f64); 4], inu: usize, geometric: bool) -> [f64; 3] {
        let s = &self.size;
        let (ir, wr) = p[0];
        let (imu, wmu) = p[1];
        let (imus, wmus) = p[2];
        let mut out = [0.0; 3];
        for (dm, wm) in [(0, 1.0 - wmu), (1, wmu)] {
            for (dr, w_r) in [(0, 1.0 - wr), (1, wr)] {
                let i = s.index(ir + dr, imu + dm, imus, inu);
                let (a, b) = (self.data[i], self.data[i + 1]);
                let w = wm * w_r;
                for k in 0..3 {
                    out[k] += w * along_mu_s(a[k] as f64, b[k] as f64, wmus, geometric);
                }
            }
        }
        out
    }

    /// Quadrilinear interpolation at a table position (see [`table_position`]); along
    /// mu_s geometric between texels whose suns are below the horizontal where the
    /// mapping asks for it ([`AngleMapping::geometric_pair`](crate::models::bruneton::parameterization::AngleMapping::geometric_pair)).
    pub fn at_position(&self, p: &[(usize, f64); 4]) -> [f64; 3] {
        let (inu, wnu) = p[3];
        let geometric = self.size.angles.geometric_pair(p[2].0, self.size.mu_s);
        let lo = self.slice(p, inu, geometric);
        if wnu == 0.0 {
            return lo;
        }
        let hi = self.slice(p, inu + 1, geometric);
        [
            lo[0] + wnu * (hi[0] - lo[0]),
            lo[1] + wnu * (hi[1] - lo[1]),
            lo[2] + wnu * (hi[2] - lo[2]),
        ]
    }

    /// The table at (r, mu, mu_s, nu) on the side of the horizon chosen by `ground`.
    pub fn lookup(
        &self,
        radii: &Radii,
        r: f64,
        mu: f64,
        mu_s: f64,
        nu: f64,
        ground: bool,
    ) -> [f64; 3] {
        self.at_position(&table_position(radii, &self.size, r, mu, mu_s, nu, ground))
    }

    /// Adds `other` texel by texel.
    pub fn add(&mut self, other: &Table4) {
        for (a, b) in self.data.iter_mut().zip(&other.data) {
            for k in 0..3 {
                a[k] += b[k];
            }
        }
    }
}

/// Between texels a and b along mu_s at weight w of b: linear, or with `geometric`
/// a (b / a)^w where both are positive (linear where either is not). With the sun below
/// the horizontal the sky dims by about e per 0.02 of mu_s, nearly exponentially, so
/// linear interpolation between texels 0.014 apart (the paper's spacing at civil
/// twilight) overestimates it by a few per cent; geometric interpolation is exact for an
/// exponential. Both agree with the texels at w = 0 and 1, so the look-up stays
/// continuous in mu_s where the rule changes from one pair of texels to the next.
pub fn along_mu_s(a: f64, b: f64, w: f64, geometric: bool) -> f64 {
    if geometric && a > 0.0 && b > 0.0 {
        a * (b / a).powf(w)
    } else {
        (1.0 - w) * a + w * b
    }
}

/// The 2D irradiance table E(r, mu_s) of three channels.
#[derive(Clone, Debug)]
pub struct IrradianceTable {
    pub mapping: IrradianceMapping,
    pub data: Vec<[f32; 3]>,
}

impl IrradianceTable {
    pub fn zeros(mapping: IrradianceMapping) -> IrradianceTable {
        IrradianceTable {
            mapping,
            data: vec![[0.0; 3]; mapping.texels()],
        }
    }

    /// (r, mu_s) at texel (ir, imus).
    pub fn texel_r_mu_s(&self, ir: usize, imus: usize) -> (f64, f64) {
        let m = &self.mapping;
        m.r_mu_s_from_unit(
            crate::models::bruneton::parameterization::texel_unit(ir, m.r_size),
            crate::models::bruneton::parameterization::texel_unit(imus, m.mu_s_size),
        )
    }

    /// Bilinear interpolation at (r, mu_s).
    pub fn lookup(&self, r: f64, mu_s: f64) -> [f64; 3] {
        let m = &self.mapping;
        let (x_r, x_mu_s) = m.unit_from_r_mu_s(r, mu_s);
        let (ir, wr) = axis(x_r, m.r_size);
        let (im, wm) = axis(x_mu_s, m.mu_s_size);
        let geometric = m.angles.irradiance_geometric_pair(im, m.mu_s_size);
        let mut out = [0.0; 3];
        for (dr, a) in [(0, 1.0 - wr), (1, wr)] {
            if a == 0.0 {
                continue;
            }
            let (low, high) = (
                self.data[m.index(ir + dr, im)],
                self.data[m.index(ir + dr, (im + 1).min(m.mu_s_size - 1))],
            );
            for k in 0..3 {
                out[k] += a * along_mu_s(low[k] as f64, high[k] as f64, wm, geometric);
            }
        }
        out
    }

    pub fn add(&mut self, other: &IrradianceTable) {
        for (a, b) in self.data.iter_mut().zip(&other.data) {
            for k in 0..3 {
                a[k] += b[k];
            }
        }
    }
}

/// Relative densities (Rayleigh, Mie, ozone) sampled finely over altitude and linearly
/// interpolated: with 8192 samples over 60 km the step is 7.3 m, and the interpolation
/// error of exp(-h / 1.2 km) is below 5e-6 relative.
#[derive(Clone, Debug)]
pub struct DensityTable {
    step_m: f64,
    values: Vec<[f64; 3]>,
}

impl DensityTable {
    pub const SAMPLES: usize = 8192;

    pub fn new(atmosphere: &Atmosphere) -> DensityTable {
        let step_m = atmosphere.thickness_m() / (Self::SAMPLES - 1) as f64;
        DensityTable {
            step_m,
            values: (0..Self::SAMPLES)
                .map(|i| densities(atmosphere, i as f64 * step_m))
                .collect(),
        }
    }

    pub fn at(&self, altitude_m: f64) -> [f64; 3] {
        let f = (altitude_m / self.step_m).clamp(0.0, (Self::SAMPLES - 1) as f64);
        let i = (f as usize).min(Self::SAMPLES - 2);
        let w = f - i as f64;
        let (a, b) = (self.values[i], self.values[i + 1]);
        [
            a[0] + w * (b[0] - a[0]),
            a[1] + w * (b[1] - a[1]),
            a[2] + w * (b[2] - a[2]),
        ]
    }
}
