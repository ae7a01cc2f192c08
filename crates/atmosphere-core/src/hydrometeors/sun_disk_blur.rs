//! A phase function seen by light from the sun's whole disc rather than one direction:
//! the mean of p over the disc, p_sun(theta) = (1 / N) sum_k p(gamma_k), at points
//! (rho_k, phi_k) of equal area on a uniform disc of angular radius rho_sun around the
//! sun, cos gamma = cos theta cos rho + sin theta sin rho cos phi (the spherical law of
//! cosines). Riley et al. 2004 (section 4.2.4) treat the sun as a disc of half a degree;
//! a point sun would make the bows' geometric-optics caustics infinitely sharp. The
//! mean over the sphere is kept: every direction is weighted alike.

use std::f64::consts::PI;

/// Rings and points per ring of the disc's quadrature.
const RINGS: usize = 8;
const PER_RING: usize = 24;

/// `phase` (values at the centres of bins of `bin_deg` from 0 degrees, linear between
/// them) averaged over a uniform disc of angular radius `sun_radius_rad`.
pub fn blur_with_sun_disk(phase: &[f64], bin_deg: f64, sun_radius_rad: f64) -> Vec<f64> {
    let at = |gamma_deg: f64| {
        let x = (gamma_deg / bin_deg - 0.5).clamp(0.0, (phase.len() - 1) as f64);
        let i = (x.floor() as usize).min(phase.len() - 2);
        let t = x - i as f64;
        phase[i] * (1.0 - t) + phase[i + 1] * t
    };
    let disc: Vec<(f64, f64)> = (0..RINGS)
        .flat_map(|k| {
            let rho = sun_radius_rad * ((k as f64 + 0.5) / RINGS as f64).sqrt();
            (0..PER_RING).map(move |j| {
                let phi = 2.0 * PI * (j as f64 + 0.5 * (k % 2) as f64) / PER_RING as f64;
                (rho, phi)
            })
        })
        .collect();
    (0..phase.len())
        .map(|b| {
            let theta = ((b as f64 + 0.5) * bin_deg).to_radians();
            let sum: f64 = disc
                .iter()
                .map(|&(rho, phi)| {
                    let c = theta.cos() * rho.cos() + theta.sin() * rho.sin() * phi.cos();
                    at(c.clamp(-1.0, 1.0).acos().to_degrees())
                })
                .sum();
            sum / disc.len() as f64
        })
        .collect()
}
