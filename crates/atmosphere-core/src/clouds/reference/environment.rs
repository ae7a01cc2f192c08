//! The light around the cloud where a path leaves the layer: the sky model's radiance
//! of the ray it leaves on, tabulated once per view ray. Directions are read in the
//! frame of the point where the view ray enters the layer (its vertical `up`, the sun's
//! azimuth as azimuth 0): upward directions (mu >= 0) as the model sees them from the
//! layer's top above that point (the sky), downward ones from its base (the air below
//! and the ground, unshaded by the cloud). The table has [`MU_BINS`] cosines of the
//! zenith, finer near the horizon (mu = s |s| on a uniform s), times [`AZIMUTH_BINS`]
//! azimuths from 0 to 180 degrees (the sky is symmetric about the sun's vertical plane),
//! read bilinearly in (s, azimuth).

use glam::DVec3;

use crate::models::error::ModelError;
use crate::models::sky_model::{SkyModel, ViewRay};

/// Zenith cosines of the table, from -1 to 1.
pub const MU_BINS: usize = 65;
/// Azimuths of the table, from 0 to 180 degrees from the sun's.
pub const AZIMUTH_BINS: usize = 19;

/// The tabulated radiance around the layer.
#[derive(Clone, Debug)]
pub struct Environment {
    up: DVec3,
    /// Horizontal, towards the sun's azimuth (any horizontal for a sun at the zenith).
    towards_sun: DVec3,
    across: DVec3,
    waves: usize,
    /// `[(i_mu * AZIMUTH_BINS + j_phi) * waves + w]`.
    radiance: Vec<f64>,
}

impl Environment {
    /// The table of `sky` about the layer point `anchor` (planet-centred), for the unit
    /// `sun`, with the layer between radii `base_radius_m` and `top_radius_m`.
    pub fn new(
        sky: &dyn SkyModel,
        anchor: DVec3,
        sun: DVec3,
        base_radius_m: f64,
        top_radius_m: f64,
    ) -> Result<Environment, ModelError> {
        let up = anchor.normalize();
        let horizontal = sun - up * sun.dot(up);
        let towards_sun = horizontal
            .try_normalize()
            .unwrap_or_else(|| up.any_orthonormal_vector());
        let across = up.cross(towards_sun);
        let waves = sky.wavelengths_nm().len();
        let mut table = Environment {
            up,
            towards_sun,
            across,
            waves,
            radiance: Vec::with_capacity(MU_BINS * AZIMUTH_BINS * waves),
        };
        for i in 0..MU_BINS {
            let s = -1.0 + 2.0 * i as f64 / (MU_BINS - 1) as f64;
            let mu = s * s.abs();
            for j in 0..AZIMUTH_BINS {
                let phi = std::f64::consts::PI * j as f64 / (AZIMUTH_BINS - 1) as f64;
                let direction = table.direction(mu, phi);
                let radius = if mu >= 0.0 {
                    top_radius_m
                } else {
                    base_radius_m
                };
                let answer = sky.radiance(&ViewRay {
                    origin_m: up * radius,
                    direction,
                    sun_direction: sun,
                    max_distance_m: None,
                })?;
                table.radiance.extend(answer.radiance);
            }
        }
        Ok(table)
    }

    fn direction(&self, mu: f64, phi: f64) -> DVec3 {
        let sin = (1.0 - mu * mu).max(0.0).sqrt();
        (self.up * mu + (self.towards_sun * phi.cos() + self.across * phi.sin()) * sin).normalize()
    }

    /// The radiance arriving from the unit `direction` (the way the path goes), per
    /// wavelength, into `out`.
    pub fn radiance(&self, direction: DVec3, out: &mut [f64]) {
        let mu = direction.dot(self.up).clamp(-1.0, 1.0);
        let s = mu.signum() * mu.abs().sqrt();
        let x = direction.dot(self.towards_sun);
        let y = direction.dot(self.across).abs();
        let phi = y.atan2(x);
        let fi = ((s + 1.0) / 2.0 * (MU_BINS - 1) as f64).clamp(0.0, (MU_BINS - 1) as f64);
        let fj = (phi / std::f64::consts::PI * (AZIMUTH_BINS - 1) as f64)
            .clamp(0.0, (AZIMUTH_BINS - 1) as f64);
        let i0 = (fi as usize).min(MU_BINS - 2);
        let j0 = (fj as usize).min(AZIMUTH_BINS - 2);
        let (a, b) = (fi - i0 as f64, fj - j0 as f64);
        let at =
            |i: usize, j: usize, w: usize| self.radiance[(i * AZIMUTH_BINS + j) * self.waves + w];
        for (w, o) in out.iter_mut().enumerate().take(self.waves) {
            let low = at(i0, j0, w) * (1.0 - b) + at(i0, j0 + 1, w) * b;
            let high = at(i0 + 1, j0, w) * (1.0 - b) + at(i0 + 1, j0 + 1, w) * b;
            *o = low * (1.0 - a) + high * a;
        }
    }
}
