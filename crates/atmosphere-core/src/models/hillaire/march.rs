//! The view ray march of Hillaire 2020 (section 5, "Ray marching"): along a view ray,
//! light scattered towards the camera at each sample is
//! sigma_s(x) (T(x, sun) p(nu) + Psi_ms(x)) E_sun, the single scattering of the point
//! sun plus the multiple-scattering transfer Psi_ms read from its LUT (section 5.5), each
//! segment integrated with [`segment_weight`]. The sky-view LUT, the aerial-perspective
//! volume, the ground's sky light and the per-pixel march all run this step.
//!
//! With a similarity-scaled medium (`Medium::diffuse`, `similarity.rs`) every
//! transmittance of the light, the sun's to the sample and the sample's to the camera, is
//! the scaled medium's, single scattering keeps the true scattering coefficients and
//! phase functions (Nakajima and Tanaka 1988's truncated single scattering), and the
//! multiple-scattering term is scattered with the scaled coefficients; the transmittance
//! the march reports stays the true medium's.
//!
//! Radiance here is per unit solar irradiance (sr^-1); the model multiplies by E_sun.

use crate::models::hillaire::medium::{Medium, coefficients, point_along, segment_weight};
use crate::models::hillaire::moments;
use crate::models::hillaire::multiple_scattering::MultipleScattering;
use crate::optics::phase::rayleigh;

/// The per-sample integrand of a view ray: the medium, the multiple-scattering LUT (none
/// for single scattering) and the phase functions at the ray's scattering angle.
#[derive(Debug)]
pub struct ViewMarch<'a> {
    medium: Medium<'a>,
    multiple: Option<&'a MultipleScattering>,
    /// Ray from radius `r` with direction cosine `mu`, sun cosine `mu_s`, view-sun cosine `nu`.
    r: f64,
    mu: f64,
    mu_s: f64,
    nu: f64,
    phase_rayleigh: f64,
    phase_mie: f64,
    /// Radiance so far per unit solar irradiance, and the throughput from the start.
    pub radiance: Vec<f64>,
    pub throughput: Vec<f64>,
    /// Throughput of the scaled medium, which the light takes (`Medium::diffuse`).
    diffuse_throughput: Vec<f64>,
    sun: Vec<f64>,
    psi: Vec<f64>,
}

impl<'a> ViewMarch<'a> {
    /// A march starting at radius `r` along a ray of direction cosine `mu`, with the sun at
    /// cosine `mu_s` to the local zenith and `nu` to the ray.
    pub fn new(
        medium: Medium<'a>,
        multiple: Option<&'a MultipleScattering>,
        r: f64,
        mu: f64,
        mu_s: f64,
        nu: f64,
    ) -> ViewMarch<'a> {
        let n = medium.wavelengths();
        let blocks = multiple.map_or(1, |m| moments::blocks(m.order));
        let phase_mie = if medium.mie {
            medium.atmosphere.mie.phase.eval(nu)
        } else {
            0.0
        };
        ViewMarch {
            medium,
            multiple,
            r,
            mu,
            mu_s,
            nu,
            phase_rayleigh: rayleigh(nu),
            phase_mie,
            radiance: vec![0.0; n],
            throughput: vec![1.0; n],
            diffuse_throughput: vec![1.0; n],
            sun: vec![0.0; n],
            psi: vec![0.0; blocks * n],
        }
    }

    /// Integrates the segment [t_mid - dt/2, t_mid + dt/2] with the medium of its midpoint.
    pub fn segment(&mut self, t_mid: f64, dt: f64) {
        let (r_t, mu_s_t) = point_along(self.r, self.mu, self.mu_s, self.nu, t_mid);
        let mu_t = ((self.r * self.mu + t_mid) / r_t).clamp(-1.0, 1.0);
        let rho = self.medium.densities(r_t);
        if rho == [0.0; 3] {
            return;
        }
        let light = self.medium.diffuse.unwrap_or(self.medium.spectra);
        self.medium
            .sun_transmittance_in(light, r_t, mu_s_t, &mut self.sun);
        if let Some(ms) = self.multiple {
            ms.lookup(r_t, mu_s_t, &mut self.psi);
        }
        let n = self.radiance.len();
        for w in 0..n {
            let (s_r, s_m, extinction) = self.medium.coefficients(rho, w);
            let (t_seg, integral) = segment_weight(extinction, dt);
            let single = self.sun[w] * (s_r * self.phase_rayleigh + s_m * self.phase_mie);
            let scaled = self.medium.diffuse.map(|d| coefficients(d, rho, w));
            let multiple = match (self.multiple, scaled) {
                (None, _) => 0.0,
                (Some(ms), None) if ms.order == 0 => self.psi[w] * (s_r + s_m),
                (Some(_), Some((s_r, s_m, _))) => self.psi[w] * (s_r + s_m),
                (Some(ms), None) => {
                    let psi = std::array::from_fn(|l| {
                        if l < moments::blocks(ms.order) {
                            self.psi[l * n + w]
                        } else {
                            0.0
                        }
                    });
                    let angles = (self.nu, mu_t, mu_s_t);
                    moments::source(psi, ms.order, angles, &ms.phase_moments, s_r, s_m)
                }
            };
            match scaled {
                None => self.radiance[w] += self.throughput[w] * (single + multiple) * integral,
                Some((_, _, scaled_extinction)) => {
                    let (t_light, integral_light) = segment_weight(scaled_extinction, dt);
                    self.radiance[w] +=
                        self.diffuse_throughput[w] * (single + multiple) * integral_light;
                    self.diffuse_throughput[w] *= t_light;
                }
            }
            self.throughput[w] *= t_seg;
        }
    }

    /// Marches `length` metres in `samples` equal segments, each sampled at its midpoint.
    pub fn run(&mut self, length: f64, samples: usize) {
        let dt = length / samples as f64;
        for k in 0..samples {
            self.segment((k as f64 + 0.5) * dt, dt);
        }
    }
}
