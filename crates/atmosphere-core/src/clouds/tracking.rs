//! One Monte Carlo path through a cloud medium, all orders of scattering: free paths by
//! delta tracking (Woodcock et al. 1965), so heterogeneous media need only a majorant;
//! at a real collision the path is absorbed with probability 1 - albedo (analog
//! absorption), else scattered by the phase function's sampler, whose weight
//! (phase / pdf) multiplies the path's.

use glam::DVec3;

use super::medium::CloudMedium;
use crate::numerics::sampling::{Sampler, direction_around};

/// How a path ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathEnd {
    /// Left the medium at `position` along `direction`, after `scatterings` real
    /// collisions, carrying `weight`.
    Escaped {
        position: DVec3,
        direction: DVec3,
        scatterings: u32,
        weight: f64,
    },
    /// Absorbed at a real collision, carrying `weight`.
    Absorbed { weight: f64 },
}

/// Follows a path entering at `position` along the unit `direction` until it leaves the
/// medium or is absorbed.
pub fn trace_path(
    medium: &impl CloudMedium,
    mut position: DVec3,
    mut direction: DVec3,
    sampler: &mut Sampler,
) -> PathEnd {
    let majorant = medium.majorant();
    let mut scatterings = 0;
    let mut weight = 1.0;
    loop {
        let to_boundary = medium.distance_to_boundary(position, direction);
        // 1 - uniform lies in (0, 1]: the free path is finite, or infinite in a medium
        // without extinction.
        let free_path = if majorant > 0.0 {
            -(1.0 - sampler.uniform()).ln() / majorant
        } else {
            f64::INFINITY
        };
        if free_path >= to_boundary {
            return PathEnd::Escaped {
                position: position + direction * to_boundary.min(f64::MAX),
                direction,
                scatterings,
                weight,
            };
        }
        position += direction * free_path;
        // A real collision with probability extinction / majorant, else a null one.
        if sampler.uniform() * majorant >= medium.extinction(position) {
            continue;
        }
        if sampler.uniform() >= medium.single_scattering_albedo(position) {
            return PathEnd::Absorbed { weight };
        }
        let (nu, phase_weight) = medium.phase().sample(sampler);
        let phi = 2.0 * std::f64::consts::PI * sampler.uniform();
        direction = direction_around(direction, nu, phi);
        weight *= phase_weight;
        scatterings += 1;
    }
}
