//! The phase function of large water drops by geometric optics (van de Hulst 1957,
//! chapter 12 and section 13.2): a ray striking a sphere at impact parameter b = sin i
//! (radius 1) leaves after p chords (p = 0: reflected outside; p = 1: transmitted; p = 2:
//! one internal reflection, the primary bow; p = 3: the secondary) deviated by
//!     D_0 = pi - 2 i,   D_p = 2 (i - r) + (p - 1) (pi - 2 r),   sin i = n sin r,
//! carrying, per polarisation, R for p = 0 and (1 - R)^2 R^(p - 1) otherwise (Fresnel's
//! R at incidence i, the same inside at r). Rays fall uniformly on the drop's disc (b^2
//! uniform); each carries unit weight to geometric optics and unit weight to
//! diffraction (the extinction paradox, Q_ext = 2), spread as the Airy pattern of the
//! drop (`optics/ice/diffraction.rs`), averaged over the drops' cross-sections.
//!
//! Geometric optics holds for size parameters x >> 1: Riley et al. 2004 (section 3.1)
//! take rain's phase function from Lorenz-Mie at 1 mm (x about 1e4), where the two agree
//! but for the bows' interference (supernumeraries, Airy's shift of a few hundredths of
//! a degree, both below the sun's disc) and a ripple too fine for any table; the deviation
//! is the same for every size, so rain of any rate has one phase function but for the
//! diffraction peak. Water's absorption (k below 1e-8 in visible light, a millionth
//! over a drop) is neglected.

use std::f64::consts::PI;

use rayon::prelude::*;

use crate::optics::ice::diffraction::airy_pattern;

/// Impact parameters per ray sum (stratified in b^2), and the orders followed.
const RAYS: usize = 400_000;
/// Orders stop when the weight left inside falls below this fraction of a ray's.
const WEIGHT_LEFT: f64 = 1e-7;
/// The most chords followed (rays near grazing incidence, R near 1, need many).
const MAX_ORDER: usize = 5000;
/// Points per bin integrating the diffraction pattern.
const POINTS_PER_BIN: usize = 8;

/// Fresnel's reflectances (s, p) of light entering index `n` from 1 at incidence `i`
/// with refraction angle `r` (Born and Wolf 1999, Eq. 1.5.21a).
fn fresnel_sp(n: f64, i: f64, r: f64) -> (f64, f64) {
    let (ci, cr) = (i.cos(), r.cos());
    let s = (ci - n * cr) / (ci + n * cr);
    let p = (cr - n * ci) / (cr + n * ci);
    (s * s, p * p)
}

/// A deviation folded into a scattering angle in [0, pi].
fn scattering_angle(deviation: f64) -> f64 {
    let d = deviation.rem_euclid(2.0 * PI);
    if d > PI { 2.0 * PI - d } else { d }
}

/// The geometric-optics weight per bin (`bins` of `bin_deg` from 0 degrees) of rays on a
/// sphere of index `n`, summing to 1 but for orders dropped past [`WEIGHT_LEFT`].
pub fn geometric_bins(n: f64, bins: usize, bin_deg: f64) -> Vec<f64> {
    let chunk = RAYS / 64;
    (0..64)
        .into_par_iter()
        .map(|c| {
            let mut hist = vec![0.0; bins];
            let mut add = |theta: f64, w: f64| {
                let b = ((theta.to_degrees() / bin_deg) as usize).min(bins - 1);
                hist[b] += w;
            };
            for k in c * chunk..(c + 1) * chunk {
                let b = ((k as f64 + 0.5) / RAYS as f64).sqrt();
                let w = 1.0 / RAYS as f64;
                let i = b.asin();
                let r = (b / n).asin();
                let (rs, rp) = fresnel_sp(n, i, r);
                add(scattering_angle(PI - 2.0 * i), w * 0.5 * (rs + rp));
                // The weight inside, per polarisation; each chord's end lets 1 - R out.
                let (mut left_s, mut left_p) = (1.0 - rs, 1.0 - rp);
                let mut p = 1;
                while 0.5 * (left_s + left_p) > WEIGHT_LEFT && p <= MAX_ORDER {
                    let deviation = 2.0 * (i - r) + (p - 1) as f64 * (PI - 2.0 * r);
                    let out = 0.5 * (left_s * (1.0 - rs) + left_p * (1.0 - rp));
                    add(scattering_angle(deviation), w * out);
                    left_s *= rs;
                    left_p *= rp;
                    p += 1;
                }
            }
            hist
        })
        .collect::<Vec<_>>()
        .iter()
        // Summed in order, so that every build gives the same table to the bit.
        .fold(vec![0.0; bins], |mut a, b| {
            a.iter_mut().zip(b).for_each(|(a, b)| *a += b);
            a
        })
}

/// The diffraction weight per bin (summing to 1) of discs of `ka` = k times radius,
/// each weighted by its cross-section weight (e.g. n(r) r^2 dr).
pub fn diffraction_bins(discs: &[(f64, f64)], bins: usize, bin_deg: f64) -> Vec<f64> {
    let h = bin_deg.to_radians() / POINTS_PER_BIN as f64;
    let per_bin: Vec<f64> = (0..bins)
        .into_par_iter()
        .map(|b| {
            (0..POINTS_PER_BIN)
                .map(|j| {
                    let theta = (b * POINTS_PER_BIN + j) as f64 * h + 0.5 * h;
                    let pattern: f64 = discs
                        .iter()
                        .map(|&(w, ka)| w * airy_pattern(ka, theta))
                        .sum();
                    pattern * 2.0 * PI * theta.sin() * h
                })
                .sum()
        })
        .collect();
    let total: f64 = per_bin.iter().sum();
    per_bin.iter().map(|v| v / total).collect()
}
