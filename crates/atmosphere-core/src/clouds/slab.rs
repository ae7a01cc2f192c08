//! A homogeneous plane-parallel layer: z from 0 (its base) to its thickness (its top),
//! unbounded in x and y.

use glam::DVec3;

use super::error::{CloudError, check_range};
use super::medium::CloudMedium;
use super::phase::CloudPhase;

/// The thickest layer accepted, m.
pub const MAX_THICKNESS_M: f64 = 1e5;
/// The largest extinction coefficient accepted, m^-1.
pub const MAX_EXTINCTION_PER_M: f64 = 1.0;

#[derive(Clone, Debug)]
pub struct Slab {
    thickness_m: f64,
    extinction_per_m: f64,
    albedo: f64,
    phase: CloudPhase,
}

impl Slab {
    /// A layer of `thickness_m` in (0, 1e5] m, extinction in [0, 1] m^-1 and
    /// single-scattering albedo in [0, 1].
    pub fn new(
        thickness_m: f64,
        extinction_per_m: f64,
        albedo: f64,
        phase: CloudPhase,
    ) -> Result<Slab, CloudError> {
        check_range("slab thickness_m", thickness_m, 0.0, MAX_THICKNESS_M)?;
        if thickness_m == 0.0 {
            return Err(CloudError("slab thickness_m = 0 must be positive".into()));
        }
        check_range(
            "slab extinction_per_m",
            extinction_per_m,
            0.0,
            MAX_EXTINCTION_PER_M,
        )?;
        check_range("slab albedo", albedo, 0.0, 1.0)?;
        Ok(Slab {
            thickness_m,
            extinction_per_m,
            albedo,
            phase,
        })
    }

    pub fn thickness_m(&self) -> f64 {
        self.thickness_m
    }

    /// Vertical optical depth.
    pub fn optical_depth(&self) -> f64 {
        self.thickness_m * self.extinction_per_m
    }
}

impl CloudMedium for Slab {
    fn extinction(&self, position: DVec3) -> f64 {
        if (0.0..=self.thickness_m).contains(&position.z) {
            self.extinction_per_m
        } else {
            0.0
        }
    }

    fn single_scattering_albedo(&self, _position: DVec3) -> f64 {
        self.albedo
    }

    fn phase(&self) -> &CloudPhase {
        &self.phase
    }

    fn majorant(&self) -> f64 {
        self.extinction_per_m
    }

    fn distance_to_boundary(&self, position: DVec3, direction: DVec3) -> f64 {
        if direction.z > 0.0 {
            (self.thickness_m - position.z).max(0.0) / direction.z
        } else if direction.z < 0.0 {
            position.z.max(0.0) / -direction.z
        } else {
            f64::INFINITY
        }
    }
}
