//! The slices of half-angle slicing (Kniss, Premoze, Hansen and Ebert 2002, as Riley et
//! al. 2004 section 4.2 and 5 use it): planes perpendicular to the half vector between
//! the direction the light travels, l = -sun, and the view direction v, so that one pass
//! over the slices serves both the light and the eye.
//!
//! When the viewer faces away from the sun (v . l >= 0) the half vector is
//! h = normalize(v + l) and the slices, taken in increasing h . x, run front to back for
//! the eye; when the viewer faces the sun (v . l < 0) it is h = normalize(l - v), the
//! half vector of l and the negated view, and the same order runs back to front for the
//! eye. In both cases l . h >= cos 45 degrees > 0: the light crosses the slices in order.
//! The slices are `slices` planes at the middles of equal intervals of h . x over the
//! volume's box; between two slices the light travels spacing / (l . h) and a pixel's ray
//! spacing / |v . h|.

use glam::DVec3;

use super::camera::VolumeCamera;
use crate::clouds::error::CloudError;

/// The smallest |v . h| of a pixel's ray accepted: a ray nearly along the slices would
/// cross them too far apart.
pub const MIN_VIEW_COSINE: f64 = 0.05;

/// The slices through a volume for one view and sun.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HalfAngle {
    /// The slices' unit normal h; slices are taken in increasing h . x.
    pub half: DVec3,
    /// The unit direction the light travels, -sun.
    pub light: DVec3,
    /// Whether the eye composites front to back (facing away from the sun) or back to
    /// front (facing it).
    pub front_to_back: bool,
    /// h . x of the first interval's start, m.
    pub start_m: f64,
    /// Distance between slices along h, m.
    pub spacing_m: f64,
    pub slices: u32,
}

/// The half vector of the view direction `view` and the sun direction `sun` (both unit),
/// and whether the eye composites front to back (the module's rule).
pub fn half_vector(view: DVec3, sun: DVec3) -> (DVec3, bool) {
    let light = -sun;
    if view.dot(light) >= 0.0 {
        ((view + light).normalize(), true)
    } else {
        ((light - view).normalize(), false)
    }
}

impl HalfAngle {
    /// `slices` slices through the box of `corners` for `camera`'s forward axis and the
    /// sun direction `sun`. Refuses a camera inside the box and one whose image's
    /// corners see the slices at a cosine below [`MIN_VIEW_COSINE`] or from the wrong
    /// side (a view too wide for one order of the slices).
    pub fn new(
        camera: &VolumeCamera,
        sun: DVec3,
        corners: &[DVec3; 8],
        slices: u32,
    ) -> Result<HalfAngle, CloudError> {
        let (half, front_to_back) = half_vector(camera.forward, sun);
        let lo = corners
            .iter()
            .map(|c| c.dot(half))
            .fold(f64::INFINITY, f64::min);
        let hi = corners
            .iter()
            .map(|c| c.dot(half))
            .fold(f64::NEG_INFINITY, f64::max);
        let (min, max) = corners
            .iter()
            .fold((DVec3::MAX, DVec3::MIN), |(a, b), c| (a.min(*c), b.max(*c)));
        let p = camera.position_m;
        if p.cmpge(min).all() && p.cmple(max).all() {
            return Err(CloudError(format!(
                "half-angle slicing needs the camera outside the volume; camera at {p}, volume from {min} to {max}"
            )));
        }
        let sign = if front_to_back { 1.0 } else { -1.0 };
        for d in camera.corner_directions() {
            let cosine = sign * d.dot(half);
            if cosine < MIN_VIEW_COSINE {
                return Err(CloudError(format!(
                    "half-angle slicing: an image corner's ray meets the slices at cosine {cosine:.3}, \
                     below {MIN_VIEW_COSINE}; narrow the camera's vertical_fov_deg ({}) or turn it",
                    camera.vertical_fov_deg
                )));
            }
        }
        Ok(HalfAngle {
            half,
            light: -sun,
            front_to_back,
            start_m: lo,
            spacing_m: (hi - lo) / f64::from(slices),
            slices,
        })
    }

    /// h . x of slice `k` (0 first).
    pub fn offset_m(&self, k: u32) -> f64 {
        self.start_m + (f64::from(k) + 0.5) * self.spacing_m
    }

    /// The light's path between two slices, m.
    pub fn light_step_m(&self) -> f64 {
        self.spacing_m / self.light.dot(self.half)
    }

    /// Where the ray from `origin` along the unit `direction` meets slice `k` and the
    /// length of its path between two slices, `None` behind the origin.
    pub fn view_hit(&self, origin: DVec3, direction: DVec3, k: u32) -> Option<(DVec3, f64)> {
        let cosine = direction.dot(self.half);
        let t = (self.offset_m(k) - origin.dot(self.half)) / cosine;
        (t > 0.0).then(|| (origin + direction * t, self.spacing_m / cosine.abs()))
    }
}
