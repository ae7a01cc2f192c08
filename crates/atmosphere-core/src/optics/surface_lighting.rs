//! How the models light a surface element: the ground sphere, and terrain on the GPU.
//!
//! A Lambertian element of albedo `a` at point `x` with unit normal `n`, seen along a ray
//! ending there with transmittance `T`, adds `T a / pi E(x, n)` to the ray's radiance,
//! where the irradiance is
//!     E(x, n) = E_sun T_sun(x) max(n . s, 0) + E_sky(x) (1 + n . up) / 2.
//! `T_sun(x)` is the sun's transmittance from `x` (zero when the planet hides the sun's
//! centre), read at the cosine `mu_s = up . s` of the local vertical; `E_sky(x)` the sky's
//! irradiance on a horizontal element at `x`, for the models that have it (Bruneton 2008
//! Eq. 15's `E[L]`, Hillaire's E_sky, Dobashi's ambient term). The factor `(1 + n . up)/2`
//! is the fraction of an isotropic sky a plane tilted away from the vertical sees (its
//! view factor); on the sphere, `n = up` and both factors are those of the ground terms of
//! the papers. Shadows cast by terrain are not modelled here.

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::models::error::ModelError;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};
use crate::optics::view_segment::ViewSegment;

/// A surface a view ray ends on.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceHit {
    /// Distance from the camera along the ray, m, > 0.
    pub distance_m: f64,
    /// Outward unit normal.
    pub normal: DVec3,
    /// Lambertian albedo at each of the model's wavelengths.
    pub albedo: Vec<f64>,
}

/// The radiance of `ray` ending on `hit`: the model's answer for the ray ended at the
/// surface's distance (`ViewRay::max_distance_m`), plus the surface's reflection
/// `T a / pi E(x, n)` at the point x where that segment ends: on the surface, or on the
/// ground or the top of the atmosphere where those come first (terrain drawn over the
/// sphere; a peak above the atmosphere), or on the surface itself, unattenuated, where it
/// lies before the atmosphere. The CPU twin of `add_surface` in `shaders/common/surface.wgsl`.
pub fn radiance_with_surface(
    model: &dyn SkyModel,
    atmosphere: &Atmosphere,
    ray: &ViewRay,
    hit: &SurfaceHit,
) -> Result<RayRadiance, ModelError> {
    let (mut answer, end) = path_to_surface(model, atmosphere, ray, hit)?;
    let irradiance = model.surface_irradiance(&SurfacePoint {
        point_m: end,
        normal: hit.normal,
        sun_direction: ray.sun_direction,
    })?;
    for (w, l) in answer.radiance.iter_mut().enumerate() {
        *l += answer.transmittance[w] * hit.albedo[w] / std::f64::consts::PI * irradiance[w];
    }
    Ok(answer)
}

/// The model's answer for `ray` ended at `hit`'s distance (`ViewRay::max_distance_m`),
/// and the point where the lit surface is taken: where that segment ends (on the surface,
/// or on the ground or the top of the atmosphere where those come first), or on the
/// surface itself where it lies before the atmosphere. An error for a hit that is not
/// ahead of the ray or whose albedo does not match the model's wavelengths.
pub fn path_to_surface(
    model: &dyn SkyModel,
    atmosphere: &Atmosphere,
    ray: &ViewRay,
    hit: &SurfaceHit,
) -> Result<(RayRadiance, DVec3), ModelError> {
    check_hit("surface", hit.distance_m, &hit.albedo, model)?;
    let ray = ViewRay {
        max_distance_m: Some(hit.distance_m),
        ..*ray
    };
    let answer = model.radiance(&ray)?;
    let end = match ViewSegment::new(atmosphere, &ray)? {
        Some(segment) => segment.end_point(),
        None => ray.origin_m + ray.direction.normalize() * hit.distance_m,
    };
    Ok((answer, end))
}

