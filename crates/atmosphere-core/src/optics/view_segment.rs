//! The part of a view ray inside the atmosphere: every model starts from it. A camera in
//! space is moved to where its ray enters the atmosphere; the segment ends on the ground,
//! on an object at the ray's distance, or where it leaves into space.

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::models::error::ModelError;
use crate::models::sky_model::ViewRay;
use crate::optics::geometry::{distance_to_entry, distance_to_exit, ray_hits_ground};

/// How a view segment ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SegmentEnd {
    Ground,
    Object,
    Space,
}

/// A view ray clipped to the atmosphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewSegment {
    /// Planet-centred start, m: the camera, or where its ray enters the atmosphere.
    pub start: DVec3,
    /// Unit direction of the ray.
    pub direction: DVec3,
    /// Unit direction towards the sun.
    pub sun_direction: DVec3,
    /// Distance from the camera to `start`, m.
    pub t_enter: f64,
    /// Radius and direction cosine at `start`.
    pub r: f64,
    pub mu: f64,
    /// Length of the segment, m.
    pub length: f64,
    pub end: SegmentEnd,
    /// True when the ray's object ends it before the ground or the top would: the
    /// segment is shorter than the ray's way through the atmosphere. An object beyond the
    /// ground ends the ray there (`end` is `Object`) without cutting it.
    pub cut: bool,
}

impl ViewSegment {
    /// The segment of `ray` inside `atmosphere`; `None` when the ray never meets the
    /// atmosphere or its object lies before it. Errors for non-finite input or a camera
    /// below the ground.
    pub fn new(atmosphere: &Atmosphere, ray: &ViewRay) -> Result<Option<ViewSegment>, ModelError> {
        ViewSegment::new_within(atmosphere.bottom_radius_m, atmosphere.top_radius_m, ray)
    }

    /// As [`ViewSegment::new`], for the shell between radii `bottom` and `top`.
    pub fn new_within(
        bottom: f64,
        top: f64,
        ray: &ViewRay,
    ) -> Result<Option<ViewSegment>, ModelError> {
        let direction = ray.direction.normalize();
        let sun_direction = ray.sun_direction.normalize();
        if !(direction.is_finite() && sun_direction.is_finite() && ray.origin_m.is_finite()) {
            return Err(ModelError::Ray(
                "non-finite or zero position or direction".into(),
            ));
        }
        if let Some(d) = ray.max_distance_m
            && (d.is_nan() || d <= 0.0)
        {
            return Err(ModelError::Ray(format!("distance {d} must be > 0")));
        }
        let r_camera = ray.origin_m.length();
        if r_camera < bottom * (1.0 - 1e-12) {
            return Err(ModelError::Ray(format!(
                "camera {} m below the ground",
                bottom - r_camera
            )));
        }
        let mu_camera = (ray.origin_m.dot(direction) / r_camera).clamp(-1.0, 1.0);
        let t_enter = if r_camera > top {
            match distance_to_entry(r_camera, mu_camera, top) {
                Some(t) => t,
                None => return Ok(None),
            }
        } else {
            0.0
        };
        let start = ray.origin_m + direction * t_enter;
        let r = start.length().clamp(bottom, top);
        let mu = (start.dot(direction) / start.length()).clamp(-1.0, 1.0);
        let (mut length, mut end) = if ray_hits_ground(r, mu, bottom) {
            (
                distance_to_entry(r, mu, bottom).unwrap_or(0.0),
                SegmentEnd::Ground,
            )
        } else {
            (distance_to_exit(r, mu, top), SegmentEnd::Space)
        };
        // An object beyond the ground ends the ray on the ground, as an object: terrain
        // is drawn over the sphere, and a caller lights the end with its own surface.
        let mut cut = false;
        if let Some(d) = ray.max_distance_m {
            let remaining = d - t_enter;
            if remaining <= 0.0 {
                return Ok(None);
            }
            cut = remaining < length;
            if cut || end == SegmentEnd::Ground {
                length = remaining.min(length);
                end = SegmentEnd::Object;
            }
        }
        Ok(Some(ViewSegment {
            start,
            direction,
            sun_direction,
            t_enter,
            r,
            mu,
            length,
            end,
            cut,
        }))
    }

    /// The point where the segment ends, m.
    pub fn end_point(&self) -> DVec3 {
        self.start + self.direction * self.length
    }
}
