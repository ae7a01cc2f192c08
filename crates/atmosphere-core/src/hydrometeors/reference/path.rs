//! One path of the volumes' path tracer, followed from a collision inside a homogeneous
//! volume (albedo 1) back towards the light, all orders of scattering, as the cloud
//! path tracer's (`clouds/reference/camera_path.rs`) but with the volume's three
//! channels on one path:
//! - at every collision x, next-event estimation of the sun: w_c P_c(nu) E_sun,c(x)
//!   e^(-beta s(x)), with nu the cosine between the path's direction and the sun, E_sun
//!   the sun through the atmosphere at x (`clouds/reference/sun_light.rs`, a point sun:
//!   the tables already hold the sun's disc) and s(x) the sun's path inside the volume;
//! - the path then scatters into a direction drawn from the proposal of [`super::phase`]
//!   (each weight w_c times P_c / q) and flies a distance drawn from e^(-beta t);
//! - where it leaves the volume it takes the light around it from that direction
//!   (`clouds/reference/environment.rs`, the sky model's radiance, the sun's disc
//!   excluded so that the sun is counted once), or none when the scene leaves the sky
//!   out.
//!
//! Russian roulette ends paths whose largest weight has fallen below
//! [`ROULETTE_WEIGHT`], unbiased; a path of more than [`MAX_SCATTERINGS`] collisions is
//! cut.

use glam::DVec3;

use super::phase::ChannelSampler;
use crate::clouds::reference::environment::Environment;
use crate::clouds::reference::sun_light::SunThroughAtmosphere;
use crate::hydrometeors::volumes::{Shape, Volume};
use crate::models::error::ModelError;
use crate::models::sky_model::SkyModel;
use crate::numerics::sampling::{Sampler, direction_around};

/// Below this largest weight a path survives with probability weight / this, its
/// weights raised by the same factor.
pub const ROULETTE_WEIGHT: f64 = 0.1;
/// Collisions at most per path.
pub const MAX_SCATTERINGS: u32 = 100_000;

/// What every path of a view shares.
pub struct VolumePaths<'a> {
    pub volume: &'a Volume,
    pub phase: &'a ChannelSampler,
    /// The sun through the atmosphere at the frame's three wavelengths.
    pub sun: &'a SunThroughAtmosphere,
    /// The light around the volume; `None`: the sky's light left out.
    pub environment: Option<&'a Environment>,
    /// Unit vector towards the sun.
    pub sun_direction: DVec3,
}

impl std::fmt::Debug for VolumePaths<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VolumePaths")
            .field("volume", self.volume)
            .field("sky", &self.environment.is_some())
            .field("sun_direction", &self.sun_direction)
            .finish()
    }
}

/// What one path brings back per channel, W m^-2 sr^-1 nm^-1, in three parts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathLight {
    /// The sun's light scattered once, at the first collision (the march's sun term).
    pub sun_single: [f64; 3],
    /// The sun's light scattered two and more times.
    pub sun_multiple: [f64; 3],
    /// The sky's light, scattered any number of times.
    pub sky: [f64; 3],
}

impl PathLight {
    /// The three parts' sum.
    pub fn total(&self) -> [f64; 3] {
        std::array::from_fn(|c| self.sun_single[c] + self.sun_multiple[c] + self.sky[c])
    }

    /// Every part times `factor`.
    pub fn scaled(&self, factor: f64) -> PathLight {
        PathLight {
            sun_single: self.sun_single.map(|v| v * factor),
            sun_multiple: self.sun_multiple.map(|v| v * factor),
            sky: self.sky.map(|v| v * factor),
        }
    }
}

/// The light that the path from the collision `x`, reached along the unit `d`, brings
/// back towards `-d`, per unit of the path's weight.
pub fn trace_from(
    paths: &VolumePaths,
    mut x: DVec3,
    mut d: DVec3,
    sampler: &mut Sampler,
) -> PathLight {
    let beta = paths.volume.extinction_per_m;
    let s = paths.sun_direction;
    let mut weight = [1.0; 3];
    let mut score = PathLight::default();
    let mut light = [0.0; 3];
    for order in 0..MAX_SCATTERINGS {
        paths.sun.irradiance(x, s, &mut light);
        if light.iter().any(|e| *e > 0.0) {
            let shadow = (-beta * paths.volume.exit_distance(x, s)).exp();
            let p = paths.phase.phase(d.dot(s));
            let sun = if order == 0 {
                &mut score.sun_single
            } else {
                &mut score.sun_multiple
            };
            for c in 0..3 {
                sun[c] += weight[c] * p[c] * light[c] * shadow;
            }
        }
        let (cos, factor) = paths.phase.sample(sampler);
        for c in 0..3 {
            weight[c] *= factor[c];
        }
        let largest = weight.iter().fold(0.0_f64, |m, w| m.max(w.abs()));
        if largest < ROULETTE_WEIGHT {
            if sampler.uniform() * ROULETTE_WEIGHT >= largest {
                return score;
            }
            weight = weight.map(|w| w * ROULETTE_WEIGHT / largest);
        }
        d = direction_around(d, cos, 2.0 * std::f64::consts::PI * sampler.uniform());
        let free = -(1.0 - sampler.uniform()).ln() / beta;
        if free >= paths.volume.exit_distance(x, d) {
            if let Some(environment) = paths.environment {
                environment.radiance(d, &mut light);
                for c in 0..3 {
                    score.sky[c] += weight[c] * light[c];
                }
            }
            return score;
        }
        x += d * free;
    }
    score
}

/// The light around `volume` for `sky` with the sun towards the unit `sun`, seen from
/// `camera_m`: the sky model's radiance tabulated about the volume's `light_point`
/// (one table for every ray of a view), upward directions from a layer's top and
/// downward ones from its base, every direction from a shaft's middle height.
pub fn environment_around(
    volume: &Volume,
    sky: &dyn SkyModel,
    camera_m: DVec3,
    sun: DVec3,
) -> Result<Environment, ModelError> {
    let anchor = volume.light_point(camera_m);
    let (base, top) = match volume.shape {
        Shape::Layer(shell) => (shell.base_radius_m, shell.top_radius_m),
        Shape::Shaft { .. } => (anchor.length(), anchor.length()),
    };
    Environment::new(sky, anchor, sun, base, top)
}
