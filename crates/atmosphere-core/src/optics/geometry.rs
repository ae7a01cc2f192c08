//! Rays and spheres around a planet, in the (r, mu) form of Bruneton 2017: `r` is the
//! distance of a point from the planet's centre and `mu` the cosine of the angle between
//! a ray's direction and the local zenith. Each formula is arranged to stay accurate where
//! the naive one cancels: rays grazing the horizon, points exactly on a sphere, points far
//! out in space.

/// `sqrt(max(x, 0))`: rounding may make an exact zero slightly negative.
pub fn safe_sqrt(x: f64) -> f64 {
    x.max(0.0).sqrt()
}

/// `r^2 (mu^2 - 1) + radius^2`, the discriminant of the ray-sphere equation, written as
/// `(r mu)^2 - (r - radius)(r + radius)` so that points on or near the sphere keep their
/// accuracy.
pub fn discriminant(r: f64, mu: f64, radius: f64) -> f64 {
    (r * mu) * (r * mu) - (r - radius) * (r + radius)
}

/// Distance along the ray from a point inside the sphere (r <= radius) to where it
/// leaves the sphere (the far root).
pub fn distance_to_exit(r: f64, mu: f64, radius: f64) -> f64 {
    let root = safe_sqrt(discriminant(r, mu, radius));
    // For mu > 0 avoid -r mu + root (cancellation): use the product of the roots.
    let far = if mu > 0.0 {
        let q = r * mu + root;
        if q > 0.0 {
            -((r - radius) * (r + radius)) / q
        } else {
            0.0
        }
    } else {
        -r * mu + root
    };
    far.max(0.0)
}

/// Distance along the ray to the near intersection with the sphere of `radius`, for a ray
/// that hits it from outside (or from on it), `None` if it misses or points away.
pub fn distance_to_entry(r: f64, mu: f64, radius: f64) -> Option<f64> {
    let disc = discriminant(r, mu, radius);
    if disc < 0.0 || mu >= 0.0 && r >= radius {
        return None;
    }
    let root = disc.sqrt();
    // Near root -r mu - root with mu < 0; as (r^2 - radius^2) / (-r mu + root) it does not
    // cancel.
    let q = -r * mu + root;
    if q <= 0.0 {
        return Some(0.0);
    }
    Some(((r - radius) * (r + radius) / q).max(0.0))
}

/// Whether a ray from radius `r` (at or above the ground) with direction cosine `mu`
/// meets the ground sphere.
pub fn ray_hits_ground(r: f64, mu: f64, bottom_radius: f64) -> bool {
    mu < 0.0 && discriminant(r, mu, bottom_radius) >= 0.0
}

/// Cosine of the zenith angle of the geometric horizon seen from radius `r`:
/// `-sqrt(1 - (R / r)^2)`, written without cancellation.
pub fn horizon_mu(r: f64, bottom_radius: f64) -> f64 {
    if r <= bottom_radius {
        return 0.0;
    }
    -(safe_sqrt((r - bottom_radius) * (r + bottom_radius)) / r)
}

/// The radius at distance `t` along a ray from (r, mu): `sqrt(r^2 + t^2 + 2 r mu t)`.
pub fn radius_at(r: f64, mu: f64, t: f64) -> f64 {
    safe_sqrt(r * r + t * t + 2.0 * r * mu * t)
}

/// The direction cosine at distance `t` along a ray from (r, mu), to the local zenith there.
pub fn mu_at(r: f64, mu: f64, t: f64) -> f64 {
    let r_t = radius_at(r, mu, t);
    if r_t == 0.0 {
        return 1.0;
    }
    ((r * mu + t) / r_t).clamp(-1.0, 1.0)
}

/// Distances along the ray where it crosses the sphere of radius `radius`, in increasing
/// order, restricted to t >= 0.
pub fn crossings(r: f64, mu: f64, radius: f64) -> Vec<f64> {
    let disc = discriminant(r, mu, radius);
    if disc < 0.0 {
        return Vec::new();
    }
    let root = disc.sqrt();
    let near = -r * mu - root;
    let far = -r * mu + root;
    [near, far].into_iter().filter(|t| *t >= 0.0).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: f64 = 6_360_000.0;
    const TOP: f64 = 6_420_000.0;

    #[test]
    fn vertical_rays_have_exact_distances() {
        assert_eq!(distance_to_exit(R, 1.0, TOP), TOP - R);
        assert_eq!(distance_to_exit(TOP, -1.0, TOP), 2.0 * TOP);
        assert_eq!(distance_to_entry(TOP + 1000.0, -1.0, TOP), Some(1000.0));
        assert_eq!(
            distance_to_entry(TOP + 1000.0, -1.0, R),
            Some(TOP + 1000.0 - R)
        );
        assert_eq!(distance_to_entry(TOP + 1000.0, 1.0, TOP), None);
    }

    #[test]
    fn horizontal_ray_on_the_ground_reaches_the_top_at_the_tangent_distance() {
        let expected = (TOP * TOP - R * R).sqrt();
        let got = distance_to_exit(R, 0.0, TOP);
        assert!((got - expected).abs() < 1e-6, "{got} vs {expected}");
    }

    #[test]
    fn exits_agree_with_the_radius_reached() {
        for &(r, mu) in &[
            (R, 0.3),
            (R + 1.0, -1e-6),
            (R + 5_000.0, 0.99),
            (TOP, 1e-9),
            (TOP, -0.2),
            (R + 30_000.0, -0.05),
        ] {
            let d = distance_to_exit(r, mu, TOP);
            let reached = radius_at(r, mu, d);
            assert!(
                (reached - TOP).abs() < 1e-6 * TOP,
                "r={r} mu={mu}: {reached}"
            );
        }
    }

    #[test]
    fn far_away_camera_enters_accurately() {
        let r = 1e8 + R;
        let mu = -0.999;
        let d = distance_to_entry(r, mu, TOP).unwrap();
        let reached = radius_at(r, mu, d);
        assert!((reached - TOP).abs() < 1e-3, "{reached}");
    }

    #[test]
    fn ground_hit_and_horizon_agree() {
        let r = R + 10_000.0;
        let h = horizon_mu(r, R);
        assert!(ray_hits_ground(r, h - 1e-9, R));
        assert!(!ray_hits_ground(r, h + 1e-9, R));
        // A camera exactly on the ground sees the ground below the horizontal.
        assert!(ray_hits_ground(R, -1e-12, R));
        assert!(!ray_hits_ground(R, 0.0, R));
        assert_eq!(horizon_mu(R, R), 0.0);
    }
}
