//! The m spheres of Dobashi, Yamamoto and Nishita 2002, section 5.4 (their Fig. 8): the
//! cloud layer between its base and top is cut into m equal shells, and cloud sphere i
//! stands for shell i (0 the lowest). A view ray crosses a shell in at most two
//! intervals (in and out again when it passes below the shell's inner sphere and
//! misses the ground); all crossings of a ray, sorted by distance, are what the
//! spheres' back-to-front composite walks. In the (r, mu) form of `optics/geometry.rs`.

use glam::DVec3;

use crate::optics::geometry::discriminant;

/// The m shells on a planet: the ground, the layer's base and thickness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shells {
    pub ground_radius_m: f64,
    pub base_radius_m: f64,
    pub thickness_m: f64,
    pub count: u32,
}

/// One interval of a ray inside shell `shell`, from `t0` to `t1` (m along the ray).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    pub shell: usize,
    pub t0: f64,
    pub t1: f64,
}

impl Shells {
    /// The thickness of one shell, m.
    pub fn shell_thickness_m(&self) -> f64 {
        self.thickness_m / f64::from(self.count)
    }

    /// The inner and outer radius of shell `k`, m.
    pub fn bounds_m(&self, k: usize) -> (f64, f64) {
        let h = self.shell_thickness_m();
        let inner = self.base_radius_m + k as f64 * h;
        (inner, inner + h)
    }

    /// The radius of cloud sphere `k`, the middle of its shell, m.
    pub fn sphere_radius_m(&self, k: usize) -> f64 {
        let (inner, outer) = self.bounds_m(k);
        (inner + outer) / 2.0
    }

    /// Every interval of the ray from `origin` along the unit `direction` inside a
    /// shell, ended at `max_distance_m` and where the ray meets the ground, sorted by
    /// their start. The second element tells whether the ray meets the ground before
    /// `max_distance_m`.
    pub fn crossings(
        &self,
        origin: DVec3,
        direction: DVec3,
        max_distance_m: f64,
    ) -> (Vec<Crossing>, bool) {
        let r = origin.length();
        let mu = (origin.dot(direction) / r).clamp(-1.0, 1.0);
        let ground = match roots(r, mu, self.ground_radius_m) {
            Some((near, _)) if near >= 0.0 && mu < 0.0 => near,
            _ => f64::INFINITY,
        };
        let end = max_distance_m.min(ground);
        let mut found = Vec::new();
        for k in 0..self.count as usize {
            let (inner, outer) = self.bounds_m(k);
            let Some((a, b)) = roots(r, mu, outer) else {
                continue;
            };
            let pieces = match roots(r, mu, inner) {
                Some((c, d)) => [(a, b.min(c)), (a.max(d), b)],
                None => [(a, b), (f64::INFINITY, f64::INFINITY)],
            };
            for (t0, t1) in pieces {
                let (t0, t1) = (t0.max(0.0), t1.min(end));
                if t0 < t1 {
                    found.push(Crossing { shell: k, t0, t1 });
                }
            }
        }
        found.sort_by(|p, q| p.t0.total_cmp(&q.t0));
        (found, ground.is_finite() && ground <= max_distance_m)
    }
}

/// The two distances (near, far) where the line through a point at radius `r` with
/// direction cosine `mu` meets the sphere of `radius`, negative behind the point; `None`
/// when it misses. The product of the roots gives the smaller one without cancellation.
pub fn roots(r: f64, mu: f64, radius: f64) -> Option<(f64, f64)> {
    let disc = discriminant(r, mu, radius);
    if disc < 0.0 {
        return None;
    }
    let b = r * mu;
    let q = -(b + b.signum() * disc.sqrt());
    let c = (r - radius) * (r + radius);
    if q == 0.0 {
        return Some((0.0, 0.0));
    }
    let (p, s) = (q, c / q);
    Some((p.min(s), p.max(s)))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SHELLS: Shells = Shells {
        ground_radius_m: 6_360_000.0,
        base_radius_m: 6_361_500.0,
        thickness_m: 1500.0,
        count: 5,
    };

    #[test]
    fn a_vertical_ray_from_orbit_crosses_each_shell_once_down_to_the_ground() {
        let origin = DVec3::new(0.0, 0.0, 6_360_000.0 + 4e5);
        let (found, ground) = SHELLS.crossings(origin, -DVec3::Z, f64::INFINITY);
        assert!(ground);
        assert_eq!(found.len(), 5);
        for (n, c) in found.iter().enumerate() {
            assert_eq!(c.shell, 4 - n);
            assert!((c.t1 - c.t0 - 300.0).abs() < 1e-6, "{c:?}");
        }
        assert!((found[0].t0 - (4e5 - 3000.0)).abs() < 1e-6);
    }

    #[test]
    fn a_limb_ray_enters_and_leaves_the_upper_shells() {
        // Tangent 2 km above the ground, inside shell 1 (1.8 to 2.1 km): shell 0 is
        // missed, shell 1 crossed in one interval, shells 2 to 4 in and out again.
        let r: f64 = 6_360_000.0 + 4e5;
        let tangent: f64 = 6_362_000.0;
        let mu = -(1.0 - (tangent / r) * (tangent / r)).sqrt();
        let origin = DVec3::new(0.0, 0.0, r);
        let direction = DVec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        let (found, ground) = SHELLS.crossings(origin, direction, f64::INFINITY);
        assert!(!ground);
        assert_eq!(found.len(), 7, "{found:?}");
        assert_eq!(found[3].shell, 1);
        assert!(found.windows(2).all(|w| w[0].t1 <= w[1].t0 + 1e-6));
        let shells: Vec<usize> = found.iter().map(|c| c.shell).collect();
        assert_eq!(shells, vec![4, 3, 2, 1, 2, 3, 4]);
    }

    #[test]
    fn roots_are_accurate_on_the_sphere() {
        let (near, far) = roots(6_361_500.0, -0.5, 6_361_500.0).unwrap();
        assert_eq!(near, 0.0);
        assert!((far - 6_361_500.0).abs() < 1e-6);
        assert!(roots(7e6, 0.5, 6.4e6).unwrap().1 < 0.0);
        assert!(roots(7e6, 0.0, 6.4e6).is_none());
    }
}
