//! The sea as a specular interface: what a view ray ending on water adds to its radiance.
//!
//! A view ray with unit direction `d` and transmittance `T` ends on the sea at point `x`
//! with outward unit normal `n`; `v = -d` looks back at the camera, `m = d - 2 (d . n) n`
//! is the mirror direction and `s` the sun's direction. The water adds
//!     T [ (1 - F(v . n)) a / pi E(x, n) + F(v . n) L_sky(x, m) + E_sun T_sun(x) G ],
//! - `F` the Fresnel reflectance of unpolarised light from air into water of refractive
//!   index 1.333: the exact Fresnel formulae (Born and Wolf 1999, sections 1.5.2-1.5.3),
//!   averaged over both polarisations;
//! - `a / pi E(x, n)` the water body's Lambertian light under the surface, `a` the water's
//!   albedo and `E` the model's irradiance (`optics::surface_lighting`), transmitted
//!   through the surface with `1 - F`;
//! - `L_sky(x, m)` the same model's radiance of the ray from `x` along `m` (a mirror
//!   turned down below the local horizon by a tilted normal is laid on the horizon), the
//!   sky's reflection on a calm sea;
//! - the sun's glint, `E_sun T_sun(x)` the sun's irradiance transmitted to `x` (from the
//!   model's irradiance: see [`transmitted_sun`]) times the glitter factor of Cox and
//!   Munk 1954 (the radiance of the sun's glitter from the slopes' distribution) with
//!   the facets' masking and shadowing,
//!   `G = F(v . h) p(tan beta) G1(v) G1(s) / (4 (n . v) cos^4 beta)`, with `h = (v + s) / |v + s|` the facet normal that mirrors the sun into the eye,
//!   `beta` its tilt from `n` and `p` the isotropic Gaussian distribution of the
//!   surface's slopes, `p = exp(-tan^2 beta / sigma^2) / (pi sigma^2)`, whose mean square
//!   slope grows with the wind speed `W` 12.5 m above the sea (Cox and Munk 1954's fit
//!   for a clean sea: `sigma^2 = 0.003 + 5.12e-3 W`, measured from 0.7 to 13.6 m/s).
//!   `p / cos^4 beta` is Beckmann's microfacet distribution with `alpha^2 = sigma^2`, and
//!   `G1` Smith's masking for it in the rational form of Walter et al. 2007 (section 5.1,
//!   Eq. 27), without which a sea seen at grazing angles would reflect without bound.
//!
//! The sun is taken as a point in the glint (its 0.27 degree radius is small against the
//! spread of the slopes, at least 3 degrees). The sky's light reflected by tilted facets
//! is not modelled (the sky's reflection is the calm sea's mirror). CPU twin of
//! `shaders/common/sea_surface.wgsl`.

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::models::error::ModelError;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};
use crate::optics::surface_lighting::check_hit;
use crate::optics::view_segment::ViewSegment;

/// Refractive index of sea water in the visible (Hale and Querry 1973 give 1.331 to
/// 1.340 for pure water between 680 and 440 nm; salt adds about 0.006).
pub const WATER_REFRACTIVE_INDEX: f64 = 1.333;

/// The wind speeds the sea accepts, m/s, 12.5 m above the sea: Cox and Munk 1954's fit
/// holds over the calm to strong breezes they measured (0.7 to 13.6 m/s) and is
/// extrapolated to a gale's 20 m/s.
pub const WIND_RANGE_M_S: std::ops::RangeInclusive<f64> = 0.0..=20.0;

/// The default wind, m/s: a gentle to moderate breeze.
pub const DEFAULT_WIND_M_S: f64 = 5.0;

/// Checks a wind speed: an error names `wind_m_s` and its value outside
/// [`WIND_RANGE_M_S`].
pub fn check_wind(wind_m_s: f64) -> Result<(), String> {
    if WIND_RANGE_M_S.contains(&wind_m_s) {
        Ok(())
    } else {
        Err(format!(
            "wind_m_s {wind_m_s} is outside [{}, {}] m/s",
            WIND_RANGE_M_S.start(),
            WIND_RANGE_M_S.end()
        ))
    }
}

