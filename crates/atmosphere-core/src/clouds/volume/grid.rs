//! A voxel grid of cloud density: `dims = [nx, ny, nz]` values in [0, 1], x fastest,
//! z slowest, each the density at its voxel's centre. Between centres the density is
//! trilinear; beyond the outermost centres it is the edge voxel's (clamped), so a grid
//! whose outer voxels are 0 fades to nothing at its faces.

use glam::DVec3;

use crate::clouds::error::CloudError;

/// The most voxels along one side.
pub const MAX_SIDE: usize = 1024;
/// The most voxels in all (128 MiB of f32).
pub const MAX_VOXELS: usize = 1 << 25;

/// Densities in [0, 1] on a regular grid.
#[derive(Clone, Debug, PartialEq)]
pub struct VoxelGrid {
    dims: [usize; 3],
    density: Vec<f32>,
}

impl VoxelGrid {
    /// The grid of `dims` with `density` (x fastest); refuses a side of 0 or over
    /// [`MAX_SIDE`], more than [`MAX_VOXELS`] voxels, a count that does not match, and a
    /// value outside [0, 1] or not finite, naming the voxel.
    pub fn new(dims: [usize; 3], density: Vec<f32>) -> Result<VoxelGrid, CloudError> {
        check_dims(dims)?;
        let count = dims[0] * dims[1] * dims[2];
        if density.len() != count {
            return Err(CloudError(format!(
                "voxel grid of {} x {} x {} needs {count} values, got {}",
                dims[0],
                dims[1],
                dims[2],
                density.len()
            )));
        }
        if let Some(k) = density
            .iter()
            .position(|d| !(d.is_finite() && (0.0..=1.0).contains(d)))
        {
            let (i, j, l) = (
                k % dims[0],
                (k / dims[0]) % dims[1],
                k / (dims[0] * dims[1]),
            );
            return Err(CloudError(format!(
                "voxel ({i}, {j}, {l}) has density {} outside [0, 1]",
                density[k]
            )));
        }
        Ok(VoxelGrid { dims, density })
    }

    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// The values, x fastest.
    pub fn values(&self) -> &[f32] {
        &self.density
    }

    /// The value of voxel (i, j, k).
    pub fn at(&self, i: usize, j: usize, k: usize) -> f32 {
        self.density[(k * self.dims[1] + j) * self.dims[0] + i]
    }

    /// The largest value.
    pub fn max_density(&self) -> f32 {
        self.density.iter().copied().fold(0.0, f32::max)
    }

    /// The trilinear density at `u` in voxel units (voxel (i, j, k) spans [i, i + 1] in
    /// x, its centre at i + 0.5), clamped to the edge voxels.
    pub fn sample(&self, u: DVec3) -> f64 {
        let axis = |x: f64, n: usize| {
            let c = (x - 0.5).clamp(0.0, (n - 1) as f64);
            let i = (c.floor() as usize).min(n.saturating_sub(2));
            (i, (i + 1).min(n - 1), c - i as f64)
        };
        let (i0, i1, fx) = axis(u.x, self.dims[0]);
        let (j0, j1, fy) = axis(u.y, self.dims[1]);
        let (k0, k1, fz) = axis(u.z, self.dims[2]);
        let v = |i, j, k| f64::from(self.at(i, j, k));
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        let x00 = lerp(v(i0, j0, k0), v(i1, j0, k0), fx);
        let x10 = lerp(v(i0, j1, k0), v(i1, j1, k0), fx);
        let x01 = lerp(v(i0, j0, k1), v(i1, j0, k1), fx);
        let x11 = lerp(v(i0, j1, k1), v(i1, j1, k1), fx);
        lerp(lerp(x00, x10, fy), lerp(x01, x11, fy), fz)
    }
}

/// `Ok` when every side lies in [1, MAX_SIDE] and the voxels number at most
/// [`MAX_VOXELS`].
pub fn check_dims(dims: [usize; 3]) -> Result<(), CloudError> {
    for (axis, &n) in ["x", "y", "z"].iter().zip(&dims) {
        if !(1..=MAX_SIDE).contains(&n) {
            return Err(CloudError(format!(
                "voxel grid dims {axis} = {n} must lie in [1, {MAX_SIDE}]"
            )));
        }
    }
    let count = dims[0] * dims[1] * dims[2];
    if count > MAX_VOXELS {
        return Err(CloudError(format!(
            "voxel grid of {} x {} x {} = {count} voxels is more than {MAX_VOXELS}",
            dims[0], dims[1], dims[2]
        )));
    }
    Ok(())
}
