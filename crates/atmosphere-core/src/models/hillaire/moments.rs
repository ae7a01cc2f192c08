//! The multiple-scattering term beyond isotropy: Legendre moments about the sun of the
//! light that has scattered at least once, a setting beside Hillaire 2020's isotropic
//! Psi_ms (section 5.5; docs/models/hillaire.md, "Anisotropic multiple scattering").
//!
//! Let L(x, w) be the radiance at x arriving from direction w after one or more
//! scatterings, and c = w . s the cosine between that direction and the sun's. Its
//! moments about the sun are L_l(x) = integral over the sphere of L(x, w) P_l(c) dw, and
//! Psi_l = L_l / (4 pi) (Psi_0 is the paper's Psi_ms). By the Funk-Hecke theorem a
//! phase function p(t) = sum (2l + 1) / (4 pi) g_l P_l(t), g_l = 2 pi integral of
//! p(t) P_l(t) dt (g_0 = 1), scatters the part of L symmetric about the sun towards a
//! camera looking along d (nu = d . s) as
//!   J(nu) = sum_l (2l + 1) g_l Psi_l P_l(nu).
//! - Rayleigh has g_1 = 0 and g_2 = 1/10: J_R = Psi_0 + Psi_2 P_2(nu) / 2, exact with
//!   two moments.
//! - Mie's forward peak needs many: the series cut at l = 2 smears it over the sky. The
//!   field is instead taken as an isotropic part and a Henyey-Greenstein lobe about the
//!   sun, L / L_0 = (1 - a) / (4 pi) + a HG(g_f, c), whose moments are a g_f^l
//!   (Psi_1 / Psi_0 = a g_f, Psi_2 / Psi_0 = a g_f^2). The Mie phase function taken as
//!   HG with its own g_1 (its g_2 differs from g_1^2 by under 1 % for Cornette-Shanks
//!   g = 0.8), the convolution of two HG lobes is the lobe of the product of their g
//!   (their Legendre moments multiply), so J_M = Psi_0 ((1 - a) + a 4 pi HG(g_f g_1, nu)):
//!   never negative, and as peaked as the aureole it comes from.
//!
//! - Near the ground the field is also brightest from near-horizontal directions (long
//!   paths), a structure symmetric about the zenith: with order 2 a fourth moment
//!   Psi_2z = (1/4 pi) integral of L P_2(mu) is kept, less the sun-symmetric part's
//!   share of it, Psi_2 P_2(mu_s) (addition theorem); the rest adds
//!   5 g_2 (Psi_2z - Psi_2 P_2(mu_s)) P_2(mu) to each scatterer's J, mu the view
//!   direction's zenith cosine at the sample (Mie's J clamped at 0).
//!
//! Psi_l at a texel: the once-scattered light with the medium's own phase functions (the
//! paper takes the first scattering as isotropic too), its moments over directions
//! crowded around the sun, divided by 1 - f_l: the paper's geometric series of orders,
//! F_ms = 1 / (1 - f_ms), per Legendre component, since one more scattering turns a
//! field component P_l(c) into g_l P_l(c) (Funk-Hecke again): f_l is f_ms with sigma_s
//! replaced by sigma_R g_l^R + sigma_M g_l^M.

use std::f64::consts::PI;

use crate::models::hillaire::medium::{
    MAX_F_MS, Medium, ground_distance, point_along, segment_weight,
};
use crate::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};
use crate::optics::geometry::{distance_to_exit, ray_hits_ground};
use crate::optics::phase::{PhaseFunction, rayleigh};

/// Highest Legendre order of the anisotropic term.
pub const MAX_ORDER: usize = 2;

/// Blocks of Psi held for `order`: Psi_0..Psi_order about the sun and, with order 2, the
/// second moment about the local zenith.
pub fn blocks(order: usize) -> usize {
    if order >= 2 { order + 2 } else { order + 1 }
}

/// Legendre polynomials P_0, P_1, P_2 at `t`.
pub fn legendre(t: f64) -> [f64; MAX_ORDER + 1] {
    [1.0, t, 0.5 * (3.0 * t * t - 1.0)]
}

