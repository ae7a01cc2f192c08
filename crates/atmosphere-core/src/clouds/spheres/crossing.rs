//! What one crossing of a cloud sphere's shell is and what it sends towards the camera:
//! shared by the octaves' light (`field.rs`) and the slab methods' (`slab_light.rs`).

use glam::DVec3;

/// The light one crossing sends towards its start, per wavelength: `radiance` seen
/// through the real medium in front of it, `scaled_radiance` (the slab methods' diffuse
/// light and the broad part of the sun's, `slab_light.rs`; zero for the octaves) through
/// the delta-scaled one, and the crossing's transmittance through either.
#[derive(Clone, Debug, PartialEq)]
pub struct SphereCrossing {
    pub radiance: Vec<f64>,
    pub scaled_radiance: Vec<f64>,
    pub transmittance: Vec<f64>,
    pub scaled_transmittance: Vec<f64>,
}

/// A crossing of shell `shell` from `start` to `end` along the unit `direction`, of mean
/// extinction `extinction` (m^-1, positive).
#[derive(Clone, Copy, Debug)]
pub struct ShellSegment {
    pub shell: usize,
    pub start: DVec3,
    pub end: DVec3,
    pub direction: DVec3,
    pub extinction: f64,
}

impl SphereCrossing {
    /// A crossing of no cloud.
    pub fn clear(waves: usize) -> SphereCrossing {
        SphereCrossing {
            radiance: vec![0.0; waves],
            scaled_radiance: vec![0.0; waves],
            transmittance: vec![1.0; waves],
            scaled_transmittance: vec![1.0; waves],
        }
    }
}
