//! The Legendre series of a Mie phase function, exact: for spheres of at most N terms,
//! |S1|^2 + |S2|^2 is a polynomial of degree 2N in nu (pi_n has degree n - 1, tau_n
//! degree n), so chi_l vanishes past l = 2N and the (2N + 1)-point Gauss-Legendre rule
//! integrates p P_l (degree at most 4N) exactly.

use num_complex::Complex64;

use super::coefficients::wiscombe_terms;
use super::error::MieError;
use super::polydisperse::{ParticleOptics, particle_optics};
use super::size_distribution::SizeDistribution;
use crate::numerics::gauss_legendre_rule::gauss_legendre;
use crate::optics::legendre_series::LegendreSeries;

/// A Mie phase function's series with what it came from.
#[derive(Clone, Debug)]
pub struct MieLegendre {
    pub series: LegendreSeries,
    /// The optics, with the phase function at the rule's nodes.
    pub optics: ParticleOptics,
    /// The Gauss-Legendre rule's (node, weight) pairs.
    pub rule: Vec<(f64, f64)>,
}

/// The Legendre series of the phase function of spheres, averaged over `distribution`
/// within `tolerance` as [`particle_optics`].
pub fn mie_legendre_series(
    m: Complex64,
    wavelength_m: f64,
    distribution: &SizeDistribution,
    tolerance: f64,
) -> Result<MieLegendre, MieError> {
    let largest_radius = distribution.log_radius_range()[1].exp();
    let x = 2.0 * std::f64::consts::PI * largest_radius / wavelength_m;
    let terms = wiscombe_terms(x);
    let rule = gauss_legendre(2 * terms + 1);
    let cosines: Vec<f64> = rule.iter().map(|&(nu, _)| nu).collect();
    let optics = particle_optics(m, wavelength_m, distribution, &cosines, tolerance)?;
    let series = LegendreSeries::from_gauss_rule(&rule, &optics.phase, 2 * terms);
    Ok(MieLegendre {
        series,
        optics,
        rule,
    })
}
