//! The view ray cut into quadrature nodes: where it enters and leaves the atmosphere, how
//! it ends (ground, object, space), and at every node the position, densities and the
//! columns of matter back to the camera.

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::models::error::ModelError;
use crate::models::sky_model::ViewRay;
use crate::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};
use crate::optics::column::{Fineness, densities, panels};
use crate::optics::view_segment::{SegmentEnd, ViewSegment};

/// How a view ray ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RayEnd {
    /// On the ground at this point (planet-centred, m).
    Ground(DVec3),
    /// On an object inside the atmosphere.
    Object,
    /// In space (or the ray never met the atmosphere).
    Space,
}

/// One quadrature node of the view ray.
#[derive(Clone, Copy, Debug)]
pub struct ViewNode {
    /// Planet-centred position, m.
    pub position: DVec3,
    /// Quadrature weight, m.
    pub weight: f64,
    /// Relative densities (Rayleigh, Mie, ozone).
    pub densities: [f64; 3],
    /// Columns from the camera to the node, m.
    pub column_from_camera: [f64; 3],
}

/// The view ray, discretised.
#[derive(Clone, Debug)]
pub struct ViewPath {
    pub direction: DVec3,
    pub nodes: Vec<ViewNode>,
    /// Columns from the camera to the end of the ray, m.
    pub total_column: [f64; 3],
    pub end: RayEnd,
}

impl ViewPath {
    /// Cuts `ray` into nodes with the given fineness.
    pub fn new(
        atmosphere: &Atmosphere,
        ray: &ViewRay,
        fineness: Fineness,
    ) -> Result<ViewPath, ModelError> {
        let bottom = atmosphere.bottom_radius_m;
        let Some(segment) = ViewSegment::new(atmosphere, ray)? else {
            return Ok(ViewPath {
                direction: ray.direction.normalize(),
                nodes: Vec::new(),
                total_column: [0.0; 3],
                end: RayEnd::Space,
            });
        };
        let (start, direction, r, mu, length) = (
            segment.start,
            segment.direction,
            segment.r,
            segment.mu,
            segment.length,
        );
        let mut nodes = Vec::new();
        let mut column = [0.0; 3];
        let penumbra = penumbra_crossings(
            atmosphere,
            start,
            direction,
            ray.sun_direction.normalize(),
            length,
        );
        for (a, b) in refine_in_penumbra(
            panels(atmosphere, r, mu, length, fineness, &penumbra),
            &penumbra,
        ) {
            for (t, w) in mapped(&GAUSS_LEGENDRE_8, a, b) {
                let mut partial = column;
                for (s, ws) in mapped(&GAUSS_LEGENDRE_8, a, t) {
                    let rho = densities(atmosphere, altitude(start + direction * s, bottom));
                    for k in 0..3 {
                        partial[k] += ws * rho[k];
                    }
                }
                let position = start + direction * t;
                nodes.push(ViewNode {
                    position,
                    weight: w,
                    densities: densities(atmosphere, altitude(position, bottom)),
                    column_from_camera: partial,
                });
            }
            for (s, ws) in mapped(&GAUSS_LEGENDRE_8, a, b) {
                let rho = densities(atmosphere, altitude(start + direction * s, bottom));
                for k in 0..3 {
                    column[k] += ws * rho[k];
                }
            }
        }
        let end = match segment.end {
            SegmentEnd::Ground => {
                let p = segment.end_point();
                RayEnd::Ground(p * (bottom / p.length()))
            }
            SegmentEnd::Object => RayEnd::Object,
            SegmentEnd::Space => RayEnd::Space,
        };
        Ok(ViewPath {
            direction,
            nodes,
            total_column: column,
            end,
        })
    }
}

/// Altitude above the ground of a planet-centred position, never negative.
pub fn altitude(position: DVec3, bottom_radius_m: f64) -> f64 {
    (position.length() - bottom_radius_m).max(0.0)
}

/// Distances along the ray from `start` where it crosses the edges and the middle of the
/// penumbra of the planet's shadow, where the visible part of the sun's disk changes
/// fast and single scattering has kinks. The shadow boundary seen through a disk edge
/// tilted by k alpha is the surface |x_perp| = R - k alpha (x . s) behind the planet
/// (x . s < 0), a quadratic in t along the ray.
pub fn penumbra_crossings(
    atmosphere: &Atmosphere,
    start: DVec3,
    direction: DVec3,
    sun: DVec3,
    length: f64,
) -> Vec<f64> {
    let radius = atmosphere.bottom_radius_m;
    let alpha = atmosphere.sun.angular_radius_rad;
    let (a0, b0) = (start.length_squared(), start.dot(direction));
    let (c0, e) = (start.dot(sun), direction.dot(sun));
    let mut out = Vec::new();
    for k in [-1.0, 0.0, 1.0] {
        // |x|^2 - (x.s)^2 - (R - k alpha (c0 + e t))^2 = 0.
        let m = radius - k * alpha * c0;
        let n = k * alpha * e;
        let qa = 1.0 - e * e - n * n;
        let qb = 2.0 * (b0 - c0 * e + m * n);
        let qc = a0 - c0 * c0 - m * m;
        let disc = qb * qb - 4.0 * qa * qc;
        if disc < 0.0 || qa.abs() < 1e-300 {
            continue;
        }
        for t in [
            (-qb - disc.sqrt()) / (2.0 * qa),
            (-qb + disc.sqrt()) / (2.0 * qa),
        ] {
            if t > 0.0 && t < length && c0 + e * t < 0.0 {
                out.push(t);
            }
        }
    }
    out.sort_by(f64::total_cmp);
    out
}

/// Panels that lie inside the penumbra (between its first and last crossing), cut into
/// eight, since the sun's visible fraction varies like a square root at its edges.
fn refine_in_penumbra(panels: Vec<(f64, f64)>, crossings: &[f64]) -> Vec<(f64, f64)> {
    let (Some(first), Some(last)) = (crossings.first(), crossings.last()) else {
        return panels;
    };
    let near = |x: f64| {
        crossings
            .iter()
            .any(|c| (*c - x).abs() <= 1e-9 * x.abs().max(1.0))
    };
    let mut out = Vec::with_capacity(panels.len() + 64);
    for (a, b) in panels {
        if near(a) || near(b) || (a >= *first && b <= *last) {
            let step = (b - a) / 8.0;
            out.extend((0..8).map(|i| (a + step * i as f64, a + step * (i + 1) as f64)));
        } else {
            out.push((a, b));
        }
    }
    out
}
