//! Which chunks the camera can see: a chunk's bounding sphere against the four side
//! planes of the view pyramid (no far plane: the depth is reversed and infinite), and
//! against the plane through the camera facing forward.

use glam::DVec3;

/// The view pyramid, planet axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    apex: DVec3,
    /// Inward unit normals of the side planes through the apex, then the forward axis.
    normals: [DVec3; 5],
}

impl Frustum {
    /// The pyramid of a camera at `apex_m` with unit axes `right`, `up`, `forward` and
    /// half extents `half_width`, `half_height` of the image at unit distance.
    pub fn new(
        apex_m: DVec3,
        [right, up, forward]: [DVec3; 3],
        half_width: f64,
        half_height: f64,
    ) -> Frustum {
        // A side plane contains the apex and an edge direction such as forward +
        // half_width right; its inward normal is perpendicular to that edge and to up
        // (or right).
        let side = |edge: DVec3, along: DVec3, inside: DVec3| {
            let n = edge.cross(along).normalize();
            if n.dot(inside) >= 0.0 { n } else { -n }
        };
        Frustum {
            apex: apex_m,
            normals: [
                side(forward + right * half_width, up, forward),
                side(forward - right * half_width, up, forward),
                side(forward + up * half_height, right, forward),
                side(forward - up * half_height, right, forward),
                forward,
            ],
        }
    }

    /// Whether a sphere may be in view (false only when it lies wholly outside a plane).
    pub fn sees_sphere(&self, centre_m: DVec3, radius_m: f64) -> bool {
        let d = centre_m - self.apex;
        self.normals.iter().all(|n| n.dot(d) >= -radius_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spheres_in_front_and_inside_are_seen_others_are_not() {
        // Looking along -z with a 90 degree square view.
        let f = Frustum::new(DVec3::ZERO, [DVec3::X, DVec3::Y, -DVec3::Z], 1.0, 1.0);
        assert!(f.sees_sphere(DVec3::new(0.0, 0.0, -10.0), 1.0));
        assert!(f.sees_sphere(DVec3::new(9.0, 0.0, -10.0), 0.1));
        assert!(!f.sees_sphere(DVec3::new(12.0, 0.0, -10.0), 1.0));
        assert!(f.sees_sphere(DVec3::new(12.0, 0.0, -10.0), 2.0));
        assert!(!f.sees_sphere(DVec3::new(0.0, -13.0, -10.0), 1.0));
        assert!(!f.sees_sphere(DVec3::new(0.0, 0.0, 10.0), 1.0));
        // The camera inside a sphere behind it.
        assert!(f.sees_sphere(DVec3::new(0.0, 0.0, 3.0), 5.0));
    }
}
