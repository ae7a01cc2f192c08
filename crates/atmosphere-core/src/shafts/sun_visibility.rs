//! The question every shadow representation answers.

use glam::DVec3;

/// How much of the sun a point of the air sees past the terrain.
pub trait SunVisibility {
    /// Fraction in [0, 1] of the sun seen from `point_m` (planet-centred, m) towards the
    /// unit direction `sun`, the terrain alone considered.
    fn sun_visible(&self, point_m: DVec3, sun: DVec3) -> f64;
}
