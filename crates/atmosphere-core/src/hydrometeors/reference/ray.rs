//! A view ray's radiance through the sky model's air and a volume by the path tracer,
//! composited as the cloud path tracer's rays are (`clouds/reference/ray.rs`):
//!     L = L_front + T_front L_v + T_v (L_full - L_front),
//! with L_full the model's answer for the whole ray, L_front and T_front its answer up
//! to the volume's entry (the model run a second time: the renderer instead takes
//! L_front as the fraction 1 - T_front of L_full, `hydrometeors/render.rs`), T_v the
//! volume's transmittance e^(-beta' (t1 - t0)) along the ray's interval in it (beta'
//! per channel, the forward peak taken as no scattering, [`super::phase`]: what lies
//! behind arrives through the peak too) and L_v
//! its own light, path traced ([`super::path`]). Each path's first collision is drawn
//! inside the interval from the exponential cut at its end and weighted by 1 - T_v
//! (every path scatters), so no path is spent crossing without a collision. The
//! standard error of L is T_front times that of L_v's mean.

use glam::DVec3;

use super::path::{PathLight, VolumePaths, trace_from};
use crate::clouds::estimate::Tally;
use crate::clouds::layer::composite::composite;
use crate::clouds::layer::march::CloudSegment;
use crate::clouds::reference::settings::{BATCH_PATHS, PathSettings};
use crate::models::error::ModelError;
use crate::models::sky_model::{RayRadiance, SkyModel, ViewRay};
use crate::numerics::sampling::{Sampler, mix_seed};

/// A view ray's answer by the path tracer.
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeTracedRay {
    /// The composited radiance, its standard error and the whole ray's transmittance.
    pub radiance: RayRadiance,
    /// The volume's transmittance e^(-beta (t1 - t0)) along the ray, its whole
    /// extinction (1 where the ray misses it).
    pub volume_transmittance: f64,
    /// The volume's light seen from the camera, T_front L_v, in its three parts.
    pub volume_light: PathLight,
    /// Paths followed (0 for a ray that misses the volume).
    pub paths: u64,
}

/// The running sums of a segment's paths: the total light per channel (for its
/// standard error) and its three parts.
#[derive(Clone, Copy, Debug, Default)]
pub struct SegmentTally {
    pub total: [Tally; 3],
    pub sun_single: [Tally; 3],
    pub sun_multiple: [Tally; 3],
    pub sky: [Tally; 3],
}

impl SegmentTally {
    fn add(&mut self, light: &PathLight) {
        let total = light.total();
        for c in 0..3 {
            self.total[c].add(total[c]);
            self.sun_single[c].add(light.sun_single[c]);
            self.sun_multiple[c].add(light.sun_multiple[c]);
            self.sky[c].add(light.sky[c]);
        }
    }

    /// The parts' means times `factor`.
    pub fn mean_parts(&self, factor: [f64; 3]) -> PathLight {
        let mean = |t: &[Tally; 3]| std::array::from_fn(|c| factor[c] * t[c].estimate().mean);
        PathLight {
            sun_single: mean(&self.sun_single),
            sun_multiple: mean(&self.sun_multiple),
            sky: mean(&self.sky),
        }
    }
}