/// The moments g_0, g_1, g_2 of a phase function: 2 pi times the integral over the
/// scattering angle's cosine t of p(t) P_l(t) (g_0 = 1 for a normalised function), by
/// 512 Gauss-Legendre panels in the angle so that forward peaks are resolved.
pub fn phase_moments(phase: impl Fn(f64) -> f64) -> [f64; MAX_ORDER + 1] {
    const PANELS: usize = 512;
    let mut g = [0.0; MAX_ORDER + 1];
    for k in 0..PANELS {
        let (a, b) = (
            PI * k as f64 / PANELS as f64,
            PI * (k + 1) as f64 / PANELS as f64,
        );
        for (theta, weight) in mapped(&GAUSS_LEGENDRE_8, a, b) {
            let t = theta.cos();
            let p = 2.0 * PI * phase(t) * theta.sin() * weight;
            for (gl, pl) in g.iter_mut().zip(legendre(t)) {
                *gl += p * pl;
            }
        }
    }
    g
}

/// The phase moments of both scatterers: Rayleigh's (1, 0, 1/10) and the Mie phase
/// function's, computed once per atmosphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseMoments {
    pub rayleigh: [f64; MAX_ORDER + 1],
    pub mie: [f64; MAX_ORDER + 1],
}

impl PhaseMoments {
    /// The moments of Rayleigh's and of `mie`; g_0 = 1 exactly (phase functions are
    /// normalised; the quadrature's rounding is left out).
    pub fn new(mie: &PhaseFunction) -> PhaseMoments {
        let mut moments = phase_moments(|t| mie.eval(t));
        moments[0] = 1.0;
        PhaseMoments {
            rayleigh: [1.0, 0.0, 0.1],
            mie: moments,
        }
    }
}

/// Largest |g_f| of the lobe.
pub const MAX_LOBE_G: f64 = 0.99;

/// The lobe (a, g_f) of a field with moments `psi` = Psi_0, Psi_1, Psi_2, of which the
/// first `order` + 1 are known: with Psi_1 / Psi_0 = r_1 > 0 and order 2, g_f = Psi_2 /
/// Psi_1 (at least r_1, so that a <= 1; at most [`MAX_LOBE_G`]) and a = r_1 / g_f;
/// otherwise the whole field is one lobe of g_f = r_1 (a = 1; backwards for r_1 < 0).
/// No lobe without light (Psi_0 <= 0).
pub fn lobe(psi: [f64; MAX_ORDER + 1], order: usize) -> (f64, f64) {
    if psi[0] <= 0.0 {
        return (0.0, 0.0);
    }
    let r1 = (psi[1] / psi[0]).clamp(-MAX_LOBE_G, MAX_LOBE_G);
    let g = if order >= 2 && r1 > 0.0 {
        (psi[2] / psi[0] / r1).clamp(r1, MAX_LOBE_G)
    } else {
        r1
    };
    let a = if g != 0.0 { r1 / g } else { 0.0 };
    (a, g)
}

/// The multiple-scattering source per unit solar irradiance at a sample whose view
/// direction has cosines `nu` to the sun and `mu` to the zenith, the sun `mu_s` to the
/// zenith, for scattering coefficients `s_r` (Rayleigh) and `s_m` (Mie), from the
/// [`blocks`] of Psi (`psi`, zero beyond them): Rayleigh's two-moment sum plus Mie's
/// lobe, and with order 2 the zenith's second moment less the sun-symmetric part's share
/// of it, Psi_2z - Psi_2 P_2(mu_s) (addition theorem), scattered as 5 g_2 (.) P_2(mu);
/// Mie's part clamped at 0.
pub fn source(
    psi: [f64; MAX_ORDER + 2],
    order: usize,
    (nu, mu, mu_s): (f64, f64, f64),
    moments: &PhaseMoments,
    s_r: f64,
    s_m: f64,
) -> f64 {
    let (a, g_f) = lobe([psi[0], psi[1], psi[2]], order);
    let g = g_f * moments.mie[1];
    let d = 1.0 + g * g - 2.0 * g * nu;
    let lobe = (1.0 - g * g) / (d * d.sqrt());
    let zenith = 5.0 * (psi[3] - psi[2] * legendre(mu_s)[2]) * legendre(mu)[2];
    let rayleigh = psi[0]
        + 5.0 * moments.rayleigh[2] * legendre(nu)[2] * psi[2]
        + moments.rayleigh[2] * zenith;
    s_r * rayleigh + s_m * (psi[0] * ((1.0 - a) + a * lobe) + moments.mie[2] * zenith).max(0.0)
}

