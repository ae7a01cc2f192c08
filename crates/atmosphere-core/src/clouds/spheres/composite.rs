//! The cloud spheres composited with a sky model on the CPU: the specification. Dobashi,
//! Yamamoto and Nishita 2002, section 5.4 draw the spheres back to front, the inmost
//! first, over the atmosphere, whose light and attenuation they take from their tables.
//! Here a view ray's crossings of the shells (`shells.rs`), at distances t_1 < ... < t_n
//! with radiance L_k and transmittance T_k (`field.rs`, each lit by the model's own sun
//! through its transmittance and its sky where the crossing starts, `layer/composite.rs`'s
//! `light_at`), are composited with the model's answers for the ray ended at each
//! crossing, A(t_k) with transmittance M(t_k), and for the whole ray, A_full (ended on
//! the ground or a surface, with its reflection), per wavelength:
//!     L = sum_(k=0..n) (prod_(j<=k) T_j) (A(t_(k+1)) - A(t_k))
//!       + sum_(k=1..n) (prod_(j<k) T_j) M(t_k) L_k,
//! with t_0 = 0, A(t_0) = 0, T_0 = 1 and A(t_(n+1)) = A_full: the model's air between
//! two spheres seen through the spheres in front of it, each sphere's light through the
//! model's transmittance and the spheres in front (its aerial perspective). With one
//! crossing this is `layer/composite.rs`'s L_front + T_front L_cloud + T_cloud L_behind.
//! The transmittance is the model's times the product of the T_k. Crossings behind
//! spheres whose transmittance has fallen below [`MIN_TRANSMITTANCE`] are left out.
//! Under the layer's slab methods a crossing's light seen through the delta-scaled
//! medium (`slab_light.rs`) is dimmed by the product of the crossings' scaled
//! transmittances T'_j in front instead of the T_j, as in the layer's march.

use glam::DVec3;

use super::field::CloudSpheres;

/// The spheres' transmittance below which the crossings behind are left out: they could
/// add at most that fraction of their light (the layer's march stops the same way).
pub const MIN_TRANSMITTANCE: f64 = 1e-4;
use crate::clouds::layer::composite::light_at;
use crate::clouds::layer::march::{CloudLight, CloudSegment};
use crate::clouds::layer::orders::ScatteringOrders;
use crate::models::error::ModelError;
use crate::models::sky_model::{RayRadiance, SkyModel, ViewRay};

/// The radiance and transmittance of `ray` through the sky of `model` and the cloud
/// `spheres`, with the droplets' tables `orders` at the model's wavelengths.
pub fn radiance_with_spheres(
    model: &dyn SkyModel,
    spheres: &CloudSpheres,
    orders: &ScatteringOrders,
    ray: &ViewRay,
) -> Result<RayRadiance, ModelError> {
    let waves = model.wavelengths_nm().len();
    if orders.wavelengths() != waves {
        return Err(ModelError::Settings(format!(
            "cloud phase tables for {} wavelengths, the model answers {waves}",
            orders.wavelengths()
        )));
    }
    let sun = ray.sun_direction.normalize();
    if sun.dot(spheres.attenuation().sun_direction()) < 1.0 - 1e-9 {
        return Err(ModelError::Settings(format!(
            "cloud spheres: attenuation textures made for the sun at {}, the ray's sun is at {sun}",
            spheres.attenuation().sun_direction()
        )));
    }
    let full = model.radiance(ray)?;
    let direction = ray.direction.normalize();
    let max = ray.max_distance_m.unwrap_or(f64::INFINITY);
    let (crossings, _) = spheres.shells().crossings(ray.origin_m, direction, max);
    if crossings.is_empty() {
        return Ok(full);
    }
    let mut shaded = Vec::with_capacity(crossings.len());
    let mut seen_cloud = 1.0;
    for crossing in &crossings {
        if seen_cloud < MIN_TRANSMITTANCE {
            break;
        }
        let entry = ray.origin_m + direction * crossing.t0;
        let light = light_at(model, entry, sun)?;
        let cloud = spheres.shade(ray.origin_m, direction, crossing, &light, orders);
        seen_cloud *= cloud.transmittance[0].max(cloud.scaled_transmittance[0]);
        shaded.push((crossing.t0, cloud));
    }
    if shaded
        .iter()
        .all(|(_, c)| c.transmittance.iter().all(|&t| t == 1.0))
    {
        return Ok(full);
    }
    let mut answer = RayRadiance::unattenuated(waves);
    let mut seen = vec![1.0; waves];
    let mut seen_scaled = vec![1.0; waves];
    let mut before = vec![0.0; waves];
    for (t0, cloud) in &shaded {
        let at = model.radiance(&ViewRay {
            max_distance_m: Some(*t0),
            ..*ray
        })?;
        for w in 0..waves {
            answer.radiance[w] += seen[w] * (at.radiance[w] - before[w]).max(0.0)
                + at.transmittance[w]
                    * (seen[w] * cloud.radiance[w] + seen_scaled[w] * cloud.scaled_radiance[w]);
            seen[w] *= cloud.transmittance[w];
            seen_scaled[w] *= cloud.scaled_transmittance[w];
        }
        before.clone_from(&at.radiance);
    }
    for w in 0..waves {
        answer.radiance[w] += seen[w] * (full.radiance[w] - before[w]).max(0.0);
        answer.transmittance[w] = full.transmittance[w] * seen[w];
    }
    Ok(answer)
}

/// The spheres alone along a ray lit by one `light`, without air: the crossings'
/// radiance composited front to back, sum_k (prod_(j<k) T_j) L_k, and the product of
/// their transmittances; the distance to the first crossing (`None` when the ray
/// crosses no shell). The GPU's sphere pass writes this per pixel.
pub fn spheres_only(
    spheres: &CloudSpheres,
    orders: &ScatteringOrders,
    light: &CloudLight,
    origin: DVec3,
    direction: DVec3,
    max_distance_m: f64,
) -> (CloudSegment, Option<f64>) {
    let waves = light.sun_irradiance.len();
    let mut total = CloudSegment {
        radiance: vec![0.0; waves],
        transmittance: vec![1.0; waves],
    };
    let mut seen_scaled = vec![1.0; waves];
    let (crossings, _) = spheres
        .shells()
        .crossings(origin, direction, max_distance_m);
    for crossing in &crossings {
        if total.transmittance[0].max(seen_scaled[0]) < MIN_TRANSMITTANCE {
            break;
        }
        let cloud = spheres.shade(origin, direction, crossing, light, orders);
        for w in 0..waves {
            total.radiance[w] += total.transmittance[w] * cloud.radiance[w]
                + seen_scaled[w] * cloud.scaled_radiance[w];
            total.transmittance[w] *= cloud.transmittance[w];
            seen_scaled[w] *= cloud.scaled_transmittance[w];
        }
    }
    (total, crossings.first().map(|c| c.t0))
}
