//! Every occluder of a scene together: the nearest surface along a view ray, and
//! whether a shadow ray is blocked.

use glam::DVec3;

use crate::beams::bvh::Bvh;
use crate::beams::occluder::Primitive;

/// The nearest a shadow ray's blocker may be to its start, m: a point on a surface (the
/// end of a view ray) does not shadow itself.
pub const SHADOW_RAY_START_M: f64 = 1e-7;

/// The scene's primitives and the hierarchy over its meshes' triangles.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Occluders {
    pub primitives: Vec<Primitive>,
    pub triangles: Bvh,
}

impl Occluders {
    /// The distance to the first surface along the ray within `t_max`.
    pub fn nearest(&self, origin: DVec3, direction: DVec3, t_max: f64) -> Option<f64> {
        let mut nearest = self.triangles.hit(origin, direction, 0.0, t_max, false);
        for p in &self.primitives {
            if let Some(t) = p.hit(origin, direction, 0.0, nearest.unwrap_or(t_max)) {
                nearest = Some(t);
            }
        }
        nearest
    }

    /// Whether a surface lies between `point` and the point `distance_m` along
    /// `direction` (a shadow ray toward a light).
    pub fn blocks(&self, point: DVec3, direction: DVec3, distance_m: f64) -> bool {
        let t_min = SHADOW_RAY_START_M;
        self.primitives
            .iter()
            .any(|p| p.hit(point, direction, t_min, distance_m).is_some())
            || self
                .triangles
                .hit(point, direction, t_min, distance_m, true)
                .is_some()
    }

    /// True when there is nothing to cast a shadow.
    pub fn is_empty(&self) -> bool {
        self.primitives.is_empty() && self.triangles.is_empty()
    }
}

impl Occluders {
    /// The box around every occluder of finite size (planes excepted), if any.
    pub fn finite_bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut bounds = self.triangles.bounds();
        for p in &self.primitives {
            let b = match *p {
                Primitive::Sphere { center, radius } => (center - radius, center + radius),
                Primitive::Box { min, max } => (min, max),
                Primitive::Quad {
                    corner,
                    edge_u,
                    edge_v,
                } => {
                    let far = corner + edge_u + edge_v;
                    let (a, b) = (corner + edge_u, corner + edge_v);
                    (corner.min(far).min(a).min(b), corner.max(far).max(a).max(b))
                }
                Primitive::Plane { .. } => continue,
            };
            bounds = Some(match bounds {
                Some((lo, hi)) => (lo.min(b.0), hi.max(b.1)),
                None => b,
            });
        }
        bounds
    }

    /// Whether one of the infinite planes lies between `point` and the point
    /// `distance_m` along `direction`.
    pub fn planes_block(&self, point: DVec3, direction: DVec3, distance_m: f64) -> bool {
        self.primitives.iter().any(|p| {
            matches!(p, Primitive::Plane { .. })
                && p.hit(point, direction, SHADOW_RAY_START_M, distance_m)
                    .is_some()
        })
    }
}
