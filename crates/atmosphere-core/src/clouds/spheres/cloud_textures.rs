//! The cloud textures T_i of Dobashi, Yamamoto and Nishita 2002, section 5.4: each cloud
//! sphere carries the density of its part of the cloud at each texel of the cover's
//! equirectangular grid. Here texel (i, j) of sphere k holds the vertical optical depth
//! of shell k above that texel,
//!     tau_k = extinction_per_m (1 - s / 2) c H int_(k/m)^((k+1)/m) P(x, c) dx,
//! with c the texel's cover times `coverage_scale` (clamped to 1), H the layer's
//! thickness, P the layer's vertical profile (`layer/profile.rs`) and 1 - s / 2 the mean
//! erosion of its detail noise of strength s: the volume layer's density integrated over
//! the shell, so the spheres and the volume hold the same cloud. The paper takes a
//! constant density; the profile's integral over c is tabulated at [`COVER_STEPS`] + 1
//! covers and read linearly. Read bilinearly as the cover is (`geo/equirectangular.rs`).

use glam::DVec3;

use super::shells::Shells;
use crate::clouds::error::CloudError;
use crate::clouds::layer::field::CloudLayer;
use crate::clouds::layer::profile::vertical_profile;
use crate::geo::equirectangular::{bilinear_taps, lat_lon};

/// Covers at which the profile's integral is tabulated, minus one.
pub const COVER_STEPS: usize = 256;
/// Midpoints per shell of the profile's integral.
const PROFILE_STEPS: usize = 256;

/// The m cloud textures on the cover's grid.
#[derive(Clone, Debug, PartialEq)]
pub struct CloudTextures {
    width: usize,
    height: usize,
    count: usize,
    shell_thickness_m: f64,
    /// `[k][j][i]`: vertical optical depth of shell k over texel (i, j).
    depths: Vec<f32>,
}

impl CloudTextures {
    /// The textures of `layer`'s cloud cut into `shells` (whose base and thickness are
    /// the layer's).
    pub fn new(layer: &CloudLayer, shells: &Shells) -> Result<CloudTextures, CloudError> {
        let s = layer.settings();
        let (base, _) = s.radii_m(shells.ground_radius_m);
        if (base - shells.base_radius_m).abs() > 1e-6 || s.thickness_m != shells.thickness_m {
            return Err(CloudError(format!(
                "cloud spheres: shells from {} m, {} m thick, for a layer from {} m, {} m thick",
                shells.base_radius_m, shells.thickness_m, base, s.thickness_m
            )));
        }
        let count = shells.count as usize;
        let cover = layer.cover();
        let (width, height) = (cover.width(), cover.height());
        let scale = s.extinction_per_m * (1.0 - s.detail_strength / 2.0) * s.thickness_m;
        let mut depths = Vec::with_capacity(count * width * height);
        for k in 0..count {
            let table = profile_integrals(k, count);
            depths.extend(cover.values().iter().map(|&v| {
                let c = (f64::from(v) * s.coverage_scale).min(1.0);
                let x = c * COVER_STEPS as f64;
                let n = (x.floor() as usize).min(COVER_STEPS - 1);
                let f = x - n as f64;
                let integral = table[n] * (1.0 - f) + table[n + 1] * f;
                (scale * c * integral) as f32
            }));
        }
        Ok(CloudTextures {
            width,
            height,
            count,
            shell_thickness_m: shells.shell_thickness_m(),
            depths,
        })
    }

    pub fn width(&self) -> usize {
        self.width
    }

    pub fn height(&self) -> usize {
        self.height
    }

    /// The texels, `[k][j][i]`, row-major, north first: what the GPU's buffer holds.
    pub fn values(&self) -> &[f32] {
        &self.depths
    }

    /// The vertical optical depth of shell `k` at the planet-fixed `point`, bilinear.
    pub fn depth(&self, k: usize, point: DVec3) -> f64 {
        let (lat, lon) = lat_lon(point);
        let layer = &self.depths[k.min(self.count - 1) * self.width * self.height..];
        bilinear_taps(self.width, self.height, lat, lon)
            .iter()
            .map(|&(n, w)| w * f64::from(layer[n]))
            .sum()
    }

    /// The mean extinction of shell `k` at `point`, m^-1.
    pub fn extinction(&self, k: usize, point: DVec3) -> f64 {
        self.depth(k, point) / self.shell_thickness_m
    }
}

/// int over shell `k` of `count` of P(x, c) dx at c = n / COVER_STEPS, n = 0 to
/// COVER_STEPS, by the midpoint rule.
fn profile_integrals(k: usize, count: usize) -> Vec<f64> {
    let (lo, hi) = (k as f64 / count as f64, (k + 1) as f64 / count as f64);
    let dx = (hi - lo) / PROFILE_STEPS as f64;
    (0..=COVER_STEPS)
        .map(|n| {
            let c = n as f64 / COVER_STEPS as f64;
            (0..PROFILE_STEPS)
                .map(|q| vertical_profile(lo + (q as f64 + 0.5) * dx, c) * dx)
                .sum()
        })
        .collect()
}
