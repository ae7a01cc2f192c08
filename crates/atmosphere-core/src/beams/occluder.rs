//! The primitive occluders of a beams scene and where a ray meets each.

use glam::DVec3;

/// A primitive occluder, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Primitive {
    Sphere {
        center: DVec3,
        radius: f64,
    },
    /// Axis-aligned.
    Box {
        min: DVec3,
        max: DVec3,
    },
    /// `corner + a edge_u + b edge_v`, a and b in [0, 1].
    Quad {
        corner: DVec3,
        edge_u: DVec3,
        edge_v: DVec3,
    },
    /// Through `point`, with the unit `normal`.
    Plane {
        point: DVec3,
        normal: DVec3,
    },
}

impl Primitive {
    /// The nearest t in (t_min, t_max) at which `origin + t direction` (unit direction)
    /// meets the surface.
    pub fn hit(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
        let within = |t: f64| (t > t_min && t < t_max).then_some(t);
        match *self {
            Primitive::Sphere { center, radius } => {
                let oc = origin - center;
                let b = oc.dot(direction);
                // c = |oc|^2 - r^2 as (|oc| - r)(|oc| + r), without cancellation.
                let d = oc.length();
                let c = (d - radius) * (d + radius);
                let disc = b * b - c;
                if disc < 0.0 {
                    return None;
                }
                let root = disc.sqrt();
                // The far root first computed stably, the near one from the product.
                let far = -b + root;
                let near = if far != 0.0 { c / far } else { -b - root };
                within(near.min(far)).or_else(|| within(near.max(far)))
            }
            Primitive::Box { min, max } => {
                let inv = direction.recip();
                let (a, b) = ((min - origin) * inv, (max - origin) * inv);
                let (lo, hi) = (a.min(b), a.max(b));
                let enter = lo.max_element();
                let exit = hi.min_element();
                if enter > exit {
                    return None;
                }
                within(enter).or_else(|| within(exit))
            }
            Primitive::Quad {
                corner,
                edge_u,
                edge_v,
            } => {
                let normal = edge_u.cross(edge_v);
                let denom = normal.dot(direction);
                if denom == 0.0 {
                    return None;
                }
                let t = normal.dot(corner - origin) / denom;
                let p = origin + direction * t - corner;
                // Coordinates of p in the (edge_u, edge_v) basis.
                let (uu, uv, vv) = (edge_u.dot(edge_u), edge_u.dot(edge_v), edge_v.dot(edge_v));
                let (pu, pv) = (p.dot(edge_u), p.dot(edge_v));
                let det = uu * vv - uv * uv;
                let a = (pu * vv - pv * uv) / det;
                let b = (pv * uu - pu * uv) / det;
                if (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b) {
                    within(t)
                } else {
                    None
                }
            }
            Primitive::Plane { point, normal } => {
                let denom = normal.dot(direction);
                if denom == 0.0 {
                    return None;
                }
                within(normal.dot(point - origin) / denom)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_primitive_is_met_where_geometry_says() {
        let o = DVec3::new(0.0, 0.0, -10.0);
        let z = DVec3::Z;
        let sphere = Primitive::Sphere {
            center: DVec3::ZERO,
            radius: 2.0,
        };
        assert_eq!(sphere.hit(o, z, 0.0, f64::INFINITY), Some(8.0));
        assert_eq!(sphere.hit(DVec3::ZERO, z, 0.0, f64::INFINITY), Some(2.0));
        assert_eq!(sphere.hit(o, DVec3::X, 0.0, f64::INFINITY), None);
        let cube = Primitive::Box {
            min: DVec3::splat(-1.0),
            max: DVec3::splat(1.0),
        };
        assert_eq!(cube.hit(o, z, 0.0, f64::INFINITY), Some(9.0));
        assert_eq!(cube.hit(o, z, 0.0, 5.0), None);
        assert_eq!(cube.hit(DVec3::ZERO, z, 0.0, f64::INFINITY), Some(1.0));
        let quad = Primitive::Quad {
            corner: DVec3::new(-1.0, -1.0, 0.0),
            edge_u: DVec3::new(2.0, 0.0, 0.0),
            edge_v: DVec3::new(0.0, 2.0, 0.0),
        };
        assert_eq!(quad.hit(o, z, 0.0, f64::INFINITY), Some(10.0));
        let off = DVec3::new(1.5, 0.0, -10.0);
        assert_eq!(quad.hit(off, z, 0.0, f64::INFINITY), None);
        let plane = Primitive::Plane {
            point: DVec3::ZERO,
            normal: DVec3::Z,
        };
        assert_eq!(plane.hit(off, z, 0.0, f64::INFINITY), Some(10.0));
        assert_eq!(plane.hit(off, DVec3::NEG_Z, 0.0, f64::INFINITY), None);
    }
}