/// The mean square slope of the sea's surface for a wind speed `wind_m_s` in
/// [`WIND_RANGE_M_S`] (Cox and Munk 1954's clean-sea fit, both directions together).
pub fn slope_variance(wind_m_s: f64) -> f64 {
    0.003 + 5.12e-3 * wind_m_s
}

/// The Fresnel reflectance of unpolarised light meeting water
/// ([`WATER_REFRACTIVE_INDEX`]) from air at incidence cosine `cos_incidence` (clamped
/// to [0, 1]): the mean of the squared amplitude ratios r_s and r_p of the Fresnel
/// formulae (Born and Wolf 1999, section 1.5.2).
pub fn fresnel_reflectance(cos_incidence: f64) -> f64 {
    let n = WATER_REFRACTIVE_INDEX;
    let c = cos_incidence.clamp(0.0, 1.0);
    let cos_t = (1.0 - (1.0 - c * c) / (n * n)).max(0.0).sqrt();
    let r_s = (c - n * cos_t) / (c + n * cos_t);
    let r_p = (n * c - cos_t) / (n * c + cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

/// The probability density of the surface's slopes `(z_x, z_y)` at a facet tilted by
/// `beta` from the mean surface, given `cos_tilt = cos beta`: Cox and Munk 1954's
/// Gaussian, isotropic (the same variance `slope_variance / 2` along and across the wind).
pub fn slope_density(cos_tilt: f64, slope_variance: f64) -> f64 {
    let c2 = (cos_tilt * cos_tilt).max(1e-12);
    let tan2 = (1.0 - c2) / c2;
    (-tan2 / slope_variance).exp() / (std::f64::consts::PI * slope_variance)
}

/// Smith's masking of a surface of mean square slope `slope_variance` seen at cosine
/// `cos_view` from its mean normal: the share of its facets a ray meets before any other
/// facet hides them, for Beckmann's distribution (Walter et al. 2007, Eq. 27).
pub fn smith_masking(cos_view: f64, slope_variance: f64) -> f64 {
    if cos_view >= 1.0 {
        return 1.0;
    }
    let a = cos_view / (slope_variance.sqrt() * (1.0 - cos_view * cos_view).sqrt());
    if a >= 1.6 {
        return 1.0;
    }
    (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a)
}

/// The glitter factor `G` of the module's equation: the sea's radiance towards unit `eye`
/// (from the surface towards the camera) per unit of the sun's irradiance arriving
/// from unit `sun`, on a sea with outward unit `normal` and mean square slope
/// `slope_variance`; 0 where the eye or the sun is below the surface.
pub fn glint_factor(eye: DVec3, sun: DVec3, normal: DVec3, slope_variance: f64) -> f64 {
    let cos_v = eye.dot(normal);
    if cos_v <= 0.0 || sun.dot(normal) <= 0.0 {
        return 0.0;
    }
    let Some(h) = (eye + sun).try_normalize() else {
        return 0.0;
    };
    let cos_beta = h.dot(normal);
    let masking =
        smith_masking(cos_v, slope_variance) * smith_masking(sun.dot(normal), slope_variance);
    fresnel_reflectance(eye.dot(h)) * slope_density(cos_beta, slope_variance) * masking
        / (4.0 * cos_v * cos_beta.powi(4))
}

/// The mirror of unit `direction` in the surface with unit `normal` at `point`, laid on
/// the local horizon where a tilted normal would turn it below.
pub fn mirror_direction(point: DVec3, direction: DVec3, normal: DVec3) -> DVec3 {
    let m = direction - 2.0 * direction.dot(normal) * normal;
    let up = point.normalize();
    let below = m.dot(up).min(0.0);
    (m - below * up).normalize()
}

/// The sun's irradiance transmitted to `point` (W m^-2 nm^-1 per wavelength), separated
/// from the model's irradiance `E(x, n) = E_sun T_sun max(n . s, 0) + E_sky (1 + n . up)/2`
/// on two elements: one facing the sun (`n = s`) and one standing on the horizon
/// across the sun (`n . s = 0`, `n . up = 0`), so that
/// `E_sun T_sun = E(x, s) - (1 + up . s) E(x, n_across)`.
pub fn transmitted_sun(
    model: &dyn SkyModel,
    point: DVec3,
    sun: DVec3,
) -> Result<Vec<f64>, ModelError> {
    let up = point.normalize();
    let across = up
        .cross(sun)
        .try_normalize()
        .unwrap_or_else(|| up.any_orthonormal_vector());
    let element = |normal| SurfacePoint {
        point_m: point,
        normal,
        sun_direction: sun,
    };
    let facing = model.surface_irradiance(&element(sun))?;
    let standing = model.surface_irradiance(&element(across))?;
    let mu_s = up.dot(sun).clamp(-1.0, 1.0);
    Ok(facing
        .iter()
        .zip(&standing)
        .map(|(f, s)| (f - (1.0 + mu_s) * s).max(0.0))
        .collect())
}

/// A view ray's end on the sea.
#[derive(Clone, Debug, PartialEq)]
pub struct SeaHit {
    /// Distance from the camera along the ray, m, > 0.
    pub distance_m: f64,
    /// Outward unit normal of the mean surface.
    pub normal: DVec3,
    /// The water body's albedo at each of the model's wavelengths.
    pub body_albedo: Vec<f64>,
    /// Mean square slope of the surface ([`slope_variance`]).
    pub slope_variance: f64,
}

/// The radiance of `ray` ending on the sea `hit`: the model's answer for the ray ended at
/// the sea's distance, plus the water's light of the module's equation at the point
/// where that segment ends (as `surface_lighting::radiance_with_surface` finds it). The
/// CPU twin of `add_sea` in `shaders/common/sea_surface.wgsl`.
pub fn radiance_with_sea(
    model: &dyn SkyModel,
    atmosphere: &Atmosphere,
    ray: &ViewRay,
    hit: &SeaHit,
) -> Result<RayRadiance, ModelError> {
    check_hit("sea", hit.distance_m, &hit.body_albedo, model)?;
    let normal = hit.normal.try_normalize().ok_or_else(|| {
        ModelError::Ray("the sea's normal must be a finite non-zero vector".into())
    })?;
    let direction = ray.direction.normalize();
    let sun = ray.sun_direction.normalize();
    let ray = ViewRay {
        max_distance_m: Some(hit.distance_m),
        ..*ray
    };
    let mut answer = model.radiance(&ray)?;
    let end = match ViewSegment::new(atmosphere, &ray)? {
        Some(segment) => segment.end_point(),
        None => ray.origin_m + direction * hit.distance_m,
    };
    // The sea lies on the ground: a point a rounding below it is lifted onto it.
    let point = end * (atmosphere.bottom_radius_m / end.length()).max(1.0);
    let body = model.surface_irradiance(&SurfacePoint {
        point_m: point,
        normal,
        sun_direction: sun,
    })?;
    let mirror = mirror_direction(point, direction, normal);
    let sky = model.radiance(&ViewRay {
        origin_m: point,
        direction: mirror,
        sun_direction: sun,
        max_distance_m: None,
    })?;
    let sun_light = transmitted_sun(model, point, sun)?;
    let f_view = fresnel_reflectance(-direction.dot(normal));
    let glint = glint_factor(-direction, sun, normal, hit.slope_variance);
    for (w, l) in answer.radiance.iter_mut().enumerate() {
        let water = (1.0 - f_view) * hit.body_albedo[w] / std::f64::consts::PI * body[w]
            + f_view * sky.radiance[w]
            + glint * sun_light[w];
        *l += answer.transmittance[w] * water;
    }
    Ok(answer)
}
