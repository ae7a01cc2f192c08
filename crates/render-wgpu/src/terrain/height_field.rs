//! A planet's surface height as a function of direction.

use std::sync::Arc;

use glam::DVec3;

/// Height of the surface above the reference sphere (metres; negative below it) in a
/// planet-fixed direction, with what the level of detail and the normals need to know.
pub trait HeightField {
    /// Height in metres at the direction `direction` (unit length).
    fn height_m(&self, direction: DVec3) -> f64;

    /// A bound on `|height_m|` anywhere, metres: chunks' bounding spheres grow by it.
    fn max_abs_height_m(&self) -> f64;

    /// The angle between neighbouring samples of the field's finest detail, radians: the
    /// level of detail splits chunks until their cells are this fine
    /// (`LodSettings::finest_level`).
    fn sample_spacing_rad(&self) -> f64;
}

/// A shared height field, as the chunk builder's threads hold it.
impl<H: HeightField + ?Sized> HeightField for Arc<H> {
    fn height_m(&self, direction: DVec3) -> f64 {
        (**self).height_m(direction)
    }

    fn max_abs_height_m(&self) -> f64 {
        (**self).max_abs_height_m()
    }

    fn sample_spacing_rad(&self) -> f64 {
        (**self).sample_spacing_rad()
    }
}
