//! The medium along a ray and the ray-march step shared by every table and by the
//! per-pixel march of Hillaire 2020: scattering and extinction from the densities, the
//! sun's transmittance from the transmittance LUT (section 5.1, the shared table of
//! Bruneton 2017's mapping), and the energy-conserving integration of a segment
//! (Hillaire 2015, "Physically based and unified volumetric rendering", which the paper's
//! ray marches use): with the medium constant over a segment of length dt, the light
//! scattered towards the camera is S (1 - exp(-sigma_t dt)) / sigma_t, exact for any
//! optical thickness of the segment.

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::optics::column::{densities, optical_depth};
use crate::optics::geometry::{radius_at, ray_hits_ground};
use crate::optics::transmittance_table::TransmittanceTable;

/// Largest f_ms used in F_ms = 1 / (1 - f_ms). f_ms < 1 holds exactly (it is at most the
/// sphere's mean of 1 - T); the bound only guards against rounding in opaque atmospheres.
pub const MAX_F_MS: f64 = 1.0 - 1e-6;

/// The transmittance of a segment with extinction `extinction` (m^-1) and length `dt`,
/// and the integral of the transmittance from the segment's start over its length (m):
/// (exp(-sigma_t dt), (1 - exp(-sigma_t dt)) / sigma_t), the second `dt` without
/// extinction.
pub fn segment_weight(extinction: f64, dt: f64) -> (f64, f64) {
    if extinction > 0.0 {
        let lost = -(-extinction * dt).exp_m1();
        (1.0 - lost, lost / extinction)
    } else {
        (1.0, dt)
    }
}

/// The atmosphere as the ray marches see it.
#[derive(Clone, Copy, Debug)]
pub struct Medium<'a> {
    pub atmosphere: &'a Atmosphere,
    pub spectra: &'a Spectra,
    pub transmittance: &'a TransmittanceTable,
    /// False when the Mie terms are left out (`ModelSettings::prune` at zero aerosol): the
    /// Mie density is then taken as 0, which changes no sum (its coefficients are 0).
    pub mie: bool,
    /// The coefficients that orders two and up see along a view ray, when they differ
    /// from `spectra`: the similarity-scaled medium (`similarity.rs`, the setting `ms_delta`).
    pub diffuse: Option<&'a Spectra>,
}

impl Medium<'_> {
    /// Number of wavelengths.
    pub fn wavelengths(&self) -> usize {
        self.spectra.wavelengths_nm.len()
    }

    /// Relative densities (Rayleigh, Mie, ozone) at radius `r`; zero above the top of the
    /// atmosphere (the profiles themselves go on), the ground's below it.
    pub fn densities(&self, r: f64) -> [f64; 3] {
        if r > self.atmosphere.top_radius_m {
            return [0.0; 3];
        }
        let mut rho = densities(
            self.atmosphere,
            (r - self.atmosphere.bottom_radius_m).max(0.0),
        );
        if !self.mie {
            rho[1] = 0.0;
        }
        rho
    }

    /// Transmittance from radius `r` towards a point sun at direction cosine `mu_s` to the
    /// local zenith, per wavelength, from the transmittance LUT; 0 where the planet hides
    /// the sun (the paper's point sun and planet shadow). Radii outside the atmosphere are
    /// clamped to it.
    pub fn sun_transmittance(&self, r: f64, mu_s: f64, out: &mut [f64]) {
        self.sun_transmittance_in(self.spectra, r, mu_s, out);
    }

    /// [`Medium::sun_transmittance`] through a medium of coefficients `spectra` (the
    /// table holds columns of matter, so any coefficients read it).
    pub fn sun_transmittance_in(&self, spectra: &Spectra, r: f64, mu_s: f64, out: &mut [f64]) {
        let bottom = self.atmosphere.bottom_radius_m;
        let r = r.clamp(bottom, self.atmosphere.top_radius_m);
        let mu_s = mu_s.clamp(-1.0, 1.0);
        if ray_hits_ground(r, mu_s, bottom) {
            out.fill(0.0);
            return;
        }
        let column = self.transmittance.column(r, mu_s);
        for (o, e) in out.iter_mut().zip(&spectra.extinction) {
            *o = (-optical_depth(column, *e)).exp();
        }
    }

    /// Scattering (Rayleigh, Mie) and extinction coefficients at wavelength `w` for
    /// densities `rho`, m^-1.
    pub fn coefficients(&self, rho: [f64; 3], w: usize) -> (f64, f64, f64) {
        coefficients(self.spectra, rho, w)
    }
}

/// Scattering (Rayleigh, Mie) and extinction coefficients of `spectra` at wavelength `w`
/// for densities `rho`, m^-1.
pub fn coefficients(spectra: &Spectra, rho: [f64; 3], w: usize) -> (f64, f64, f64) {
    (
        spectra.rayleigh_scattering[w] * rho[0],
        spectra.mie_scattering[w] * rho[1],
        optical_depth(rho, spectra.extinction[w]),
    )
}

/// A point at distance `t` along the ray from (r, mu) whose sun cosine is `mu_s` and
/// whose view-sun cosine is `nu`: its radius and its own sun cosine.
pub fn point_along(r: f64, mu: f64, mu_s: f64, nu: f64, t: f64) -> (f64, f64) {
    let r_t = radius_at(r, mu, t);
    let mu_s_t = if r_t > 0.0 {
        ((r * mu_s + t * nu) / r_t).clamp(-1.0, 1.0)
    } else {
        mu_s
    };
    (r_t, mu_s_t)
}

/// Distance from radius `r` along a ray with direction cosine `mu` to the ground, for a
/// ray at or below the horizon; a tangent ray (and rounding around it) gives the distance
/// to the tangent point, so that rays just below the horizon end continuously.
pub fn ground_distance(r: f64, mu: f64, bottom: f64) -> f64 {
    let disc = (r * mu) * (r * mu) - (r - bottom) * (r + bottom);
    let q = -r * mu + disc.max(0.0).sqrt();
    if q > 0.0 {
        ((r - bottom) * (r + bottom) / q).max(0.0)
    } else {
        0.0
    }
}
