//! A view ray in a beams scene.

use glam::DVec3;

use crate::beams::error::BeamError;

/// A ray from `origin_m` along the unit vector `direction`, ending at `max_distance_m`
/// when given (an object), else at the first occluder or where the medium has
/// extinguished its light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneRay {
    pub origin_m: DVec3,
    pub direction: DVec3,
    pub max_distance_m: Option<f64>,
}

impl SceneRay {
    /// The ray, its direction normalised; an error names a non-finite origin, a zero
    /// direction or a distance that is not a finite number >= 0.
    pub fn new(
        origin_m: DVec3,
        direction: DVec3,
        max_distance_m: Option<f64>,
    ) -> Result<SceneRay, BeamError> {
        if !origin_m.is_finite() {
            return Err(BeamError::Ray(format!("origin {origin_m} is not finite")));
        }
        let Some(direction) = direction.try_normalize() else {
            return Err(BeamError::Ray(format!(
                "direction {direction} has no length or is not finite"
            )));
        };
        if let Some(d) = max_distance_m.filter(|d| !(d.is_finite() && *d >= 0.0)) {
            return Err(BeamError::Ray(format!(
                "distance_m {d} must be a finite number >= 0"
            )));
        }
        Ok(SceneRay {
            origin_m,
            direction,
            max_distance_m,
        })
    }

    /// The point at distance `t_m` along the ray.
    pub fn at(&self, t_m: f64) -> DVec3 {
        self.origin_m + self.direction * t_m
    }
}
