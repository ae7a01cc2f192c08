//! The camera of a beams scene: a pinhole with a vertical field of view.

use glam::DVec3;

use crate::beams::error::BeamError;
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

    /// For methods that sample planes facing this camera (Dobashi et al. 2000, 2002): the
    /// cosine of `ray` to the forward axis, `None` for a ray facing away; an error naming
    /// `method` when the ray does not start at the camera.
    pub fn forward_cosine(&self, method: &str, ray: &SceneRay) -> Result<Option<f64>, BeamError> {
        let tolerance = 1e-6 * self.position_m.length().max(1.0);
        if ray.origin_m.distance(self.position_m) > tolerance {
            return Err(BeamError::Ray(format!(
                "{method} renders from the scene camera at {}; this ray starts at {}",
                self.position_m, ray.origin_m
            )));
        }
        let cos_forward = ray.direction.dot(self.forward);
        Ok((cos_forward > 0.0).then_some(cos_forward))
    }
}
