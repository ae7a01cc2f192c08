//! The aerial-perspective volume of Hillaire 2020 (section 5.4): light scattered towards
//! the camera and transmittance from the camera to every depth of a froxel grid, 32
//! depth slices over 32 km, so that any surface within that range costs one look-up.
//!
//! The paper's volume is aligned with the camera frustum (32 x 32 froxels per slice). A
//! CPU ray has no frustum, so the slices here are laid over directions around the camera
//! in the sky-view's [`LatLong`] mapping, 96 x 96 by default: about 1.9 degrees per texel,
//! the paper's 32 texels across a 60 degree field of view. Slice k holds depth
//! (k + 1) range / slices (the last slice on the range), the camera itself being depth 0
//! (radiance 0, transmittance 1); depths between slices are interpolated linearly.
//! Each direction is marched once through all slices with 2 samples per slice (the
//! paper's implementation marches slice k with 2 (k + 1) samples, the same density).
//! Rays are marched as straight lines past the ground, through the ground-level medium,
//! so that slices beyond a surface continue smoothly for interpolation.

use crate::models::hillaire::directions::{LatLong, view_sun_cosine};
use crate::models::hillaire::march::ViewMarch;
use crate::models::hillaire::medium::Medium;
use crate::models::hillaire::multiple_scattering::MultipleScattering;
use crate::models::hillaire::rows::rows_in_parallel;

/// The volume's shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeShape {
    pub grid: LatLong,
    pub slices: usize,
    pub range_m: f64,
    pub samples_per_slice: usize,
}

/// The aerial-perspective volume of one view.
#[derive(Clone, Debug, PartialEq)]
pub struct AerialPerspective {
    pub shape: VolumeShape,
    pub r: f64,
    pub mu_s: f64,
    wavelengths: usize,
    bottom_m: f64,
    /// Per direction of the [`LatLong`] grid (row, column), per slice: radiance per unit
    /// solar irradiance then transmittance, `wavelengths` values each.
    pub values: Vec<f32>,
}

impl AerialPerspective {
    /// Marches every direction through the slices (rows on scoped threads: see
    /// `view_cache`).
    pub fn build(
        medium: &Medium,
        multiple: Option<&MultipleScattering>,
        shape: VolumeShape,
        r: f64,
        mu_s: f64,
    ) -> AerialPerspective {
        let n = medium.wavelengths();
        let bottom = medium.atmosphere.bottom_radius_m;
        let grid = shape.grid;
        let slice_m = shape.range_m / shape.slices as f64;
        let dt = slice_m / shape.samples_per_slice as f64;
        let values = rows_in_parallel(grid.height, |j| {
            let mut row = Vec::with_capacity(grid.width * shape.slices * 2 * n);
            for i in 0..grid.width {
                let (mu, phi, _) = grid.texel_direction(r, bottom, i, j);
                let nu = view_sun_cosine(mu, phi, mu_s);
                let mut march = ViewMarch::new(*medium, multiple, r, mu, mu_s, nu);
                for k in 0..shape.slices {
                    for s in 0..shape.samples_per_slice {
                        march.segment(k as f64 * slice_m + (s as f64 + 0.5) * dt, dt);
                    }
                    row.extend(march.radiance.iter().map(|v| *v as f32));
                    row.extend(march.throughput.iter().map(|v| *v as f32));
                }
            }
            row
        });
        AerialPerspective {
            shape,
            r,
            mu_s,
            wavelengths: n,
            bottom_m: bottom,
            values,
        }
    }

    /// Radiance per unit solar irradiance and transmittance from the camera to `depth_m`
    /// (at most the range) along direction cosine `mu` and azimuth `phi` from the sun; the
    /// ray ends on the `ground` side of the horizon or not.
    pub fn lookup(
        &self,
        mu: f64,
        phi: f64,
        ground: bool,
        depth_m: f64,
        radiance: &mut [f64],
        transmittance: &mut [f64],
    ) {
        let grid = self.shape.grid;
        let n = self.wavelengths;
        let stride = self.shape.slices * 2 * n;
        let p = grid.position(self.r, self.bottom_m, mu, phi, ground);
        let read = |k: usize, out: &mut [f64], second: bool| {
            let offset = (2 * k + usize::from(second)) * n;
            grid.interpolate(&self.values, stride, offset, &p, ground, out);
        };
        let f = (depth_m / self.shape.range_m).clamp(0.0, 1.0) * self.shape.slices as f64;
        if f <= 1.0 {
            // Between the camera (radiance 0, transmittance 1) and the first slice.
            read(0, radiance, false);
            read(0, transmittance, true);
            for w in 0..n {
                radiance[w] *= f;
                transmittance[w] = 1.0 + f * (transmittance[w] - 1.0);
            }
            return;
        }
        let k = ((f - 1.0) as usize).min(self.shape.slices - 2);
        let a = f - 1.0 - k as f64;
        let mut next = vec![0.0; n];
        for (out, second) in [(radiance, false), (transmittance, true)] {
            read(k, out, second);
            read(k + 1, &mut next, second);
            for w in 0..n {
                out[w] += a * (next[w] - out[w]);
            }
        }
    }

    /// Bytes held by a volume of `shape` at `wavelengths` wavelengths.
    pub fn bytes_for(shape: VolumeShape, wavelengths: usize) -> usize {
        2 * shape.grid.width
            * shape.grid.height
            * shape.slices
            * wavelengths
            * std::mem::size_of::<f32>()
    }
}