/// Adds to `radiance` the ground at a view ray's end `end_m`, lit as a surface element
/// facing up (the models' ground term): `T a / pi E(x, up)` per wavelength, with `T` the
/// ray's `transmittance` and `a` the ground's `albedo`.
pub fn add_ground_light(
    model: &dyn SkyModel,
    end_m: DVec3,
    sun_direction: DVec3,
    albedo: f64,
    transmittance: &[f64],
    radiance: &mut [f64],
) -> Result<(), ModelError> {
    let irradiance = model.surface_irradiance(&SurfacePoint::facing_up(end_m, sun_direction))?;
    for (w, l) in radiance.iter_mut().enumerate() {
        *l += transmittance[w] * albedo / std::f64::consts::PI * irradiance[w];
    }
    Ok(())
}

/// A surface element, checked, in the variables the models look up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceElement {
    /// Distance from the planet's centre, m, clamped to the atmosphere's shell: a point
    /// above the top (a peak drawn with a large exaggeration) is lit as at the top.
    pub r: f64,
    /// Cosine of the sun's zenith angle at the point.
    pub mu_s: f64,
    /// `max(n . s, 0)`: the cosine of the sun's incidence.
    pub sun_cosine: f64,
    /// `(1 + n . up) / 2`: the part of the sky the element sees.
    pub sky_view_factor: f64,
}

impl SurfaceElement {
    /// The element `surface` in `atmosphere`; an error names a non-finite or zero vector
    /// or a point below the ground. Points a rounding below the ground are lifted onto it.
    pub fn new(
        atmosphere: &Atmosphere,
        surface: &SurfacePoint,
    ) -> Result<SurfaceElement, ModelError> {
        SurfaceElement::new_within(atmosphere.bottom_radius_m, atmosphere.top_radius_m, surface)
    }

    /// As [`SurfaceElement::new`], for the shell between radii `bottom` and `top`.
    pub fn new_within(
        bottom: f64,
        top: f64,
        surface: &SurfacePoint,
    ) -> Result<SurfaceElement, ModelError> {
        let bad = |what: &str| ModelError::Ray(format!("surface element: {what}"));
        let normal = surface
            .normal
            .try_normalize()
            .ok_or_else(|| bad("the normal must be a finite non-zero vector"))?;
        let sun = surface
            .sun_direction
            .try_normalize()
            .ok_or_else(|| bad("the sun direction must be a finite non-zero vector"))?;
        let point_m = surface.point_m;
        if !point_m.is_finite() {
            return Err(bad("the point must be finite"));
        }
        let r = point_m.length();
        if r < bottom * (1.0 - 1e-9) {
            return Err(bad(&format!(
                "the point is {:.3} m below the ground",
                bottom - r
            )));
        }
        let up = point_m / r;
        Ok(SurfaceElement {
            r: r.clamp(bottom, top),
            mu_s: up.dot(sun).clamp(-1.0, 1.0),
            sun_cosine: normal.dot(sun).max(0.0),
            sky_view_factor: 0.5 * (1.0 + normal.dot(up).clamp(-1.0, 1.0)),
        })
    }

    /// `E_sun T_sun max(n . s, 0) + E_sky (1 + n . up) / 2` for one wavelength.
    pub fn irradiance(&self, solar_irradiance: f64, sun_transmittance: f64, sky: f64) -> f64 {
        solar_irradiance * sun_transmittance * self.sun_cosine + sky * self.sky_view_factor
    }

    /// [`SurfaceElement::irradiance`] at each wavelength `w` of `solar_irradiance`, lit by
    /// the sun alone (the single-scattering models: no sky light).
    pub fn sun_irradiances(
        &self,
        solar_irradiance: &[f64],
        sun_transmittance: impl Fn(usize) -> f64,
    ) -> Vec<f64> {
        (0..solar_irradiance.len())
            .map(|w| self.irradiance(solar_irradiance[w], sun_transmittance(w), 0.0))
            .collect()
    }
}