/// The unit direction i, j of `sqrt_directions`^2 about the sun, in the frame whose z is
/// the local zenith and whose sun is (sin_s, 0, mu_s): its cosine c to the sun at
/// u = (i + 1/2) / n with c = 1 - 2 u^2 (rings crowding around the sun, where forward
/// peaks are), azimuth about the sun at equal steps; and its share of the sphere,
/// 2 u / n^2 (the rings' solid angle 4 pi * 4 u du / (4 pi) per azimuth).
/// Returns (zenith cosine, sun cosine, weight).
pub fn sun_direction(i: usize, j: usize, n: usize, mu_s: f64) -> (f64, f64, f64) {
    let u = (i as f64 + 0.5) / n as f64;
    let c = 1.0 - 2.0 * u * u;
    let sin_c = (1.0 - c * c).max(0.0).sqrt();
    let psi = 2.0 * PI * (j as f64 + 0.5) / n as f64;
    let sin_s = (1.0 - mu_s * mu_s).max(0.0).sqrt();
    // w = c s + sin_c (cos psi e1 + sin psi e2), e1 = (mu_s, 0, -sin_s), e2 = y.
    let mu = (c * mu_s - sin_c * psi.cos() * sin_s).clamp(-1.0, 1.0);
    (mu, c, 2.0 * u / (n * n) as f64)
}

/// Psi_0..Psi_`order` at radius `r` with the sun at zenith cosine `mu_s`, per unit solar
/// irradiance: `order + 1` blocks of one value per wavelength.
pub fn psi_moments(
    medium: &Medium,
    moments: &PhaseMoments,
    r: f64,
    mu_s: f64,
    order: usize,
    sqrt_directions: usize,
    samples: usize,
) -> Vec<f64> {
    let n = medium.wavelengths();
    let a = medium.atmosphere;
    let (bottom, top) = (a.bottom_radius_m, a.top_radius_m);
    let mie_phase = |c: f64| {
        if medium.mie { a.mie.phase.eval(c) } else { 0.0 }
    };
    let blocks = blocks(order);
    // Mean over the sphere of L P_l (= Psi_l before the series) and of the transfer f_l.
    let mut mean = vec![0.0; blocks * n];
    let mut transfer = vec![0.0; blocks * n];
    let mut sun = vec![0.0; n];
    let mut throughput = vec![0.0; n];
    let mut radiance = vec![0.0; n];
    let mut returned = vec![0.0; blocks * n];
    for i in 0..sqrt_directions {
        for j in 0..sqrt_directions {
            let (mu, c, weight) = sun_direction(i, j, sqrt_directions, mu_s);
            let (p_r, p_m) = (rayleigh(c), mie_phase(c));
            let ground = ray_hits_ground(r, mu, bottom);
            let length = if ground {
                ground_distance(r, mu, bottom)
            } else {
                distance_to_exit(r, mu, top)
            };
            let dt = length / samples as f64;
            throughput.fill(1.0);
            radiance.fill(0.0);
            returned.fill(0.0);
            for k in 0..samples {
                let (r_t, mu_s_t) = point_along(r, mu, mu_s, c, (k as f64 + 0.5) * dt);
                let rho = medium.densities(r_t);
                medium.sun_transmittance(r_t, mu_s_t, &mut sun);
                for w in 0..n {
                    let (s_r, s_m, extinction) = medium.coefficients(rho, w);
                    let (t_seg, integral) = segment_weight(extinction, dt);
                    let reach = throughput[w] * integral;
                    radiance[w] += (s_r * p_r + s_m * p_m) * sun[w] * reach;
                    for l in 0..blocks {
                        let k = l.min(2);
                        returned[l * n + w] +=
                            (s_r * moments.rayleigh[k] + s_m * moments.mie[k]) * reach;
                    }
                    throughput[w] *= t_seg;
                }
            }
            if ground {
                let (_, mu_s_g) = point_along(r, mu, mu_s, c, length);
                medium.sun_transmittance(bottom, mu_s_g, &mut sun);
                for w in 0..n {
                    radiance[w] += throughput[w] * sun[w] * mu_s_g.max(0.0) * a.ground_albedo / PI;
                }
            }
            let sun_p = legendre(c);
            let p = [sun_p[0], sun_p[1], sun_p[2], legendre(mu)[2]];
            for l in 0..blocks {
                for w in 0..n {
                    mean[l * n + w] += weight * radiance[w] * p[l];
                    transfer[l * n + w] += weight * returned[l * n + w];
                }
            }
        }
    }
    mean.iter()
        .zip(&transfer)
        .map(|(m, f)| m / (1.0 - f.clamp(-MAX_F_MS, MAX_F_MS)))
        .collect()
}
