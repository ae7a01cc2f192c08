//! The spherical shell the cloud layer fills, between the base radius and the top
//! radius: where a view ray first crosses it, and how far a ray from a point inside it
//! runs before it leaves. In the (r, mu) form of `optics/geometry.rs`.

use glam::DVec3;

use crate::optics::geometry::{distance_to_entry, distance_to_exit, ray_hits_ground};

/// A shell between two radii around the planet's centre, with the ground below.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shell {
    pub ground_radius_m: f64,
    pub base_radius_m: f64,
    pub top_radius_m: f64,
}

impl Shell {
    /// The first interval `[t0, t1]` of the ray from `origin` along the unit `direction`
    /// inside the shell, ended at `max_distance_m` and on the ground; `None` when the
    /// ray does not enter the shell before either.
    pub fn first_segment(
        &self,
        origin: DVec3,
        direction: DVec3,
        max_distance_m: f64,
    ) -> Option<(f64, f64)> {
        let r = origin.length();
        let mu = (origin.dot(direction) / r).clamp(-1.0, 1.0);
        let (t0, t1) = if r > self.top_radius_m {
            let t0 = distance_to_entry(r, mu, self.top_radius_m)?;
            let t1 = match distance_to_entry(r, mu, self.base_radius_m) {
                Some(t) => t,
                None => {
                    -r * mu
                        + (r * r * (mu * mu - 1.0) + self.top_radius_m.powi(2))
                            .max(0.0)
                            .sqrt()
                }
            };
            (t0, t1)
        } else if r >= self.base_radius_m {
            (0.0, self.exit_distance(origin, direction))
        } else {
            (
                distance_to_exit(r, mu, self.base_radius_m),
                distance_to_exit(r, mu, self.top_radius_m),
            )
        };
        let ground = if ray_hits_ground(r.max(self.ground_radius_m), mu, self.ground_radius_m) {
            distance_to_entry(r.max(self.ground_radius_m), mu, self.ground_radius_m)
                .unwrap_or(f64::INFINITY)
        } else {
            f64::INFINITY
        };
        let t1 = t1.min(max_distance_m).min(ground);
        (t0 < t1).then_some((t0, t1))
    }

    /// From `point` inside the shell along the unit `direction`: the distance to where
    /// the ray leaves it, through the base (going down) or the top.
    pub fn exit_distance(&self, point: DVec3, direction: DVec3) -> f64 {
        let r = point.length().clamp(self.base_radius_m, self.top_radius_m);
        let mu = (point.dot(direction) / point.length()).clamp(-1.0, 1.0);
        distance_to_entry(r, mu, self.base_radius_m)
            .unwrap_or_else(|| distance_to_exit(r, mu, self.top_radius_m))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SHELL: Shell = Shell {
        ground_radius_m: 6_360_000.0,
        base_radius_m: 6_362_000.0,
        top_radius_m: 6_363_000.0,
    };

    #[test]
    fn vertical_rays_cross_the_layer_once() {
        let below = DVec3::new(0.0, 0.0, 6_360_010.0);
        let (t0, t1) = SHELL.first_segment(below, DVec3::Z, f64::INFINITY).unwrap();
        assert!((t0 - 1990.0).abs() < 1e-6 && (t1 - 2990.0).abs() < 1e-6);
        let above = DVec3::new(0.0, 0.0, 6_370_000.0);
        let (t0, t1) = SHELL
            .first_segment(above, -DVec3::Z, f64::INFINITY)
            .unwrap();
        assert!((t0 - 7000.0).abs() < 1e-6 && (t1 - 8000.0).abs() < 1e-6);
        let inside = DVec3::new(0.0, 0.0, 6_362_500.0);
        let (t0, t1) = SHELL
            .first_segment(inside, -DVec3::Z, f64::INFINITY)
            .unwrap();
        assert!(t0 == 0.0 && (t1 - 500.0).abs() < 1e-6);
        // Ended by an object in front of the layer: nothing.
        assert!(SHELL.first_segment(below, DVec3::Z, 100.0).is_none());
    }

    #[test]
    fn a_ray_grazing_the_top_from_above_leaves_through_the_top() {
        let above = DVec3::new(0.0, 0.0, 6_370_000.0);
        // Steep enough to enter the top sphere (|mu| > 0.0469), too shallow to reach
        // the base (|mu| < 0.0501).
        let direction = DVec3::new(1.0, 0.0, -0.048).normalize();
        let (t0, t1) = SHELL
            .first_segment(above, direction, f64::INFINITY)
            .unwrap();
        let exit = above + direction * t1;
        assert!(t1 > t0);
        assert!(
            (exit.length() - SHELL.top_radius_m).abs() < 1e-3,
            "{}",
            exit.length()
        );
    }
}
