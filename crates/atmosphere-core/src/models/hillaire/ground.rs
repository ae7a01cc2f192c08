//! The ground's light: a Lambertian surface of albedo rho reflects
//! rho / pi (E_sun T(x, sun) max(mu_s, 0) + E_sky(mu_s)) (Hillaire 2020 section 5, the
//! planet's surface lit by the sun and by the sky).
//!
//! The paper lights surfaces with the sky through a sky-light capture rendered from its
//! LUTs, which is the engine's work, not the paper's tables. On the CPU the sky's
//! irradiance at the ground is a small table E_sky(mu_s), 32 values over mu_s in [-1, 1]
//! at equal steps of x = sign(mu_s) sqrt(|mu_s|) (values crowd around the horizon, where
//! the sky's light falls fastest as the sun sets), each the cosine-weighted integral of the sky's radiance over the upper hemisphere,
//! with that radiance from the same view march as the sky-view LUT (single scattering
//! plus Psi_ms): 8 Gauss-Legendre nodes in the zenith cosine times 8 azimuths over half
//! the circle (the sky is symmetric about the sun's vertical plane).

use std::f64::consts::PI;

use rayon::prelude::*;

use crate::models::hillaire::directions::view_sun_cosine;
use crate::models::hillaire::march::ViewMarch;
use crate::models::hillaire::medium::Medium;
use crate::models::hillaire::multiple_scattering::{MultipleScattering, cell};
use crate::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};
use crate::optics::geometry::distance_to_exit;
use crate::optics::transmittance_table::unit_from_coord;

/// Quadrature of the hemisphere for [`GroundIrradiance`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HemisphereQuadrature {
    /// Panels of 8-point Gauss-Legendre over the zenith cosine in [0, 1].
    pub zenith_panels: usize,
    /// Azimuths over [0, pi], each at the centre of an equal step.
    pub azimuths: usize,
    /// Segments of each ray's march.
    pub samples: usize,
}

/// The sky's irradiance at the ground per unit solar irradiance, over the sun's zenith
/// cosine; f32 per wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct GroundIrradiance {
    pub size: usize,
    wavelengths: usize,
    pub values: Vec<f32>,
}

/// E_sky / E_sun at the ground for a sun at zenith cosine `mu_s`, per wavelength.
pub fn sky_irradiance(
    medium: &Medium,
    multiple: Option<&MultipleScattering>,
    mu_s: f64,
    quadrature: HemisphereQuadrature,
) -> Vec<f64> {
    let n = medium.wavelengths();
    let a = medium.atmosphere;
    let r = a.bottom_radius_m;
    let mut e = vec![0.0; n];
    let panels = quadrature.zenith_panels;
    let d_phi = PI / quadrature.azimuths as f64;
    for p in 0..panels {
        let (lo, hi) = (p as f64 / panels as f64, (p + 1) as f64 / panels as f64);
        for (mu, weight) in mapped(&GAUSS_LEGENDRE_8, lo, hi) {
            let length = distance_to_exit(r, mu, a.top_radius_m);
            for k in 0..quadrature.azimuths {
                let phi = (k as f64 + 0.5) * d_phi;
                let nu = view_sun_cosine(mu, phi, mu_s);
                let mut march = ViewMarch::new(*medium, multiple, r, mu, mu_s, nu);
                march.run(length, quadrature.samples);
                // Both halves of the circle: 2 d_phi.
                for w in 0..n {
                    e[w] += march.radiance[w] * mu * weight * 2.0 * d_phi;
                }
            }
        }
    }
    e
}

impl GroundIrradiance {
    /// Builds the table of `size` values, the first and last on mu_s = -1 and 1.
    pub fn build(
        medium: &Medium,
        multiple: Option<&MultipleScattering>,
        size: usize,
        quadrature: HemisphereQuadrature,
    ) -> GroundIrradiance {
        let values = (0..size)
            .into_par_iter()
            .flat_map_iter(|i| {
                let x = -1.0 + 2.0 * unit_from_coord((i as f64 + 0.5) / size as f64, size);
                let mu_s = x * x.abs();
                sky_irradiance(medium, multiple, mu_s, quadrature)
                    .into_iter()
                    .map(|v| v as f32)
            })
            .collect();
        GroundIrradiance {
            size,
            wavelengths: medium.wavelengths(),
            values,
        }
    }

    /// E_sky / E_sun at sun cosine `mu_s`, per wavelength: geometric interpolation
    /// between positive values (the sky's light falls nearly exponentially as the sun
    /// sinks; linear interpolation made the ground 2.6 times too bright with the sun 6°
    /// below the horizon), linear where a value is zero.
    pub fn lookup(&self, mu_s: f64, out: &mut [f64]) {
        let mu_s = mu_s.clamp(-1.0, 1.0);
        let x = mu_s.signum() * mu_s.abs().sqrt();
        let (i, a) = cell((x + 1.0) * 0.5, self.size);
        let n = self.wavelengths;
        for w in 0..n {
            let lo = self.values[i * n + w] as f64;
            let hi = self.values[(i + 1) * n + w] as f64;
            out[w] = if lo > 0.0 && hi > 0.0 {
                lo * (hi / lo).powf(a)
            } else {
                lo + a * (hi - lo)
            };
        }
    }

    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.values.as_slice())
    }
}
