//! Which chunks the camera can see: a chunk's bounding sphere against the four side
//! planes of the view pyramid (no far plane: the depth is reversed and infinite), and
//! against the plane through the camera facing forward; and how close to the planet's
//! centre any ray of the pyramid comes, so that chunks lying wholly below that (the
//! ground beneath a camera looking up) are not drawn.

use glam::DVec3;

/// The view pyramid, planet axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    apex: DVec3,
    /// Inward unit normals of the side planes through the apex, then the forward axis.
    normals: [DVec3; 5],
    /// Unit directions of the pyramid's corner rays, in order around it.
    corners: [DVec3; 4],
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
        let corner = |x: f64, y: f64| (forward + right * x + up * y).normalize();
        Frustum {
            apex: apex_m,
            corners: [
                corner(half_width, half_height),
                corner(-half_width, half_height),
                corner(-half_width, -half_height),
                corner(half_width, -half_height),
            ],
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

    /// The least distance from the planet's centre (the origin) that any ray of the
    /// pyramid reaches: the apex's distance `r`, or `r sin(z)` for the ray looking most
    /// steeply down, at zenith angle `z` beyond 90 deg. The steepest ray is found as the
    /// largest `d . (-up)` over the pyramid's spherical quadrilateral: at the nadir if it
    /// is inside, else on an edge (a corner, or where the nadir projects onto the edge's
    /// great circle).
    pub fn lowest_radius_m(&self) -> f64 {
        let r = self.apex.length();
        let down = -self.apex / r;
        let mut steepest = if self.normals[..4].iter().all(|n| n.dot(down) >= 0.0) {
            1.0f64
        } else {
            f64::NEG_INFINITY
        };
        for k in 0..4 {
            let (a, b) = (self.corners[k], self.corners[(k + 1) % 4]);
            steepest = steepest.max(a.dot(down));
            let n = a.cross(b).normalize();
            if let Some(p) = (down - n * n.dot(down)).try_normalize()
                && a.cross(p).dot(n) >= 0.0
                && p.cross(b).dot(n) >= 0.0
            {
                steepest = steepest.max(p.dot(down));
            }
        }
        if steepest > 0.0 {
            r * (1.0 - steepest * steepest).max(0.0).sqrt()
        } else {
            r
        }
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

    #[test]
    fn the_lowest_ray_is_found_at_corners_edges_and_the_nadir() {
        let r = 100.0;
        let apex = DVec3::new(0.0, 0.0, r);
        // Looking straight up: no ray comes closer than the apex.
        let up = Frustum::new(apex, [DVec3::X, DVec3::Y, DVec3::Z], 1.0, 1.0);
        assert_eq!(up.lowest_radius_m(), r);
        // Straight down: the nadir is in view.
        let down = Frustum::new(apex, [DVec3::X, -DVec3::Y, -DVec3::Z], 1.0, 1.0);
        assert!(down.lowest_radius_m() < 1e-9);
        // Level, 90 degrees tall: the bottom edge's middle looks 45 degrees down, lower
        // than its corners.
        let level = Frustum::new(apex, [-DVec3::Y, DVec3::Z, DVec3::X], 1.0, 1.0);
        let expected = r * 45f64.to_radians().sin();
        assert!(
            (level.lowest_radius_m() - expected).abs() < 1e-9,
            "{}",
            level.lowest_radius_m()
        );
        // Brute force over a tilted pyramid.
        let forward = DVec3::new(0.3, 0.2, -0.4).normalize();
        let right = forward.cross(DVec3::Z).normalize();
        let upv = right.cross(forward);
        let f = Frustum::new(apex, [right, upv, forward], 0.7, 0.4);
        let mut lowest = f64::INFINITY;
        for i in 0..=200 {
            for j in 0..=200 {
                let (x, y) = (-0.7 + 1.4 * i as f64 / 200.0, -0.4 + 0.8 * j as f64 / 200.0);
                let d = (forward + right * x + upv * y).normalize();
                let mu = d.z;
                let closest = if mu < 0.0 {
                    r * (1.0 - mu * mu).sqrt()
                } else {
                    r
                };
                lowest = lowest.min(closest);
            }
        }
        assert!(
            (f.lowest_radius_m() - lowest).abs() < 1e-3 * r,
            "{} {lowest}",
            f.lowest_radius_m()
        );
    }
}
