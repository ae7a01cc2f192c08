//! A view ray's radiance through the sky model's air and the cloud layer by the path
//! tracer: the layer's composite (`layer/composite.rs`),
//!     L = L_front + T_front L_cloud + T_cloud (L_full - L_front),
//! with the same model answers L_full, L_front, T_front as the march's (the cloud's
//! shadow in them where `PathScene::view_air` gives it), but the cloud's
//! own light L_cloud path traced (`camera_path.rs`) and its transmittance T_cloud
//! integrated along the ray's first crossing of the layer by the midpoint rule in steps
//! of at most [`TRANSMITTANCE_STEP_M`]. Each path draws its first collision on the
//! crossing by delta tracking (a path that crosses without one adds nothing: the light
//! behind is the composite's T_cloud term). The standard error of L is T_front times
//! that of L_cloud's mean.

use glam::DVec3;

use super::camera_path::{LayerLight, PathScene, first_collision, trace_from};
use super::environment::Environment;
use super::settings::{BATCH_PATHS, PathSettings};
use crate::clouds::estimate::Tally;
use crate::clouds::layer::composite::composite;
use crate::clouds::layer::march::CloudSegment;
use crate::clouds::medium::CloudMedium;
use crate::models::error::ModelError;
use crate::models::sky_model::{RayRadiance, ViewRay};
use crate::numerics::sampling::{Sampler, mix_seed};

/// The longest step of the cloud transmittance's midpoint rule, m (the detail noise's
/// smallest cells are a few hundred metres).
pub const TRANSMITTANCE_STEP_M: f64 = 10.0;
/// Steps of that rule at most, for grazing crossings hundreds of kilometres long.
const MAX_TRANSMITTANCE_STEPS: usize = 1 << 16;

/// What the path tracer answers for a view ray.
#[derive(Clone, Debug, PartialEq)]
pub struct PathTracedRay {
    /// The composited radiance, its standard error and the whole ray's transmittance.
    pub radiance: RayRadiance,
    /// The cloud's transmittance along the ray's crossing of the layer (1 without one).
    pub cloud_transmittance: f64,
    /// Paths followed (0 for a ray that misses the layer).
    pub paths: u64,
}

/// The answer for `ray` with its standard error; `paths` paths per wavelength.
pub fn radiance_path_traced(
    scene: &PathScene,
    ray: &ViewRay,
    settings: &PathSettings,
) -> Result<PathTracedRay, ModelError> {
    settings
        .check()
        .map_err(|e| ModelError::Settings(e.to_string()))?;
    let waves = scene.sun.wavelengths();
    if scene.orders.wavelengths() != waves
        || scene.phases.len() != waves
        || scene.sky.wavelengths_nm().len() != waves
    {
        return Err(ModelError::Settings(format!(
            "cloud path tracer: phase tables for {} wavelengths, the sky model answers {}, \
             the sun {waves}",
            scene.orders.wavelengths(),
            scene.sky.wavelengths_nm().len()
        )));
    }
    let view_air = scene.view_air.unwrap_or(scene.sky);
    let full = view_air.radiance(ray)?;
    let direction = ray.direction.normalize();
    let Some((t0, t1)) = scene.layer.shell().first_segment(
        ray.origin_m,
        direction,
        ray.max_distance_m.unwrap_or(f64::INFINITY),
    ) else {
        return Ok(PathTracedRay {
            radiance: full,
            cloud_transmittance: 1.0,
            paths: 0,
        });
    };
    let front = if t0 > 0.0 {
        view_air.radiance(&ViewRay {
            max_distance_m: Some(t0),
            ..*ray
        })?
    } else {
        RayRadiance::unattenuated(waves)
    };
    let start = ray.origin_m + direction * t0;
    let shell = scene.layer.shell();
    let environment = Environment::new(
        scene.sky,
        start,
        scene.sun_direction,
        shell.base_radius_m,
        shell.top_radius_m,
    )?;
    let transmittance = crossing_transmittance(scene, ray.origin_m, direction, t0, t1);
    let seed = mix_seed(&[
        settings.seed,
        ray.origin_m.x.to_bits(),
        ray.origin_m.y.to_bits(),
        ray.origin_m.z.to_bits(),
        direction.x.to_bits(),
        direction.y.to_bits(),
        direction.z.to_bits(),
    ]);
    let medium = scene.medium();
    let light = LayerLight {
        sun: scene.sun,
        environment: &environment,
        sun_direction: scene.sun_direction,
    };
    let mut tallies = vec![Tally::default(); waves];
    let mut paths = 0;
    while paths < settings.max_paths {
        for _ in 0..BATCH_PATHS.min(settings.max_paths - paths) {
            for (w, tally) in tallies.iter_mut().enumerate() {
                let mut sampler = Sampler::new(mix_seed(&[seed, paths, w as u64]));
                let score =
                    match first_collision(scene.layer, start, direction, t1 - t0, &mut sampler) {
                        Some(x) => trace_from(&medium, &light, w, x, direction, &mut sampler),
                        None => 0.0,
                    };
                tally.add(score);
            }
            paths += 1;
        }
        if paths >= settings.min_paths
            && converged(&tallies, &full, &front, transmittance, settings)
        {
            break;
        }
    }
    let cloud = CloudSegment {
        radiance: tallies.iter().map(|t| t.estimate().mean).collect(),
        transmittance: vec![transmittance; waves],
    };
    let mut answer = composite(&full, &front, &cloud);
    answer.radiance_std_error = tallies
        .iter()
        .zip(&front.transmittance)
        .map(|(t, front_t)| front_t * t.estimate().standard_error)
        .collect();
    Ok(PathTracedRay {
        radiance: answer,
        cloud_transmittance: transmittance,
        paths,
    })
}

/// exp(-int sigma) over `[t0, t1]` by the midpoint rule.
fn crossing_transmittance(scene: &PathScene, origin: DVec3, d: DVec3, t0: f64, t1: f64) -> f64 {
    let length = t1 - t0;
    let steps = ((length / TRANSMITTANCE_STEP_M).ceil() as usize).clamp(1, MAX_TRANSMITTANCE_STEPS);
    let dt = length / steps as f64;
    let depth: f64 = (0..steps)
        .map(|i| {
            scene
                .layer
                .extinction(origin + d * (t0 + (i as f64 + 0.5) * dt))
        })
        .sum::<f64>()
        * dt;
    (-depth).exp()
}

/// Whether the standard error of every wavelength's composited radiance is below the
/// target fraction of it.
fn converged(
    tallies: &[Tally],
    full: &RayRadiance,
    front: &RayRadiance,
    transmittance: f64,
    settings: &PathSettings,
) -> bool {
    tallies.iter().enumerate().all(|(w, tally)| {
        let e = tally.estimate();
        let behind = (full.radiance[w] - front.radiance[w]).max(0.0);
        let total = front.radiance[w] + front.transmittance[w] * e.mean + transmittance * behind;
        front.transmittance[w] * e.standard_error <= settings.target_relative_error * total
    })
}
