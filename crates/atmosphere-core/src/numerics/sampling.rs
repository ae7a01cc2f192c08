//! Random numbers and directions for the Monte Carlo parts of the reference.

use std::f64::consts::PI;

use glam::DVec3;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// A seeded, reproducible stream of uniform numbers.
#[derive(Clone, Debug)]
pub struct Sampler(Pcg64Mcg);

impl Sampler {
    pub fn new(seed: u64) -> Sampler {
        Sampler(Pcg64Mcg::seed_from_u64(seed))
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0.random::<f64>()
    }
}

/// A 64-bit mix of several values (SplitMix64 finaliser), to derive per-ray seeds that
/// do not depend on thread scheduling.
pub fn mix_seed(values: &[u64]) -> u64 {
    let mut h = 0x9E37_79B9_7F4A_7C15u64;
    for v in values {
        h ^= v
            .wrapping_add(0x9E37_79B9_7F4A_7C15)
            .wrapping_add(h << 6)
            .wrapping_add(h >> 2);
        h = (h ^ (h >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        h = (h ^ (h >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        h ^= h >> 31;
    }
    h
}

/// Two unit vectors completing `n` to an orthonormal basis (Duff et al. 2017).
pub fn orthonormal_basis(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// The direction at cosine `cos_theta` from `axis`, at azimuth `phi` around it.
pub fn direction_around(axis: DVec3, cos_theta: f64, phi: f64) -> DVec3 {
    let (b1, b2) = orthonormal_basis(axis);
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    (axis * cos_theta + (b1 * phi.cos() + b2 * phi.sin()) * sin_theta).normalize()
}

/// A direction uniformly distributed in the cone of half-angle `half_angle` around
/// `axis` (the sun's disk). `1 - cos` is written as `2 sin^2(a/2)` to keep tiny cones
/// accurate.
pub fn uniform_in_cone(axis: DVec3, half_angle: f64, sampler: &mut Sampler) -> DVec3 {
    let one_minus_cos_max = 2.0 * (0.5 * half_angle).sin().powi(2);
    let one_minus_cos = sampler.uniform() * one_minus_cos_max;
    direction_around(axis, 1.0 - one_minus_cos, 2.0 * PI * sampler.uniform())
}

/// A direction with probability density cos(theta) / pi about the normal `n`.
pub fn cosine_weighted(n: DVec3, sampler: &mut Sampler) -> DVec3 {
    let cos_theta = sampler.uniform().sqrt();
    direction_around(n, cos_theta, 2.0 * PI * sampler.uniform())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal() {
        for n in [DVec3::Z, -DVec3::Z, DVec3::new(0.3, -0.5, 0.1).normalize()] {
            let (a, b) = orthonormal_basis(n);
            assert!(a.dot(n).abs() < 1e-12 && b.dot(n).abs() < 1e-12 && a.dot(b).abs() < 1e-12);
            assert!((a.length() - 1.0).abs() < 1e-12 && (b.length() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn cone_samples_stay_in_the_cone_and_fill_it() {
        let mut s = Sampler::new(3);
        let axis = DVec3::new(0.0, 0.6, 0.8);
        let alpha = 0.004675;
        let mut mean_angle = 0.0;
        let n = 20_000;
        for _ in 0..n {
            let d = uniform_in_cone(axis, alpha, &mut s);
            let angle = d.dot(axis).clamp(-1.0, 1.0).acos();
            assert!(angle <= alpha * (1.0 + 1e-6));
            mean_angle += angle / n as f64;
        }
        // Uniform over a small disk: mean radius 2/3 of the radius.
        assert!(
            (mean_angle / alpha - 2.0 / 3.0).abs() < 0.01,
            "{}",
            mean_angle / alpha
        );
    }

    #[test]
    fn cosine_weighted_mean_cosine_is_two_thirds() {
        let mut s = Sampler::new(5);
        let n = DVec3::X;
        let count = 100_000;
        let mean: f64 = (0..count)
            .map(|_| cosine_weighted(n, &mut s).dot(n))
            .sum::<f64>()
            / count as f64;
        assert!((mean - 2.0 / 3.0).abs() < 0.005, "{mean}");
    }
}
