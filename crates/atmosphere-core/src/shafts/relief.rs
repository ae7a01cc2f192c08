//! The drawn terrain as the shadow code sees it: an elevation per direction.

use glam::DVec3;

/// A relief on the reference sphere: render-wgpu's terrain surface (with its vertical
/// exaggeration and sea surface) implements it, and so do the tests' synthetic ridges.
pub trait Relief {
    /// Drawn elevation above the reference sphere, m, in a unit planet-fixed direction.
    fn elevation_m(&self, direction: DVec3) -> f64;

    /// A bound on the elevation anywhere, m (no point of the relief is higher).
    fn elevation_bound_m(&self) -> f64;
}
