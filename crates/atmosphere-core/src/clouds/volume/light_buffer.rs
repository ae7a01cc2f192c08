//! The light buffer of half-angle slicing (Riley et al. 2004 sections 4.2.2 and 5): an
//! image seen from the sun, orthographic along the light's direction l, over the
//! volume's box; each texel holds, for the column of light through it, the sun's
//! intensity I at each wavelength and the optical depth tau it has crossed (Riley et al.
//! keep n = albedo tau in the alpha channel). Each slice advances every texel by Riley's
//! Eq. 25 over the slice's optical depth d = sigma Delta_l along the light (one factor per
//! slice, as the paper applies it), and adds d to tau. Reads between texel centres are
//! bilinear.

use glam::DVec3;

use super::cloud::VoxelCloud;
use super::half_angle::HalfAngle;
use crate::clouds::layer::march::riley_step;
use crate::clouds::layer::orders::ScatteringOrders;
use crate::clouds::medium::CloudMedium;

/// The light's image of one volume: texel (i, j) is the column of light through
/// e_u (u0 + (i + 1/2) du) + e_v (v0 + (j + 1/2) dv).
#[derive(Clone, Debug, PartialEq)]
pub struct LightBuffer {
    pub e_u: DVec3,
    pub e_v: DVec3,
    /// The lowest corner's coordinates and the texel's size along e_u and e_v, m.
    pub u0: f64,
    pub v0: f64,
    pub du: f64,
    pub dv: f64,
    pub side: usize,
    pub wavelengths: usize,
    /// `[(j * side + i) * wavelengths + w]`.
    pub intensity: Vec<f64>,
    /// `[j * side + i]`.
    pub depth: Vec<f64>,
}

impl LightBuffer {
    /// A buffer of `side` x `side` texels covering the box of `corners` seen along the
    /// unit `light`: intensity 1, depth 0.
    pub fn new(light: DVec3, corners: &[DVec3; 8], side: usize, wavelengths: usize) -> LightBuffer {
        let (e_u, e_v) = light.any_orthonormal_pair();
        let bounds = |e: DVec3| {
            corners
                .iter()
                .map(|c| c.dot(e))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                    (a.min(x), b.max(x))
                })
        };
        let ((u0, u1), (v0, v1)) = (bounds(e_u), bounds(e_v));
        LightBuffer {
            e_u,
            e_v,
            u0,
            v0,
            du: (u1 - u0) / side as f64,
            dv: (v1 - v0) / side as f64,
            side,
            wavelengths,
            intensity: vec![1.0; side * side * wavelengths],
            depth: vec![0.0; side * side],
        }
    }

    /// A point on texel (i, j)'s column.
    pub fn texel_point(&self, i: usize, j: usize) -> DVec3 {
        self.e_u * (self.u0 + (i as f64 + 0.5) * self.du)
            + self.e_v * (self.v0 + (j as f64 + 0.5) * self.dv)
    }

    /// The bilinear intensity (into `intensity`, one per wavelength) and depth at `p`,
    /// clamped to the edge texels.
    pub fn read(&self, p: DVec3, intensity: &mut [f64]) -> f64 {
        let axis = |x: f64| {
            let c = x.clamp(0.0, (self.side - 1) as f64);
            let i = (c.floor() as usize).min(self.side.saturating_sub(2));
            (i, (i + 1).min(self.side - 1), c - i as f64)
        };
        let (i0, i1, fx) = axis((p.dot(self.e_u) - self.u0) / self.du - 0.5);
        let (j0, j1, fy) = axis((p.dot(self.e_v) - self.v0) / self.dv - 0.5);
        let weights = [
            (i0, j0, (1.0 - fx) * (1.0 - fy)),
            (i1, j0, fx * (1.0 - fy)),
            (i0, j1, (1.0 - fx) * fy),
            (i1, j1, fx * fy),
        ];
        intensity.fill(0.0);
        let mut depth = 0.0;
        for (i, j, weight) in weights {
            let texel = j * self.side + i;
            depth += weight * self.depth[texel];
            for (w, value) in intensity.iter_mut().enumerate() {
                *value += weight * self.intensity[texel * self.wavelengths + w];
            }
        }
        depth
    }

    /// Advances every texel's column across slice `k` of `slices` through `cloud`: where
    /// the column meets the slice inside the box, d = sigma Delta_l multiplies I by
    /// Riley's Eq. 25 factor and adds to tau.
    pub fn advance(
        &mut self,
        cloud: &VoxelCloud,
        slices: &HalfAngle,
        k: u32,
        orders: &ScatteringOrders,
    ) {
        let step = slices.light_step_m();
        let cosine = slices.light.dot(slices.half);
        let albedo = cloud.albedo();
        for j in 0..self.side {
            for i in 0..self.side {
                let q = self.texel_point(i, j);
                let p = q + slices.light * ((slices.offset_m(k) - q.dot(slices.half)) / cosine);
                let d = cloud.extinction(p) * step;
                if d <= 0.0 {
                    continue;
                }
                let texel = j * self.side + i;
                let walked = self.depth[texel];
                for w in 0..self.wavelengths {
                    self.intensity[texel * self.wavelengths + w] *=
                        riley_step(orders, w, albedo, walked, d);
                }
                self.depth[texel] = walked + d;
            }
        }
    }
}
