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
use crate::optics::column::optical_depth;
use crate::optics::phase::rayleigh;
use crate::reference::path_tracer::{PathTracer, Scatterer};

/// Cells in the cosine of the zenith angle over [-1, 1]: about half a degree at the
/// horizon, where the lit band lies in deep twilight.
const ZENITH_CELLS: usize = 256;
/// Pieces of each direction's lit part on which the guide's radiance is estimated.
const GUIDE_PIECES: usize = 8;
/// Cells in azimuth over [-pi, pi), symmetric about the sun's azimuth.
const AZIMUTH_CELLS: usize = 32;

/// Whether the reference guides the directions of paths that scatter in the umbra.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Guiding {
    /// The phase function (or the ground's cosine) alone.
    Off,
    /// A mixture with a guide towards sunlit air, where the view ray's last events lie in
    /// the umbra.
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
    /// The guide around `anchor` at the tracer's wavelength, or `None` where no direction
    /// sees sunlit air.
    pub fn new(tracer: &PathTracer<'_>, anchor: DVec3) -> Option<DirectionGuide> {
        let up = anchor.normalize();
        let across = tracer.sun_direction - up * tracer.sun_direction.dot(up);
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
                let value = rough_incoming(tracer, anchor, guide.direction(u, phi));
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
    pub fn expected(&self, outgoing: DVec3, tracer: &PathTracer<'_>) -> ExpectedLight {
        let (du, dphi) = cell_size();
        let mie = &tracer.atmosphere.mie.phase;
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

/// A rough estimate of the sunlight scattered once towards `position` from `direction`
/// (the lit part of the ray's envelope, the ground at its end, for the sun's centre), in
/// units of the solar irradiance.
fn rough_incoming(tracer: &PathTracer<'_>, position: DVec3, direction: DVec3) -> f64 {
    let segment = tracer.segment(position, direction);
    let dark = tracer.umbra_interval(position, direction, &segment);
    let (_, envelope) = tracer.lit_envelope(position, direction, &segment, dark, GUIDE_PIECES);
    let mut value: f64 = envelope.iter().sum();
    if segment.hits_ground {
        let p = position + direction * segment.length;
        let cosine = p.normalize().dot(tracer.sun_direction);
        if cosine > 0.0 {
            let start = tracer.start_column(&segment);
            let view_t = (-optical_depth(
                tracer.column_along(&segment, start, segment.length),
                tracer.extinction,
            ))
            .exp();
            value += view_t * tracer.atmosphere.ground_albedo / PI
                * cosine
                * tracer.sun_transmittance(p, tracer.sun_direction);
        }
    }
    value
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Atmosphere;
    use crate::models::settings::ModelSettings;
    use crate::reference::Reference;

    /// Directions drawn from the mixture of guide and phase function (or cosine) carry
    /// weights whose mean is the integral of the phase function (or of cosine / pi over
    /// the hemisphere): 1. A guide whose density disagreed with its draws would miss it.
    #[test]
    fn mixture_weights_integrate_the_phase_function_and_the_cosine() {
        let earth = Atmosphere::preset("earth").unwrap();
        let settings = ModelSettings {
            wavelengths_nm: vec![440.0],
            ..ModelSettings::default()
        };
        let reference = Reference::prepare(&earth, &settings).unwrap();
        let z = 102f64.to_radians();
        let sun = DVec3::new(z.sin(), 0.0, z.cos());
        let unguided = reference.tracer(0, sun);
        let ground = DVec3::new(0.0, 0.0, earth.bottom_radius_m);
        let air = DVec3::new(0.0, 0.0, earth.bottom_radius_m + 12_000.0);
        for (anchor, scatterer) in [
            (
                air,
                Scatterer::Air {
                    rayleigh: 2e-6,
                    mie: 1e-6,
                },
            ),
            (ground, Scatterer::Ground(DVec3::Z)),
        ] {
            assert!(unguided.in_umbra(anchor));
            let guide = DirectionGuide::new(&unguided, anchor).expect("lit air in view");
            let tracer = PathTracer {
                guide: Some(&guide),
                ..unguided
            };
            let outgoing = DVec3::new(0.3, 0.2, 0.9).normalize();
            let mut sampler = Sampler::new(3);
            let n = 200_000;
            let (mut sum, mut sum_sq, mut towards_sun) = (0.0, 0.0, 0usize);
            for _ in 0..n {
                let (direction, weight) = tracer.scatter(anchor, outgoing, scatterer, &mut sampler);
                sum += weight;
                sum_sq += weight * weight;
                towards_sun += usize::from(direction.dot(sun) > 0.9);
            }
            let mean = sum / n as f64;
            let std_error = ((sum_sq / n as f64 - mean * mean) / n as f64).sqrt();
            assert!(
                (mean - 1.0).abs() < 4.0 * std_error,
                "{scatterer:?}: mean weight {mean} +- {std_error}"
            );
            // The guide does send directions towards the sun, where the lit air is.
            assert!(towards_sun > n / 4, "{scatterer:?}: {towards_sun} of {n}");
        }
    }
}
