//! A surface in the cloud layer's shadow: `surface_lighting::radiance_with_surface` with
//! the sun's part of the model's irradiance multiplied by the sun's transmittance through
//! the cloud at the surface point, read from the frame's sun map (`sun_map.rs`, Dobashi
//! et al. 2002 section 5.4's attenuation textures):
//!
//!     E(x, n) = E_sun T_sun(x) T_cloud(x) max(n . s, 0) + E_sky(x) (1 + n . up) / 2.
//!
//! The CPU twin of `element_irradiance` in `shaders/common/surface.wgsl`. The model gives
//! E(x, n) whole; its sky part follows from an element at x perpendicular to the sun,
//! tilted towards the zenith (n' . s = 0), which receives only the sky:
//! E_sky(x) (1 + n . up) / 2 = E(x, n') (1 + n . up) / (1 + n' . up).

use glam::DVec3;

use super::sun_map::CloudSunMap;
use crate::atmosphere::Atmosphere;
use crate::models::error::ModelError;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};
use crate::optics::surface_lighting::{SurfaceHit, path_to_surface};

/// The radiance of `ray` ending on `hit`, its sun shaded by the cloud of `map` (see the
/// module documentation); without cloud the answer of `radiance_with_surface`.
pub fn radiance_with_shadowed_surface(
    model: &dyn SkyModel,
    atmosphere: &Atmosphere,
    ray: &ViewRay,
    hit: &SurfaceHit,
    map: &CloudSunMap,
) -> Result<RayRadiance, ModelError> {
    let (mut answer, end) = path_to_surface(model, atmosphere, ray, hit)?;
    let sun = ray.sun_direction.normalize();
    let element = |normal: DVec3| {
        model.surface_irradiance(&SurfacePoint {
            point_m: end,
            normal,
            sun_direction: sun,
        })
    };
    let whole = element(hit.normal)?;
    let up = end.normalize();
    let across = (up - up.dot(sun) * sun)
        .try_normalize()
        .unwrap_or_else(|| sun.any_orthonormal_vector());
    let sky_only = element(across)?;
    let view_factor =
        (1.0 + hit.normal.normalize().dot(up).clamp(-1.0, 1.0)) / (1.0 + across.dot(up));
    let cloud = map.transmittance(end);
    for (w, l) in answer.radiance.iter_mut().enumerate() {
        let sky = sky_only[w] * view_factor;
        let irradiance = sky + cloud * (whole[w] - sky);
        *l += answer.transmittance[w] * hit.albedo[w] / std::f64::consts::PI * irradiance;
    }
    Ok(answer)
}
