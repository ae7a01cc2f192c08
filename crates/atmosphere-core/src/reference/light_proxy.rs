//! How much once-scattered sunlight arrives at a point, as a table over the point's
//! altitude and the cosine of the sun's zenith angle there, for drawing the later events
//! of twilight paths where the light is (`towards_light.rs`).
//!
//! The atmosphere is spherically symmetric and the sun is far, so the light arriving at a
//! point depends only on its radius r and on mu_s (the parameterization of Bruneton and
//! Neyret 2008, section 4, less the view's angles, which are integrated over). Each cell
//! holds the integral over the sphere of directions of the rough once-scattered radiance
//! (`PathTracer::rough_incoming`): in the umbra it grows by orders of magnitude towards
//! the shadow's edge, and that growth is what the distance sampling follows. It is only a
//! density to draw from: any positive value keeps the estimate unbiased.

use std::f64::consts::PI;

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::numerics::sampling::orthonormal_basis;

/// Nodes in altitude, crowded quadratically towards the ground.
const ALTITUDES: usize = 24;
/// Nodes in mu_s over [`MU_S_RANGE`]; outside it the nearest node's value.
const MU_S_NODES: usize = 64;
/// The suns the table covers: from 60 deg below the horizontal (deep in the umbra at any
/// altitude) to about 17 deg above it (every point lit, where no path is guided).
const MU_S_RANGE: (f64, f64) = (-0.5, 0.3);
/// Directions in elevation, crowded towards the horizon where the lit band lies in deep
/// twilight, and in azimuth over half a turn (the light is symmetric about the sun's
/// vertical plane).
const ELEVATIONS: usize = 24;
const AZIMUTHS: usize = 8;

/// The once-scattered light arriving at a point, by altitude and mu_s, at one wavelength.
#[derive(Clone, Debug)]
pub struct LightProxy {
    bottom_radius_m: f64,
    top_altitude_m: f64,
    /// Altitude-major, `ALTITUDES` x `MU_S_NODES`, in units of the solar irradiance.
    values: Vec<f64>,
}

impl LightProxy {
    /// The table for `atmosphere` from `incoming(position, direction)`, the rough
    /// once-scattered radiance arriving at a point from a direction with the sun towards
    /// `sun` (which only sets the frame: `PathTracer::rough_incoming`); `None` where no
    /// cell sees any sunlit air. Built on the calling thread: the reference builds it on
    /// first use inside a `OnceLock` while rays run in parallel, and a parallel build
    /// there could hand the building thread another ray that waits on the same lock.
    pub fn new(
        atmosphere: &Atmosphere,
        sun: DVec3,
        incoming: impl Fn(DVec3, DVec3) -> f64,
    ) -> Option<LightProxy> {
        let bottom = atmosphere.bottom_radius_m;
        let top = atmosphere.top_radius_m - bottom;
        let (across, _) = orthonormal_basis(sun);
        let directions = sphere_directions();
        let values: Vec<f64> = (0..ALTITUDES * MU_S_NODES)
            .map(|cell| {
                let h = altitude_node(cell / MU_S_NODES, top);
                let mu_s = mu_s_node(cell % MU_S_NODES);
                let position = (bottom + h) * (mu_s * sun + (1.0 - mu_s * mu_s).sqrt() * across);
                let up = position.normalize();
                let towards_sun = (sun - up * sun.dot(up)).try_normalize().unwrap_or(across);
                let side = up.cross(towards_sun);
                directions
                    .iter()
                    .map(|&(local, solid_angle)| {
                        let d = local.x * towards_sun + local.y * side + local.z * up;
                        solid_angle * incoming(position, d)
                    })
                    .sum::<f64>()
            })
            .collect();
        let any = values.iter().any(|v| *v > 0.0);
        any.then_some(LightProxy {
            bottom_radius_m: bottom,
            top_altitude_m: top,
            values,
        })
    }

