//! Deterministic 3D gradient noise (Perlin 2002, "Improving noise": a pseudo-random unit
//! gradient at every integer lattice point, blended with the quintic fade
//! 6t^5 - 15t^4 + 10t^3) and its fractal sum. Evaluated at points of a sphere it has no
//! seam and no pole. The lattice gradients come from an integer hash of the lattice
//! point and a seed, so a value depends only on (seed, point): the same on every run,
//! thread and machine, and written so a shader can mirror it (u32 arithmetic only).

use glam::DVec3;

/// A 32-bit integer hash with good avalanche (the "lowbias32" mixer: xor-shift and
/// multiply rounds).
fn mix(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// The hash of a lattice point under a seed.
fn lattice_hash(seed: u32, i: i32, j: i32, k: i32) -> u32 {
    mix(seed ^ mix((i as u32) ^ mix((j as u32) ^ mix(k as u32))))
}

/// One of the 12 edge directions of a cube (Perlin 2002), chosen by the hash, dotted with
/// the offset from the lattice point.
fn gradient_dot(hash: u32, offset: DVec3) -> f64 {
    let (x, y, z) = (offset.x, offset.y, offset.z);
    match hash % 12 {
        0 => x + y,
        1 => -x + y,
        2 => x - y,
        3 => -x - y,
        4 => x + z,
        5 => -x + z,
        6 => x - z,
        7 => -x - z,
        8 => y + z,
        9 => -y + z,
        10 => y - z,
        _ => -y - z,
    }
}

fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}

/// Gradient noise at `point`: 0 at every lattice point, within about [-1, 1], continuous
/// with continuous first and second derivatives.
pub fn gradient_noise(seed: u32, point: DVec3) -> f64 {
    let base = point.floor();
    let f = point - base;
    let (i, j, k) = (base.x as i32, base.y as i32, base.z as i32);
    let corner = |di: i32, dj: i32, dk: i32| {
        let offset = f - DVec3::new(di as f64, dj as f64, dk as f64);
        gradient_dot(lattice_hash(seed, i + di, j + dj, k + dk), offset)
    };
    let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
    let x00 = lerp(corner(0, 0, 0), corner(1, 0, 0), u);
    let x10 = lerp(corner(0, 1, 0), corner(1, 1, 0), u);
    let x01 = lerp(corner(0, 0, 1), corner(1, 0, 1), u);
    let x11 = lerp(corner(0, 1, 1), corner(1, 1, 1), u);
    lerp(lerp(x00, x10, v), lerp(x01, x11, v), w)
}

/// Fractal sum of `octaves` octaves of gradient noise: frequency doubling and amplitude
/// `gain` times the last per octave, each octave with its own seed, normalised by the sum
/// of the amplitudes so that the result stays within about [-1, 1].
pub fn fractal_noise(seed: u32, point: DVec3, octaves: u32, gain: f64) -> f64 {
    let (mut sum, mut norm, mut amplitude, mut frequency) = (0.0, 0.0, 1.0, 1.0);
    for octave in 0..octaves {
        sum += amplitude * gradient_noise(mix(seed.wrapping_add(octave)), point * frequency);
        norm += amplitude;
        amplitude *= gain;
        frequency *= 2.0;
    }
    if norm > 0.0 { sum / norm } else { 0.0 }
}

/// A seed derived from `seed` for an independent stream named by `stream`.
pub fn derived_seed(seed: u32, stream: u32) -> u32 {
    mix(seed ^ mix(stream.wrapping_add(0x9e37_79b9)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vanishes_on_the_lattice_and_is_continuous() {
        for p in [DVec3::ZERO, DVec3::new(3.0, -2.0, 7.0)] {
            assert_eq!(gradient_noise(5, p), 0.0);
        }
        let p = DVec3::new(0.999_999_9, 0.3, 0.4);
        let q = DVec3::new(1.000_000_1, 0.3, 0.4);
        assert!((gradient_noise(5, p) - gradient_noise(5, q)).abs() < 1e-5);
    }

    #[test]
    fn has_zero_mean_and_unit_scale_and_depends_on_the_seed() {
        let mut sum = 0.0;
        let mut sum_sq = 0.0;
        let mut max: f64 = 0.0;
        let n = 20_000;
        let mut differs = 0;
        for s in 0..n {
            let p = DVec3::new(s as f64 * 0.731, s as f64 * 0.377 + 0.5, s as f64 * 0.193);
            let v = gradient_noise(11, p);
            sum += v;
            sum_sq += v * v;
            max = max.max(v.abs());
            if (v - gradient_noise(12, p)).abs() > 1e-3 {
                differs += 1;
            }
        }
        let mean = sum / n as f64;
        let rms = (sum_sq / n as f64).sqrt();
        assert!(mean.abs() < 0.02, "{mean}");
        assert!(rms > 0.15 && rms < 0.5, "{rms}");
        assert!(max <= 1.1, "{max}");
        assert!(differs > n * 9 / 10, "{differs}");
    }

    #[test]
    fn the_fractal_sum_stays_in_range() {
        for s in 0..2000 {
            let p = DVec3::new(s as f64 * 0.0131, 1.0 - s as f64 * 0.0077, 0.25);
            let v = fractal_noise(3, p, 8, 0.5);
            assert!(v.abs() <= 1.0, "{v}");
        }
    }
}
