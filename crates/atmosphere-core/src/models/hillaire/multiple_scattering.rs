//! The multiple-scattering LUT Psi_ms of Hillaire 2020 (section 5.5), 32 x 32 over the
//! sun's zenith cosine mu_s in [-1, 1] and the altitude from the ground to the top.
//!
//! At a point x, light of orders two and up is approximated as isotropic, and light
//! reaching x after one scattering as if that scattering were isotropic too:
//! - L_2nd order = integral over the sphere of L'(x, -w) P_u dw, with P_u = 1 / (4 pi) and
//!   L' the single scattering (isotropic phase) along direction w, plus the ground's
//!   Lambertian reflection of the sun where the ray meets it;
//! - f_ms = integral over the sphere of L_f(x, -w) P_u dw, L_f = integral of
//!   sigma_s T dt along w: the fraction of light scattered once more towards x;
//! - F_ms = 1 + f_ms + f_ms^2 + ... = 1 / (1 - f_ms), and Psi_ms = L_2nd order F_ms.
//!
//! The sphere is sampled by 64 directions (8 x 8 strata of uniform solid angle) and each
//! ray by 20 segments, as in the paper's implementation. Values are per unit solar
//! irradiance, stored in f32 per wavelength.
//!
//! With the anisotropic setting (`ms_order` 1 or 2, `moments.rs`) the table holds
//! Psi_0..Psi_order, the moments of the multiple-scattering field about the sun, as
//! blocks of rows one above the other (the GPU's texture is stacked alike); Psi_0 is
//! then the paper's Psi_ms with the medium's phase functions at the first scattering.

use std::f64::consts::PI;

use rayon::prelude::*;

use crate::models::hillaire::medium::{
    MAX_F_MS, Medium, ground_distance, point_along, segment_weight,
};
use crate::models::hillaire::moments::{PhaseMoments, blocks, psi_moments};
use crate::optics::geometry::{distance_to_exit, ray_hits_ground};
use crate::optics::transmittance_table::{coord_from_unit, unit_from_coord};

/// L_2nd order and f_ms at one point, per wavelength, per unit solar irradiance.
#[derive(Clone, Debug, PartialEq)]
pub struct Transfer {
    pub l_2nd: Vec<f64>,
    pub f_ms: Vec<f64>,
}

impl Transfer {
    /// Psi_ms = L_2nd order / (1 - f_ms).
    pub fn psi(&self) -> Vec<f64> {
        self.l_2nd
            .iter()
            .zip(&self.f_ms)
            .map(|(l, f)| l / (1.0 - f.clamp(0.0, MAX_F_MS)))
            .collect()
    }
}

/// L_2nd order and f_ms at radius `r` with the sun at zenith cosine `mu_s`, over
/// `sqrt_directions`^2 directions of equal solid angle (cos theta in equal steps,
/// azimuth in equal steps, each stratum's centre) and `samples` segments per ray.
pub fn transfer(
    medium: &Medium,
    r: f64,
    mu_s: f64,
    sqrt_directions: usize,
    samples: usize,
) -> Transfer {
    let n = medium.wavelengths();
    let a = medium.atmosphere;
    let (bottom, top) = (a.bottom_radius_m, a.top_radius_m);
    let albedo = a.ground_albedo;
    let sin_s = (1.0 - mu_s * mu_s).max(0.0).sqrt();
    let mut l_2nd = vec![0.0; n];
    let mut f_ms = vec![0.0; n];
    let mut sun = vec![0.0; n];
    let mut throughput = vec![0.0; n];
    let directions = (sqrt_directions * sqrt_directions) as f64;
    for i in 0..sqrt_directions {
        let mu = 1.0 - 2.0 * (i as f64 + 0.5) / sqrt_directions as f64;
        let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
        let ground = ray_hits_ground(r, mu, bottom);
        let length = if ground {
            ground_distance(r, mu, bottom)
        } else {
            distance_to_exit(r, mu, top)
        };
        let dt = length / samples as f64;
        for j in 0..sqrt_directions {
            let phi = 2.0 * PI * (j as f64 + 0.5) / sqrt_directions as f64;
            let nu = mu * mu_s + sin_v * sin_s * phi.cos();
            throughput.fill(1.0);
            for k in 0..samples {
                let (r_t, mu_s_t) = point_along(r, mu, mu_s, nu, (k as f64 + 0.5) * dt);
                let rho = medium.densities(r_t);
                medium.sun_transmittance(r_t, mu_s_t, &mut sun);
                for w in 0..n {
                    let (s_r, s_m, extinction) = medium.coefficients(rho, w);
                    let (t_seg, integral) = segment_weight(extinction, dt);
                    let scattering = (s_r + s_m) * throughput[w] * integral;
                    // Isotropic phase at the first scattering; the sphere's P_u and solid
                    // angle give the 1 / directions weight below.
                    l_2nd[w] += scattering * sun[w] / (4.0 * PI);
                    f_ms[w] += scattering;
                    throughput[w] *= t_seg;
                }
            }
            if ground {
                let (_, mu_s_g) = point_along(r, mu, mu_s, nu, length);
                medium.sun_transmittance(bottom, mu_s_g, &mut sun);
                for w in 0..n {
                    l_2nd[w] += throughput[w] * sun[w] * mu_s_g.max(0.0) * albedo / PI;
                }
            }
        }
    }
    for w in 0..n {
        l_2nd[w] /= directions;
        f_ms[w] /= directions;
    }
    Transfer { l_2nd, f_ms }
}

