//! A planet's surface height as a function of direction.

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