/// The answer for `ray` through `paths`' volume and `sky`'s air (at the frame's three
/// wavelengths), with its standard error, to the stopping rule `settings`.
pub fn radiance_path_traced(
    paths: &VolumePaths,
    sky: &dyn SkyModel,
    ray: &ViewRay,
    settings: &PathSettings,
) -> Result<VolumeTracedRay, ModelError> {
    settings
        .check()
        .map_err(|e| ModelError::Settings(e.to_string()))?;
    let waves = sky.wavelengths_nm().len();
    if waves != 3 || paths.sun.wavelengths() != 3 {
        return Err(ModelError::Settings(format!(
            "volume path tracer: the volumes have three channels, the sky model answers \
             {waves} wavelengths, the sun {}",
            paths.sun.wavelengths()
        )));
    }
    let full = sky.radiance(ray)?;
    let direction = ray.direction.normalize();
    let max_distance = ray.max_distance_m.unwrap_or(f64::INFINITY);
    let Some((t0, t1)) = paths.volume.segment(ray.origin_m, direction, max_distance) else {
        return Ok(VolumeTracedRay {
            radiance: full,
            volume_transmittance: 1.0,
            volume_light: PathLight::default(),
            paths: 0,
        });
    };
    let front = if t0 > 0.0 {
        sky.radiance(&ViewRay {
            max_distance_m: Some(t0),
            ..*ray
        })?
    } else {
        RayRadiance::unattenuated(waves)
    };
    let transmittance: [f64; 3] = std::array::from_fn(|c| (-paths.extinction(c) * (t1 - t0)).exp());
    let seed = mix_seed(&[
        settings.seed,
        ray.origin_m.x.to_bits(),
        ray.origin_m.y.to_bits(),
        ray.origin_m.z.to_bits(),
        direction.x.to_bits(),
        direction.y.to_bits(),
        direction.z.to_bits(),
    ]);
    let done = |t: &SegmentTally| converged(&t.total, &full, &front, transmittance, settings);
    let (tally, count) = trace_segment(
        paths,
        (ray.origin_m, direction),
        (t0, t1),
        settings,
        seed,
        done,
    );
    let volume = CloudSegment {
        radiance: tally.total.iter().map(|t| t.estimate().mean).collect(),
        transmittance: transmittance.to_vec(),
    };
    let mut answer = composite(&full, &front, &volume);
    answer.radiance_std_error = tally
        .total
        .iter()
        .zip(&front.transmittance)
        .map(|(t, front_t)| front_t * t.estimate().standard_error)
        .collect();
    let front_t = std::array::from_fn(|c| front.transmittance[c]);
    Ok(VolumeTracedRay {
        radiance: answer,
        volume_transmittance: (-paths.volume.extinction_per_m * (t1 - t0)).exp(),
        volume_light: tally.mean_parts(front_t),
        paths: count,
    })
}

/// The volume's own light L_v along the interval `(t0, t1)` of the ray `(origin,
/// direction)` (unit), and the paths followed: batches of paths from `seed` until
/// `done` says so after at least `min_paths`, or `max_paths`.
pub fn trace_segment(
    paths: &VolumePaths,
    (origin, direction): (DVec3, DVec3),
    (t0, t1): (f64, f64),
    settings: &PathSettings,
    seed: u64,
    done: impl Fn(&SegmentTally) -> bool,
) -> (SegmentTally, u64) {
    let mut tally = SegmentTally::default();
    let mut count = 0;
    while count < settings.max_paths {
        for _ in 0..BATCH_PATHS.min(settings.max_paths - count) {
            let mut light = PathLight::default();
            for c in 0..3 {
                let beta = paths.extinction(c);
                let transmittance = (-beta * (t1 - t0)).exp();
                if transmittance >= 1.0 {
                    continue;
                }
                let mut sampler = Sampler::new(mix_seed(&[seed, count, c as u64]));
                let u = sampler.uniform();
                let t = t0 - (1.0 - u * (1.0 - transmittance)).ln() / beta;
                let x = origin + direction * t.min(t1);
                let [single, multiple, sky] = trace_from(paths, c, x, direction, &mut sampler);
                light.sun_single[c] = single * (1.0 - transmittance);
                light.sun_multiple[c] = multiple * (1.0 - transmittance);
                light.sky[c] = sky * (1.0 - transmittance);
            }
            tally.add(&light);
            count += 1;
        }
        if count >= settings.min_paths && done(&tally) {
            break;
        }
    }
    (tally, count)
}

/// Whether the standard error of every channel's composited radiance is below the
/// target fraction of it.
fn converged(
    tallies: &[Tally; 3],
    full: &RayRadiance,
    front: &RayRadiance,
    transmittance: [f64; 3],
    settings: &PathSettings,
) -> bool {
    tallies.iter().enumerate().all(|(c, tally)| {
        let e = tally.estimate();
        let behind = (full.radiance[c] - front.radiance[c]).max(0.0);
        let total = front.radiance[c] + front.transmittance[c] * e.mean + transmittance[c] * behind;
        front.transmittance[c] * e.standard_error <= settings.target_relative_error * total.abs()
    })
}

/// The direction `centre` turned by `angle_deg` towards the unit `towards` (at right
/// angles to it): the rays of a line across a bow, a halo or a glory.
pub fn turned(centre: DVec3, towards: DVec3, angle_deg: f64) -> DVec3 {
    let a = angle_deg.to_radians();
    (centre * a.cos() + towards * a.sin()).normalize()
}
