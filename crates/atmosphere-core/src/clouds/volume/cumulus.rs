//! A generated cumulus, deterministic: a union of spherical blobs in four tiers of
//! shrinking radius (a broad base, a narrower tower, a crown: the cauliflower top),
//! their radii carved by fractal gradient noise (Perlin 2002, `numerics/gradient_noise.rs`)
//! so that the surface billows, cut by a flat base where the air reaches saturation.
//! The blob field is s(p) = max over blobs of 1 - |p - c| / (r (1 + 0.3 n(p))), n the
//! noise of 4 octaves over 12 voxels; the density is smoothstep(0, 0.3, s) above the
//! base (ramped over 2 voxels), 0 below it and on the grid's outer voxels. The shipped
//! `assets/scenes/clouds/cumulus.u8` is [`cumulus`] as bytes
//! (`cargo run -p atmosphere-core --example generate_cumulus`).

use glam::DVec3;

use super::grid::VoxelGrid;
use crate::numerics::gradient_noise::{derived_seed, fractal_noise};

/// The generated grid's size, voxels (x, y, z up).
pub const CUMULUS_DIMS: [usize; 3] = [96, 96, 64];
/// The noise's and the blobs' seed.
pub const CUMULUS_SEED: u32 = 2004;
/// The flat base's height, voxels.
const BASE: f64 = 6.0;

/// A blob: centre and radius in voxels.
struct Blob {
    centre: DVec3,
    radius: f64,
}

/// A number in [0, 1) from the seed's stream `k`.
fn uniform(k: u32) -> f64 {
    f64::from(derived_seed(CUMULUS_SEED, k)) / 4_294_967_296.0
}

/// The tiers: (blobs, ring radius, height of the centres above the base, radius), each
/// blob's angle, ring distance and radius jittered.
fn blobs() -> Vec<Blob> {
    let tiers = [
        (7, 17.0, 9.0, 15.0),
        (5, 10.0, 22.0, 12.0),
        (3, 6.0, 33.0, 9.5),
        (1, 0.0, 42.0, 7.5),
    ];
    let (cx, cy) = (CUMULUS_DIMS[0] as f64 / 2.0, CUMULUS_DIMS[1] as f64 / 2.0);
    let mut list = vec![Blob {
        centre: DVec3::new(cx, cy, BASE + 8.0),
        radius: 19.0,
    }];
    let mut k = 0;
    for (count, ring, height, radius) in tiers {
        for b in 0..count {
            let angle =
                (f64::from(b) + 0.6 * uniform(k)) / f64::from(count) * std::f64::consts::TAU;
            let distance = ring * (0.8 + 0.4 * uniform(k + 1));
            list.push(Blob {
                centre: DVec3::new(
                    cx + distance * angle.cos(),
                    cy + distance * angle.sin(),
                    BASE + height + 3.0 * (uniform(k + 2) - 0.5),
                ),
                radius: radius * (0.85 + 0.3 * uniform(k + 3)),
            });
            k += 4;
        }
    }
    list
}

fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The generated cumulus (the module's recipe) on a [`CUMULUS_DIMS`] grid.
pub fn cumulus() -> VoxelGrid {
    let [nx, ny, nz] = CUMULUS_DIMS;
    let blobs = blobs();
    let mut density = vec![0.0f32; nx * ny * nz];
    for k in 1..nz - 1 {
        for j in 1..ny - 1 {
            for i in 1..nx - 1 {
                let p = DVec3::new(i as f64, j as f64, k as f64) + 0.5;
                if p.z < BASE {
                    continue;
                }
                let carve = 1.0 + 0.3 * fractal_noise(CUMULUS_SEED, p / 12.0, 4, 0.5);
                let s = blobs
                    .iter()
                    .map(|b| 1.0 - p.distance(b.centre) / (b.radius * carve))
                    .fold(f64::NEG_INFINITY, f64::max);
                let value = smoothstep(0.0, 0.3, s) * smoothstep(BASE, BASE + 2.0, p.z);
                density[(k * ny + j) * nx + i] = value as f32;
            }
        }
    }
    VoxelGrid::new(CUMULUS_DIMS, density).expect("the cumulus's densities lie in [0, 1]")
}
