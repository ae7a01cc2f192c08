//! Directions towards sunlit air, for paths that scatter in the planet's umbra.
//!
//! In deep twilight a point in the umbra is lit only by air the sun still reaches, high
//! up and hundreds of kilometres away towards the sun: seen from the ground, a thin band
//! a few degrees above the horizon. A direction drawn from the phase function almost
//! never points into it, so almost every path carries nothing. The guide tabulates, over
//! cells of equal solid angle around an anchor point (cosine of the zenith angle by
//! azimuth from the sun), a rough estimate of the once-scattered radiance arriving there,
//! and draws directions in proportion to it. The path tracer draws from a mixture of the
//! guide and the phase function (or the ground's cosine) and weights each direction by
//! the phase function over the mixture's density: the balance heuristic of multiple
//! importance sampling (Veach and Guibas 1995, Eq. 9, one sample), unbiased wherever the
//! phase function's own density is positive, whatever the guide says.

use std::f64::consts::PI;

use glam::DVec3;

use crate::numerics::sampling::{Sampler, orthonormal_basis};
use crate::optics::phase::PhaseFunction;
use crate::optics::phase::rayleigh;
use crate::reference::scatterer::Scatterer;

/// Cells in the cosine of the zenith angle over [-1, 1]: about half a degree at the
/// horizon, where the lit band lies in deep twilight.
const ZENITH_CELLS: usize = 256;
/// Cells in azimuth over [-pi, pi), symmetric about the sun's azimuth.
const AZIMUTH_CELLS: usize = 32;

/// Whether the reference guides the directions of paths that scatter in the umbra.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Guiding {
    /// The phase function (or the ground's cosine) alone.
    Off,
    /// A mixture with a guide towards sunlit air, where the view ray's last events lie in
    /// the umbra; the later events of those paths drawn by delta tracking.
    Directions,
    /// The directions as with `Directions`, and the later events of those paths drawn
    /// towards the light as well (`towards_light.rs`).
    TowardsLitAir,
}

/// A tabulated distribution of directions around an anchor point.
#[derive(Clone, Debug)]
pub struct DirectionGuide {
    up: DVec3,
    /// Towards the sun's azimuth.
    x: DVec3,
    y: DVec3,
    /// Probability of each cell, zenith-major.
    probability: Vec<f64>,
    /// Cumulative probability at the end of each cell.
    cdf: Vec<f64>,
    /// The rough once-scattered radiance integrated over the sphere, in units of the
    /// solar irradiance.
    integral: f64,
}

/// The light a guide expects to arrive at its anchor, weighted by the phase function of
/// each species towards a given direction, and by the ground's cosine / pi.
#[derive(Clone, Copy, Debug)]
pub struct ExpectedLight {
    pub rayleigh: f64,
    pub mie: f64,
    pub ground: f64,
}

impl ExpectedLight {
    /// The light scattered by `scatterer` towards the direction it was computed for.
    pub(crate) fn scattered_by(&self, scatterer: Scatterer) -> f64 {
        match scatterer {
            Scatterer::Air { rayleigh, mie } if rayleigh + mie > 0.0 => {
                (rayleigh * self.rayleigh + mie * self.mie) / (rayleigh + mie)
            }
            Scatterer::Air { .. } => 0.0,
            Scatterer::Ground(_) => self.ground,
        }
    }
}

