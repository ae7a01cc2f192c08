//! The voxel cloud as a medium: a [`VoxelGrid`] placed as an axis-aligned box in the
//! scene's frame (metres, z up), its extinction the grid's density times
//! `extinction_per_m`. It implements [`CloudMedium`], so the layer's ray march and the
//! path tracer walk it as they walk the layer.

use glam::DVec3;

use super::grid::VoxelGrid;
use crate::clouds::error::{CloudError, check_range};
use crate::clouds::layer::orders::{ANGLES, ScatteringOrders};
use crate::clouds::medium::CloudMedium;
use crate::clouds::phase::CloudPhase;
use crate::optics::phase::PhaseFunction;

/// The smallest and largest voxel accepted, m.
pub const MIN_VOXEL_M: f64 = 1e-3;
pub const MAX_VOXEL_M: f64 = 1e4;
/// The densest cloud accepted, m^-1 (as the layer's).
pub const MAX_EXTINCTION_PER_M: f64 = 1.0;
/// The farthest a volume's corner may lie from the scene's origin, m.
pub const MAX_ORIGIN_M: f64 = 1e7;

/// A voxel grid of droplets placed in the scene.
#[derive(Clone, Debug)]
pub struct VoxelCloud {
    grid: VoxelGrid,
    /// The box's lowest corner, m.
    origin_m: DVec3,
    voxel_m: f64,
    extinction_per_m: f64,
    albedo: f64,
    phase: CloudPhase,
}

impl VoxelCloud {
    /// `grid` with its lowest corner at `origin_m`, voxels `voxel_m` on a side, extinction
    /// `extinction_per_m` at density 1 and single-scattering `albedo`, each checked
    /// against its range; `phase` is what the path tracer samples.
    pub fn new(
        grid: VoxelGrid,
        origin_m: DVec3,
        voxel_m: f64,
        extinction_per_m: f64,
        albedo: f64,
        phase: CloudPhase,
    ) -> Result<VoxelCloud, CloudError> {
        for (axis, v) in ["x", "y", "z"].iter().zip(origin_m.to_array()) {
            check_range(
                &format!("volume origin_m {axis}"),
                v,
                -MAX_ORIGIN_M,
                MAX_ORIGIN_M,
            )?;
        }
        check_range("volume voxel_m", voxel_m, MIN_VOXEL_M, MAX_VOXEL_M)?;
        check_range(
            "volume extinction_per_m",
            extinction_per_m,
            0.0,
            MAX_EXTINCTION_PER_M,
        )?;
        check_range("volume albedo", albedo, 0.0, 1.0)?;
        Ok(VoxelCloud {
            grid,
            origin_m,
            voxel_m,
            extinction_per_m,
            albedo,
            phase,
        })
    }

    pub fn grid(&self) -> &VoxelGrid {
        &self.grid
    }

    pub fn origin_m(&self) -> DVec3 {
        self.origin_m
    }

    pub fn voxel_m(&self) -> f64 {
        self.voxel_m
    }

    pub fn extinction_per_m(&self) -> f64 {
        self.extinction_per_m
    }

    pub fn albedo(&self) -> f64 {
        self.albedo
    }

    /// The box's lowest and highest corners, m.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        let [nx, ny, nz] = self.grid.dims();
        let size = DVec3::new(nx as f64, ny as f64, nz as f64) * self.voxel_m;
        (self.origin_m, self.origin_m + size)
    }

    /// The box's eight corners.
    pub fn corners(&self) -> [DVec3; 8] {
        let (lo, hi) = self.bounds();
        std::array::from_fn(|k| {
            DVec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        })
    }

    /// Whether `p` lies in the box (faces included).
    pub fn contains(&self, p: DVec3) -> bool {
        let (lo, hi) = self.bounds();
        p.cmpge(lo).all() && p.cmple(hi).all()
    }

    /// The interval `[t0, t1]`, t0 >= 0, of the ray from `origin` along the unit
    /// `direction` inside the box (the slab method), `None` when it misses.
    pub fn crossing(&self, origin: DVec3, direction: DVec3) -> Option<(f64, f64)> {
        let (lo, hi) = self.bounds();
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        for a in 0..3 {
            let (o, d) = (origin[a], direction[a]);
            if d == 0.0 {
                if o < lo[a] || o > hi[a] {
                    return None;
                }
                continue;
            }
            let (ta, tb) = ((lo[a] - o) / d, (hi[a] - o) / d);
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
        }
        (t0 < t1).then_some((t0, t1))
    }
}

impl CloudMedium for VoxelCloud {
    fn extinction(&self, position: DVec3) -> f64 {
        if !self.contains(position) {
            return 0.0;
        }
        let u = (position - self.origin_m) / self.voxel_m;
        self.extinction_per_m * self.grid.sample(u)
    }

    fn single_scattering_albedo(&self, _position: DVec3) -> f64 {
        self.albedo
    }

    fn phase(&self) -> &CloudPhase {
        &self.phase
    }

    fn majorant(&self) -> f64 {
        self.extinction_per_m * f64::from(self.grid.max_density())
    }

    fn distance_to_boundary(&self, position: DVec3, direction: DVec3) -> f64 {
        self.crossing(position, direction).map_or(0.0, |(_, t1)| t1)
    }
}

/// The phase function A_1 of `orders` at wavelength `w` as a [`CloudPhase`]: the
/// single-scattering phase function the march's tables were made of, for the path
/// tracer.
pub fn single_scattering_phase(
    orders: &ScatteringOrders,
    w: usize,
) -> Result<CloudPhase, CloudError> {
    let angles_deg = (0..ANGLES)
        .map(|k| k as f64 * 180.0 / (ANGLES - 1) as f64)
        .collect();
    let values = orders.table(w)[..ANGLES].to_vec();
    CloudPhase::new(PhaseFunction::Tabulated { angles_deg, values })
}