/// The LUT Psi_ms(mu_s, h): texel centres of the first and last columns (rows) on
/// mu_s = -1 and 1 (the ground and the top), bilinear between.
#[derive(Clone, Debug, PartialEq)]
pub struct MultipleScattering {
    pub width: usize,
    pub height: usize,
    /// Highest Legendre moment held: 0 (the paper's isotropic Psi_ms), 1 or 2.
    pub order: usize,
    /// The phase functions' moments the table was built with (`moments.rs`).
    pub phase_moments: PhaseMoments,
    wavelengths: usize,
    bottom_m: f64,
    top_m: f64,
    /// Psi_l per moment block, texel (row-major, rows of altitude) and wavelength,
    /// sr^-1: index ((l * height + j) * width + i) * wavelengths + w.
    pub values: Vec<f32>,
}

impl MultipleScattering {
    /// Builds the LUT: `size` = (mu_s, altitude) texels, `sqrt_directions`^2 directions and
    /// `samples` segments per direction; moments up to `order` (0: the paper's).
    pub fn build(
        medium: &Medium,
        size: (usize, usize),
        sqrt_directions: usize,
        samples: usize,
        order: usize,
    ) -> MultipleScattering {
        let (width, height) = size;
        let n = medium.wavelengths();
        let moments = &PhaseMoments::new(&medium.atmosphere.mie.phase);
        let mut table = MultipleScattering {
            width,
            height,
            order,
            phase_moments: *moments,
            wavelengths: n,
            bottom_m: medium.atmosphere.bottom_radius_m,
            top_m: medium.atmosphere.top_radius_m,
            values: Vec::new(),
        };
        let texels: Vec<Vec<f64>> = (0..width * height)
            .into_par_iter()
            .map(|index| {
                let (r, mu_s) = table.texel_r_mu_s(index % width, index / width);
                if order == 0 {
                    transfer(medium, r, mu_s, sqrt_directions, samples).psi()
                } else {
                    psi_moments(medium, moments, r, mu_s, order, sqrt_directions, samples)
                }
            })
            .collect();
        table.values = (0..blocks(order))
            .flat_map(|l| {
                texels
                    .iter()
                    .flat_map(move |t| t[l * n..(l + 1) * n].iter().map(|v| *v as f32))
            })
            .collect();
        table
    }

    /// (r, mu_s) at the centre of texel (i, j).
    pub fn texel_r_mu_s(&self, i: usize, j: usize) -> (f64, f64) {
        let x = unit_from_coord((i as f64 + 0.5) / self.width as f64, self.width);
        let y = unit_from_coord((j as f64 + 0.5) / self.height as f64, self.height);
        (
            self.bottom_m + (self.top_m - self.bottom_m) * y,
            -1.0 + 2.0 * x,
        )
    }

    /// Psi_ms (Psi_0) stored at texel (i, j), wavelength `w`.
    pub fn texel(&self, i: usize, j: usize, w: usize) -> f64 {
        self.values[(j * self.width + i) * self.wavelengths + w] as f64
    }

    /// Psi_0..Psi_order at radius `r` and sun cosine `mu_s`: `order + 1` blocks of one
    /// value per wavelength (bilinear, clamped to the table).
    pub fn lookup(&self, r: f64, mu_s: f64, out: &mut [f64]) {
        let x = (mu_s.clamp(-1.0, 1.0) + 1.0) * 0.5;
        let y = ((r - self.bottom_m) / (self.top_m - self.bottom_m)).clamp(0.0, 1.0);
        let (i0, ax) = cell(x, self.width);
        let (j0, ay) = cell(y, self.height);
        let n = self.wavelengths;
        for l in 0..blocks(self.order) {
            let at = |i: usize, j: usize| ((l * self.height + j) * self.width + i) * n;
            let (a, b, c, d) = (
                at(i0, j0),
                at(i0 + 1, j0),
                at(i0, j0 + 1),
                at(i0 + 1, j0 + 1),
            );
            for w in 0..n {
                let v = |k: usize| self.values[k + w] as f64;
                let low = v(a) + ax * (v(b) - v(a));
                let high = v(c) + ax * (v(d) - v(c));
                out[l * n + w] = low + ay * (high - low);
            }
        }
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.values.as_slice())
    }
}

/// The texel below a unit coordinate `x` whose end texels sit on 0 and 1, and the weight
/// of the next one.
pub fn cell(x: f64, size: usize) -> (usize, f64) {
    let f = (coord_from_unit(x, size) * size as f64 - 0.5).clamp(0.0, (size - 1) as f64);
    let i = (f as usize).min(size.saturating_sub(2));
    (i, f - i as f64)
}
