//! Deterministic 3D cellular noise (Worley 1996, "A cellular texture basis function"): one
//! feature point at a hashed position in every unit cell of the lattice; the value at a
//! point is the distance to the nearest feature point (F1), about 0 at a feature point
//! and rarely above 1. Its level sets are round cells, the shape of convective cloud
//! clusters.

use glam::DVec3;

use super::gradient_noise::derived_seed;

/// A uniform number in [0, 1) from a hash.
fn unit(hash: u32) -> f64 {
    f64::from(hash >> 8) / f64::from(1u32 << 24)
}

/// The feature point of lattice cell (i, j, k), in the cell's own unit cube.
fn feature(seed: u32, i: i32, j: i32, k: i32) -> DVec3 {
    let h = derived_seed(
        seed,
        (i as u32).wrapping_mul(73_856_093)
            ^ (j as u32).wrapping_mul(19_349_663)
            ^ (k as u32).wrapping_mul(83_492_791),
    );
    DVec3::new(unit(h), unit(derived_seed(h, 1)), unit(derived_seed(h, 2)))
}

/// Distance from `point` to the nearest feature point (Worley's F1), searching the 27
/// cells around the point's own.
pub fn cellular_distance(seed: u32, point: DVec3) -> f64 {
    let base = point.floor();
    let (i, j, k) = (base.x as i32, base.y as i32, base.z as i32);
    let mut nearest_sq = f64::INFINITY;
    for dk in -1..=1 {
        for dj in -1..=1 {
            for di in -1..=1 {
                let cell = DVec3::new(base.x + di as f64, base.y + dj as f64, base.z + dk as f64);
                let p = cell + feature(seed, i + di, j + dj, k + dk);
                nearest_sq = nearest_sq.min(p.distance_squared(point));
            }
        }
    }
    nearest_sq.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_distance_is_continuous_and_bounded() {
        let mut previous = cellular_distance(7, DVec3::new(0.0, 0.2, 0.3));
        for s in 1..5000 {
            let p = DVec3::new(s as f64 * 1e-3, 0.2, 0.3);
            let d = cellular_distance(7, p);
            assert!((0.0..=3f64.sqrt()).contains(&d), "{d}");
            assert!((d - previous).abs() <= 1.01e-3, "{s}: {previous} -> {d}");
            previous = d;
        }
    }

    #[test]
    fn every_cell_holds_a_feature_point_where_the_distance_vanishes() {
        for (i, j, k) in [(0, 0, 0), (-3, 4, 9), (100, -7, 2)] {
            let p = DVec3::new(i as f64, j as f64, k as f64) + feature(7, i, j, k);
            assert!(cellular_distance(7, p) < 1e-12);
        }
    }
}
