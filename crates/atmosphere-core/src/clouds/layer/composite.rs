//! The cloud layer composited with a sky model on the CPU: the specification of the GPU's
//! cloud pass. A view ray meets the layer on `[t0, t1]` (its first crossing,
//! [`super::shell::Shell::first_segment`]); the model answers the ray whole (`full`) and
//! ended at the cloud (`front`, the aerial perspective in front of it); the march answers
//! the cloud's radiance and transmittance; and, per wavelength,
//!     L = L_front + T_front L_cloud + T_cloud (L_full - L_front),   T = T_full T_cloud,
//! which is L_front + T_front (L_cloud + T_cloud L_behind) with the model's light
//! behind the cloud, T_front L_behind = L_full - L_front. Riley et al. 2004 section 5
//! composites the atmosphere in front of and behind the volume the same way.
//!
//! The cloud is lit where the ray enters it, by the model's own sun and sky: a surface
//! element facing the sun there has E(s) = E_sun T_sun + E_sky (1 + mu_s) / 2, one
//! perpendicular to the sun and tilted towards the zenith E(n) = E_sky (1 + n . up) / 2
//! (`optics/surface_lighting.rs`), which give E_sun T_sun and E_sky.
//!
//! The layer's sun light here is each sample's shadow march (`sun_light = march`); a
//! layer lit by the frame's sun map (`sun_light = map`) needs the map of a frame whose
//! camera stands at the ray's origin (`radiance_with_cloud_segment`), and is refused
//! without one.

use glam::DVec3;

use super::field::CloudLayer;
use super::march::{CloudLight, CloudSegment, MarchRay, march, march_in_sun_map};
use super::orders::ScatteringOrders;
use super::settings::SunLight;
use super::sun_map::CloudSunMap;
use crate::models::error::ModelError;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};

/// The radiance and transmittance of `ray` through the sky of `model` and the cloud
/// `layer`, with the layer's multiple-scattering tables `orders` at the model's
/// wavelengths.
pub fn radiance_with_clouds(
    model: &dyn SkyModel,
    layer: &CloudLayer,
    orders: &ScatteringOrders,
    ray: &ViewRay,
) -> Result<RayRadiance, ModelError> {
    radiance_with_cloud_segment(model, layer, orders, ray, None).map(|(answer, _)| answer)
}

/// [`radiance_with_clouds`], with the cloud's march (`None` where the ray misses the
/// layer) beside the answer; a layer lit by the sun map (`sun_light = map`) reads
/// `sun_map`, the map of a frame whose camera is at the ray's origin, and is refused
/// without one.
pub fn radiance_with_cloud_segment(
    model: &dyn SkyModel,
    layer: &CloudLayer,
    orders: &ScatteringOrders,
    ray: &ViewRay,
    sun_map: Option<&CloudSunMap>,
) -> Result<(RayRadiance, Option<CloudSegment>), ModelError> {
    let waves = model.wavelengths_nm().len();
    if orders.wavelengths() != waves {
        return Err(ModelError::Settings(format!(
            "cloud phase tables for {} wavelengths, the model answers {waves}",
            orders.wavelengths()
        )));
    }
    if layer.settings().sun_light == SunLight::Map && sun_map.is_none() {
        return Err(ModelError::Settings(
            "cloud sun_light = map needs the frame's sun map (march_in_sun_map); this \
             composite lights the layer by its shadow march (sun_light = march)"
                .into(),
        ));
    }
    let full = model.radiance(ray)?;
    let direction = ray.direction.normalize();
    let Some((t0, t1)) = layer.shell().first_segment(
        ray.origin_m,
        direction,
        ray.max_distance_m.unwrap_or(f64::INFINITY),
    ) else {
        return Ok((full, None));
    };
    let front = if t0 > 0.0 {
        model.radiance(&ViewRay {
            max_distance_m: Some(t0),
            ..*ray
        })?
    } else {
        RayRadiance::unattenuated(waves)
    };
    let entry = ray.origin_m + direction * t0;
    let light = light_at(model, entry, ray.sun_direction.normalize())?;
    let march_ray = MarchRay {
        origin: ray.origin_m,
        direction,
        t0,
        t1,
    };
    let cloud = match (layer.settings().sun_light, sun_map) {
        (SunLight::Map, Some(map)) => {
            march_in_sun_map(layer, &march_ray, &light, orders, layer.settings(), map)
        }
        _ => march(layer, &march_ray, &light, orders, layer.settings()),
    };
    Ok((composite(&full, &front, &cloud), Some(cloud)))
}

/// The module's composite of the model's answer for the whole ray, `full` (ended on a
/// surface, with its reflection, where the ray has one), for the ray ended where it
/// enters the cloud, `front`, and the cloud's march `cloud`, per wavelength.
pub fn composite(full: &RayRadiance, front: &RayRadiance, cloud: &CloudSegment) -> RayRadiance {
    let mut answer = full.clone();
    for w in 0..answer.radiance.len() {
        let behind = (full.radiance[w] - front.radiance[w]).max(0.0);
        answer.radiance[w] = front.radiance[w]
            + front.transmittance[w] * cloud.radiance[w]
            + cloud.transmittance[w] * behind;
        answer.transmittance[w] = full.transmittance[w] * cloud.transmittance[w];
    }
    answer
}

/// The model's sun (through its transmittance) and sky irradiance at `point`.
pub fn light_at(
    model: &dyn SkyModel,
    point: DVec3,
    sun_direction: DVec3,
) -> Result<CloudLight, ModelError> {
    let up = point.normalize();
    let mu_s = up.dot(sun_direction);
    let across = up - sun_direction * mu_s;
    // Perpendicular to the sun, as near the zenith as it can be; any horizontal
    // direction when the sun stands at the zenith or nadir.
    let side = if across.length() > 1e-9 {
        across.normalize()
    } else {
        up.any_orthonormal_vector()
    };
    let irradiance = |normal: DVec3| {
        model.surface_irradiance(&SurfacePoint {
            point_m: point,
            normal,
            sun_direction,
        })
    };
    let facing_sun = irradiance(sun_direction)?;
    let sideways = irradiance(side)?;
    let view_factor = (1.0 + side.dot(up)) / 2.0;
    let sky_irradiance: Vec<f64> = sideways.iter().map(|e| e / view_factor).collect();
    let sun_irradiance = facing_sun
        .iter()
        .zip(&sky_irradiance)
        .map(|(e, sky)| (e - sky * (1.0 + mu_s) / 2.0).max(0.0))
        .collect();
    Ok(CloudLight {
        sun_direction,
        sun_irradiance,
        sky_irradiance,
        up,
    })
}
