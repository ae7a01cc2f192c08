//! What a cloud medium answers to be path traced: the layer, the spheres and the voxel
//! cloud implement it. Positions are in metres in the medium's own frame.

use glam::DVec3;

use super::phase::CloudPhase;

pub trait CloudMedium {
    /// Extinction coefficient at `position`, m^-1 (0 outside the cloud).
    fn extinction(&self, position: DVec3) -> f64;

    /// The extinction a march's shadow rays towards the sun read, m^-1: the same field
    /// unless the medium offers a cheaper, smoother one for its light.
    fn light_extinction(&self, position: DVec3) -> f64 {
        self.extinction(position)
    }

    /// Single-scattering albedo at `position`, in [0, 1].
    fn single_scattering_albedo(&self, position: DVec3) -> f64;

    /// The droplets' phase function and its sampler.
    fn phase(&self) -> &CloudPhase;

    /// An upper bound of [`CloudMedium::extinction`] over the whole medium, m^-1: delta
    /// tracking's free paths are drawn with it.
    fn majorant(&self) -> f64;

    /// The distance along `direction` (unit) from `position`, inside the medium, to its
    /// boundary, m.
    fn distance_to_boundary(&self, position: DVec3, direction: DVec3) -> f64;
}