    /// The light arriving at `position` with the sun towards `sun_direction`: bilinear
    /// between the nodes, clamped to the table's range.
    pub fn at(&self, position: DVec3, sun_direction: DVec3) -> f64 {
        let r = position.length();
        let h = (r - self.bottom_radius_m).clamp(0.0, self.top_altitude_m);
        let mu_s = (position.dot(sun_direction) / r).clamp(MU_S_RANGE.0, MU_S_RANGE.1);
        // Inverse of altitude_node: h = top x^2 with x = i / (ALTITUDES - 1).
        let x = (h / self.top_altitude_m).sqrt() * (ALTITUDES - 1) as f64;
        let y = (mu_s - MU_S_RANGE.0) / (MU_S_RANGE.1 - MU_S_RANGE.0) * (MU_S_NODES - 1) as f64;
        let (i, fx) = split(x, ALTITUDES);
        let (j, fy) = split(y, MU_S_NODES);
        let v = |i: usize, j: usize| self.values[i * MU_S_NODES + j];
        (1.0 - fx) * ((1.0 - fy) * v(i, j) + fy * v(i, j + 1))
            + fx * ((1.0 - fy) * v(i + 1, j) + fy * v(i + 1, j + 1))
    }
}

/// The lower node of the interval holding `x` (in node units) and the fraction past it.
fn split(x: f64, nodes: usize) -> (usize, f64) {
    let i = (x.floor().max(0.0) as usize).min(nodes - 2);
    (i, (x - i as f64).clamp(0.0, 1.0))
}

fn altitude_node(i: usize, top_altitude_m: f64) -> f64 {
    let x = i as f64 / (ALTITUDES - 1) as f64;
    top_altitude_m * x * x
}

fn mu_s_node(j: usize) -> f64 {
    MU_S_RANGE.0 + (MU_S_RANGE.1 - MU_S_RANGE.0) * j as f64 / (MU_S_NODES - 1) as f64
}

/// Directions over the whole sphere in a local frame (x towards the sun's azimuth, z up)
/// with their solid angles: elevations e = 90 deg s |s| for s at the midpoints of
/// `ELEVATIONS` equal steps of [-1, 1], azimuths at the midpoints of `AZIMUTHS` steps of
/// [0, pi], each standing for its mirror image too.
fn sphere_directions() -> Vec<(DVec3, f64)> {
    let mut out = Vec::with_capacity(ELEVATIONS * AZIMUTHS);
    let ds = 2.0 / ELEVATIONS as f64;
    let dphi = PI / AZIMUTHS as f64;
    for i in 0..ELEVATIONS {
        let s = -1.0 + ds * (i as f64 + 0.5);
        let elevation = 0.5 * PI * s * s.abs();
        // de/ds = pi |s|; the cell's solid angle over both mirror images.
        let d_elevation = PI * s.abs() * ds;
        for j in 0..AZIMUTHS {
            let phi = dphi * (j as f64 + 0.5);
            let local = DVec3::new(
                elevation.cos() * phi.cos(),
                elevation.cos() * phi.sin(),
                elevation.sin(),
            );
            out.push((local, 2.0 * elevation.cos() * d_elevation * dphi));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_directions_cover_the_sphere() {
        let total: f64 = sphere_directions().iter().map(|d| d.1).sum();
        assert!((total - 4.0 * PI).abs() < 0.02 * 4.0 * PI, "{total}");
    }

    #[test]
    fn nodes_and_look_ups_agree() {
        let table = LightProxy {
            bottom_radius_m: 1.0,
            top_altitude_m: 100.0,
            values: (0..ALTITUDES * MU_S_NODES).map(|k| k as f64).collect(),
        };
        let sun = DVec3::Z;
        for (i, j) in [(0, 0), (3, 17), (ALTITUDES - 1, MU_S_NODES - 1)] {
            let h = altitude_node(i, 100.0);
            let mu_s = mu_s_node(j);
            let p = (1.0 + h) * DVec3::new((1.0 - mu_s * mu_s).sqrt(), 0.0, mu_s);
            let expected = (i * MU_S_NODES + j) as f64;
            assert!((table.at(p, sun) - expected).abs() < 1e-6, "{i} {j}");
        }
    }
}
