//! What scatters light at an event of a Monte Carlo path: air or the ground.

use glam::DVec3;

/// What scatters light at a path's event.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Scatterer {
    /// Air with these scattering coefficients, Rayleigh and Mie, m^-1.
    Air { rayleigh: f64, mie: f64 },
    /// The Lambertian ground, with this normal.
    Ground(DVec3),
}