impl DirectionGuide {
    /// The guide around `anchor`, from `incoming(direction)`: a rough estimate of the
    /// sunlight scattered once towards the anchor from each direction (in units of the
    /// solar irradiance); `None` where no direction sees sunlit air.
    pub fn new(
        anchor: DVec3,
        sun_direction: DVec3,
        incoming: impl Fn(DVec3) -> f64,
    ) -> Option<DirectionGuide> {
        let up = anchor.normalize();
        let across = sun_direction - up * sun_direction.dot(up);
        let x = if across.length_squared() > 1e-24 {
            across.normalize()
        } else {
            orthonormal_basis(up).0
        };
        let y = up.cross(x);
        let mut guide = DirectionGuide {
            up,
            x,
            y,
            probability: vec![0.0; ZENITH_CELLS * AZIMUTH_CELLS],
            cdf: Vec::new(),
            integral: 0.0,
        };
        // The atmosphere is symmetric about the plane of the anchor and the sun: half the
        // azimuths are computed, the others mirrored.
        let (du, dphi) = cell_size();
        for i in 0..ZENITH_CELLS {
            let u = -1.0 + du * (i as f64 + 0.5);
            for j in AZIMUTH_CELLS / 2..AZIMUTH_CELLS {
                let phi = -PI + dphi * (j as f64 + 0.5);
                let value = incoming(guide.direction(u, phi));
                guide.probability[i * AZIMUTH_CELLS + j] = value;
                guide.probability[i * AZIMUTH_CELLS + AZIMUTH_CELLS - 1 - j] = value;
            }
        }
        let total: f64 = guide.probability.iter().sum();
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        guide.integral = total * du * dphi;
        let mut acc = 0.0;
        guide.cdf = guide
            .probability
            .iter_mut()
            .map(|p| {
                *p /= total;
                acc += *p;
                acc
            })
            .collect();
        Some(guide)
    }

    /// A direction drawn from the guide.
    pub fn sample(&self, sampler: &mut Sampler) -> DVec3 {
        let pick = sampler.uniform();
        let cell = self
            .cdf
            .partition_point(|c| *c < pick)
            .min(self.cdf.len() - 1);
        let (du, dphi) = cell_size();
        let (i, j) = (cell / AZIMUTH_CELLS, cell % AZIMUTH_CELLS);
        let u = -1.0 + du * (i as f64 + sampler.uniform());
        let phi = -PI + dphi * (j as f64 + sampler.uniform());
        self.direction(u, phi)
    }

    /// The guide's density over the sphere (sr^-1) at the unit vector `direction`.
    pub fn pdf(&self, direction: DVec3) -> f64 {
        let (du, dphi) = cell_size();
        let u = direction.dot(self.up).clamp(-1.0, 1.0);
        let phi = direction.dot(self.y).atan2(direction.dot(self.x));
        let i = (((u + 1.0) / du) as usize).min(ZENITH_CELLS - 1);
        let j = (((phi + PI) / dphi) as usize).min(AZIMUTH_CELLS - 1);
        self.probability[i * AZIMUTH_CELLS + j] / (du * dphi)
    }

    /// The light expected at the anchor, scattered towards `-outgoing` (the direction a
    /// path arrived along): the integral over the cells of the rough radiance times
    /// each phase function (and the cosine with the anchor's up / pi, for the ground).
    pub fn expected(&self, outgoing: DVec3, mie: &PhaseFunction) -> ExpectedLight {
        let (du, dphi) = cell_size();
        let mut out = ExpectedLight {
            rayleigh: 0.0,
            mie: 0.0,
            ground: 0.0,
        };
        for (cell, p) in self.probability.iter().enumerate() {
            if *p == 0.0 {
                continue;
            }
            let (i, j) = (cell / AZIMUTH_CELLS, cell % AZIMUTH_CELLS);
            let u = -1.0 + du * (i as f64 + 0.5);
            let direction = self.direction(u, -PI + dphi * (j as f64 + 0.5));
            let nu = outgoing.dot(direction);
            out.rayleigh += p * rayleigh(nu);
            out.mie += p * mie.eval(nu);
            out.ground += p * u.max(0.0) / PI;
        }
        out.rayleigh *= self.integral;
        out.mie *= self.integral;
        out.ground *= self.integral;
        out
    }

    fn direction(&self, u: f64, phi: f64) -> DVec3 {
        let s = (1.0 - u * u).max(0.0).sqrt();
        (self.x * (s * phi.cos()) + self.y * (s * phi.sin()) + self.up * u).normalize()
    }
}

/// Sizes of a cell in the cosine of the zenith angle and in azimuth: its solid angle is
/// their product.
fn cell_size() -> (f64, f64) {
    (2.0 / ZENITH_CELLS as f64, 2.0 * PI / AZIMUTH_CELLS as f64)
}
