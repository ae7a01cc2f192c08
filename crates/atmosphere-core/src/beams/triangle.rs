//! A triangle and where a ray meets it (Moeller and Trumbore 1997).

use glam::DVec3;

/// A triangle by its corners, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle(pub [DVec3; 3]);

impl Triangle {
    /// The distance along the ray `origin + t direction` at which it crosses the
    /// triangle, for t in (t_min, t_max); either side of the triangle counts.
    pub fn hit(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
        let [a, b, c] = self.0;
        let (e1, e2) = (b - a, c - a);
        let p = direction.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-300 {
            return None;
        }
        let inv = 1.0 / det;
        let s = origin - a;
        let u = s.dot(p) * inv;
        if !(0.0..=1.0).contains(&u) {
            return None;
        }
        let q = s.cross(e1);
        let v = direction.dot(q) * inv;
        if v < 0.0 || u + v > 1.0 {
            return None;
        }
        let t = e2.dot(q) * inv;
        (t > t_min && t < t_max).then_some(t)
    }

    /// The smallest and largest corner coordinates.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        let [a, b, c] = self.0;
        (a.min(b).min(c), a.max(b).max(c))
    }

    /// The centroid.
    pub fn centroid(&self) -> DVec3 {
        (self.0[0] + self.0[1] + self.0[2]) / 3.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_meets_triangle_inside_and_misses_outside() {
        let t = Triangle([DVec3::ZERO, DVec3::X, DVec3::Y]);
        let down = DVec3::NEG_Z;
        let hit = t.hit(DVec3::new(0.2, 0.2, 3.0), down, 0.0, 10.0);
        assert_eq!(hit, Some(3.0));
        assert_eq!(t.hit(DVec3::new(0.6, 0.6, 3.0), down, 0.0, 10.0), None);
        assert_eq!(t.hit(DVec3::new(0.2, 0.2, 3.0), down, 0.0, 2.0), None);
        assert_eq!(t.hit(DVec3::new(0.2, 0.2, 3.0), DVec3::X, 0.0, 10.0), None);
    }
}
