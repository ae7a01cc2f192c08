//! The camera of a beams scene: a pinhole with a vertical field of view.

use glam::DVec3;

use crate::beams::ray::SceneRay;

/// A pinhole camera, m; `forward`, `right` and `up` are orthonormal.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub position_m: DVec3,
    pub forward: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    pub vertical_fov_deg: f64,
    pub width_px: u32,
    pub height_px: u32,
}

impl Camera {
    /// The ray through the point (x, y) of the image, in pixels from its top left corner
    /// (pixel centres at half-integers).
    pub fn ray(&self, x_px: f64, y_px: f64) -> SceneRay {
        let tan_half = (0.5 * self.vertical_fov_deg.to_radians()).tan();
        let aspect = f64::from(self.width_px) / f64::from(self.height_px);
        let sx = (2.0 * x_px / f64::from(self.width_px) - 1.0) * tan_half * aspect;
        let sy = (1.0 - 2.0 * y_px / f64::from(self.height_px)) * tan_half;
        SceneRay {
            origin_m: self.position_m,
            direction: (self.forward + self.right * sx + self.up * sy).normalize(),
            max_distance_m: None,
        }
    }
}
