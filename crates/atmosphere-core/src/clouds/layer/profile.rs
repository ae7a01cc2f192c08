//! The layer's density at a point: the cover of its place, times a vertical profile
//! between the base and the top, times the erosion of detail noise. The cloud's depth
//! follows the cover (this layer's choice, no paper's): where cover is thin the clouds
//! are shallow, like fair-weather cumulus; where it is full they fill the layer, like
//! nimbostratus.

use glam::DVec3;

use crate::numerics::gradient_noise::fractal_noise;

/// The most octaves of the detail noise.
pub const DETAIL_OCTAVES: u32 = 3;
/// The detail noise's seed.
pub const DETAIL_SEED: u32 = 0x5eed_c10d;
/// The fraction of the layer's thickness over which the density rises at the base.
const BASE_RISE: f64 = 0.1;
/// The cloud top's height fraction at cover 0 (it reaches 1 at cover 1).
const SHALLOWEST_TOP: f64 = 0.35;

/// Smooth step from 0 at `edge0` to 1 at `edge1` (Hermite cubic).
pub fn smoothstep(edge0: f64, edge1: f64, x: f64) -> f64 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The vertical profile at height fraction `x` (0 at the base, 1 at the top) where the
/// cover is `cover`: rising over the lowest tenth, falling over the upper two fifths of
/// the cloud's own depth, whose top lies at `0.35 + 0.65 cover` of the layer.
pub fn vertical_profile(x: f64, cover: f64) -> f64 {
    if !(0.0..=1.0).contains(&x) {
        return 0.0;
    }
    let top = SHALLOWEST_TOP + (1.0 - SHALLOWEST_TOP) * cover;
    smoothstep(0.0, BASE_RISE, x) * (1.0 - smoothstep(0.6 * top, top, x))
}

/// The erosion by detail noise at `point_m` (planet-fixed, metres): 1 minus `strength`
/// times a fractal gradient noise (Perlin 2002) of `octaves` octaves mapped to [0, 1],
/// so it only removes cloud and never adds any where the cover is 0. With 0 octaves the
/// noise is its mean, 0: an erosion of 1 - strength / 2 everywhere.
pub fn detail_erosion(point_m: DVec3, scale_m: f64, strength: f64, octaves: u32) -> f64 {
    if strength == 0.0 {
        return 1.0;
    }
    let n = fractal_noise(DETAIL_SEED, point_m / scale_m, octaves, 0.5);
    1.0 - strength * (0.5 - 0.5 * n.clamp(-1.0, 1.0))
}

/// The density (0 to 1) at height fraction `x`, with cover `cover` and erosion
/// `erosion`.
pub fn density(x: f64, cover: f64, erosion: f64) -> f64 {
    (cover * vertical_profile(x, cover) * erosion).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_profile_vanishes_outside_the_layer_and_at_zero_cover() {
        assert_eq!(vertical_profile(-0.01, 1.0), 0.0);
        assert_eq!(vertical_profile(1.01, 1.0), 0.0);
        assert_eq!(density(0.5, 0.0, 1.0), 0.0);
        assert!((vertical_profile(0.3, 1.0) - 1.0).abs() < 1e-12);
        // A thin cover makes shallow clouds: nothing above 35 % of the layer.
        assert_eq!(vertical_profile(0.36, 0.0), 0.0);
        assert!(vertical_profile(0.15, 0.0) > 0.9);
    }

    #[test]
    fn erosion_stays_in_its_range() {
        for k in 0..200 {
            let p = DVec3::new(k as f64 * 137.0, 6.36e6, k as f64 * -59.0);
            let e = detail_erosion(p, 2000.0, 0.7, DETAIL_OCTAVES);
            assert!((0.3..=1.0).contains(&e), "{e}");
        }
        assert_eq!(detail_erosion(DVec3::ONE, 2000.0, 0.0, 3), 1.0);
        assert_eq!(detail_erosion(DVec3::ONE * 777.0, 2000.0, 0.6, 0), 0.7);
    }
}