/// Nothing, or an error when a `what` (surface, sea) hit at `distance_m` is not ahead of
/// the ray or its `albedo` has not one value per wavelength of `model`.
pub fn check_hit(
    what: &str,
    distance_m: f64,
    albedo: &[f64],
    model: &dyn SkyModel,
) -> Result<(), ModelError> {
    if !(distance_m.is_finite() && distance_m > 0.0) {
        return Err(ModelError::Ray(format!(
            "{what} distance {distance_m} must be > 0"
        )));
    }
    if albedo.len() != model.wavelengths_nm().len() {
        return Err(ModelError::Ray(format!(
            "{} albedos for {} wavelengths",
            albedo.len(),
            model.wavelengths_nm().len()
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn earth() -> Atmosphere {
        Atmosphere::preset("earth").unwrap()
    }

    fn element(point_m: DVec3, normal: DVec3, sun_direction: DVec3) -> SurfacePoint {
        SurfacePoint {
            point_m,
            normal,
            sun_direction,
        }
    }

    #[test]
    fn a_level_element_sees_the_whole_sky_and_the_sun_at_its_zenith_cosine() {
        let a = earth();
        let point = DVec3::new(0.0, 0.0, a.bottom_radius_m + 1000.0);
        let sun = DVec3::new(0.6, 0.0, 0.8);
        let e = SurfaceElement::new(&a, &element(point, DVec3::Z, sun)).unwrap();
        assert_eq!(e.r, a.bottom_radius_m + 1000.0);
        assert!((e.mu_s - 0.8).abs() < 1e-15);
        assert!((e.sun_cosine - 0.8).abs() < 1e-15);
        assert_eq!(e.sky_view_factor, 1.0);
        assert!((e.irradiance(2.0, 0.5, 0.3) - (2.0 * 0.5 * 0.8 + 0.3)).abs() < 1e-15);
        // Above the atmosphere, lit as at its top.
        let high = SurfaceElement::new(&a, &element(point * 2.0, DVec3::Z, sun)).unwrap();
        assert_eq!(high.r, a.top_radius_m);
    }

    #[test]
    fn a_tilted_element_faces_the_sun_and_sees_part_of_the_sky() {
        let a = earth();
        let point = DVec3::new(0.0, 0.0, a.bottom_radius_m);
        // A 60 degree slope facing the sun, which is 30 degrees above the horizon.
        let normal = DVec3::new(60f64.to_radians().sin(), 0.0, 60f64.to_radians().cos());
        let sun = DVec3::new(60f64.to_radians().sin(), 0.0, 60f64.to_radians().cos());
        let e = SurfaceElement::new(&a, &element(point, normal, sun)).unwrap();
        assert!((e.sun_cosine - 1.0).abs() < 1e-12);
        assert!((e.mu_s - 0.5).abs() < 1e-12);
        assert!((e.sky_view_factor - 0.75).abs() < 1e-12);
        // Facing away from the sun: no direct light, whatever the sun's height.
        let away =
            SurfaceElement::new(&a, &element(point, -normal.reflect(DVec3::Z), sun)).unwrap();
        assert_eq!(away.sun_cosine, 0.0);
    }

    #[test]
    fn bad_elements_are_named() {
        let a = earth();
        let r = a.bottom_radius_m;
        let err = |p: DVec3, n: DVec3, s: DVec3| {
            SurfaceElement::new(&a, &element(p, n, s))
                .unwrap_err()
                .to_string()
        };
        let p = DVec3::new(0.0, 0.0, r);
        assert!(err(p, DVec3::ZERO, DVec3::Z).contains("normal"));
        assert!(err(p, DVec3::Z, DVec3::NAN).contains("sun direction"));
        assert!(err(DVec3::new(0.0, 0.0, f64::INFINITY), DVec3::Z, DVec3::Z).contains("point"));
        assert!(err(DVec3::new(0.0, 0.0, r - 10.0), DVec3::Z, DVec3::Z).contains("below"));
        // A rounding below the ground is on it.
        let e = SurfaceElement::new(
            &a,
            &element(DVec3::new(0.0, 0.0, r * (1.0 - 1e-12)), DVec3::Z, DVec3::Z),
        );
        assert_eq!(e.unwrap().r, r);
    }
}
