//! A smooth ball of voxel cloud for the volume's tests.

use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::volume::cloud::VoxelCloud;
use atmosphere_core::clouds::volume::grid::VoxelGrid;
use glam::DVec3;

/// Density exp(-4 r^2) (1 - r^2), 0 on the grid's faces, in a 24^3 grid of 10 m voxels
/// centred on the origin (r in units of the grid's half side), of extinction `sigma`
/// m^-1 at density 1: optical depth about 200 sigma through its centre.
pub fn smooth_ball(sigma: f64, albedo: f64, phase: CloudPhase) -> VoxelCloud {
    let n = 24;
    let density = (0..n * n * n)
        .map(|k| {
            let c = |i: usize| (i as f64 + 0.5) / (n as f64 / 2.0) - 1.0;
            let (x, y, z) = (c(k % n), c((k / n) % n), c(k / (n * n)));
            let r2 = x * x + y * y + z * z;
            if r2 >= 1.0 {
                0.0
            } else {
                ((-4.0 * r2).exp() * (1.0 - r2)) as f32
            }
        })
        .collect();
    let grid = VoxelGrid::new([n, n, n], density).unwrap();
    VoxelCloud::new(grid, DVec3::splat(-120.0), 10.0, sigma, albedo, phase).unwrap()
}
