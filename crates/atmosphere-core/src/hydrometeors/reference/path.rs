//! One path of the volumes' path tracer, followed from a collision inside a homogeneous
//! volume (albedo 1) back towards the light, all orders of scattering, as the cloud
//! path tracer's (`clouds/reference/camera_path.rs`), each of the frame's three
//! channels c on its own paths:
//! - at every collision x, next-event estimation of the sun: w P_c(nu) E_sun,c(x)
//!   e^(-beta s(x)), with nu the cosine between the path's direction and the sun, E_sun
//!   the sun through the atmosphere at x (`clouds/reference/sun_light.rs`, a point sun:
//!   the tables already hold the sun's disc) and s(x) the sun's path inside the volume,
//!   P_c and the extinction beta with the forward peak taken as no scattering
//!   ([`super::phase`]);
//! - the path then scatters into a direction drawn from the proposal of [`super::phase`]
//!   (the weight w times P_c / q) and flies a distance drawn from e^(-beta t);
//! - where it leaves the volume it takes the light around it from that direction
//!   (`clouds/reference/environment.rs`, the sky model's radiance, the sun's disc
//!   excluded so that the sun is counted once), or none when the scene leaves the sky
//!   out.
//!
//! Russian roulette ends paths whose weight has fallen below
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

/// Below this weight a path survives with probability weight / this, its weight
/// raised to this.
pub const ROULETTE_WEIGHT: f64 = 0.1;
/// Collisions at most per path.
pub const MAX_SCATTERINGS: u32 = 100_000;

/// The sun's irradiance at a point on a plane facing it, per channel.
pub trait SunIrradiance: Sync {
    /// The irradiance at `point` from the sun towards the unit `sun`, into `out`.
    fn irradiance(&self, point: DVec3, sun: DVec3, out: &mut [f64]);
    /// How many channels it answers.
    fn wavelengths(&self) -> usize;
}

impl SunIrradiance for SunThroughAtmosphere {
    fn irradiance(&self, point: DVec3, sun: DVec3, out: &mut [f64]) {
        SunThroughAtmosphere::irradiance(self, point, sun, out);
    }

    fn wavelengths(&self) -> usize {
        SunThroughAtmosphere::wavelengths(self)
    }
}

/// The same irradiance everywhere (the renderer's one value per volume).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UniformSun(pub [f64; 3]);

impl SunIrradiance for UniformSun {
    fn irradiance(&self, _: DVec3, _: DVec3, out: &mut [f64]) {
        out.copy_from_slice(&self.0);
    }

    fn wavelengths(&self) -> usize {
        3
    }
}

/// What every path of a view shares.
pub struct VolumePaths<'a> {
    pub volume: &'a Volume,
    pub phase: &'a ChannelSampler,
    /// The sun at the frame's three wavelengths: through the atmosphere, or uniform.
    pub sun: &'a dyn SunIrradiance,
    /// The light around the volume; `None`: the sky's light left out.
    pub environment: Option<&'a Environment>,
    /// Unit vector towards the sun.
    pub sun_direction: DVec3,
}

impl VolumePaths<'_> {
    /// Channel `c`'s extinction with the forward peak taken as no scattering
    /// ([`super::phase`]), m^-1.
    pub fn extinction(&self, c: usize) -> f64 {
        self.volume.extinction_per_m * (1.0 - self.phase.peak.peak_fraction[c])
    }
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
}

/// The light of channel `c` that the path from the collision `x`, reached along the
/// unit `d`, brings back towards `-d`, per unit of the path's weight: the sun once,
/// the sun more times, the sky.
pub fn trace_from(
    paths: &VolumePaths,
    c: usize,
    x: DVec3,
    d: DVec3,
    sampler: &mut Sampler,
) -> [f64; 3] {
    trace_from_cut(paths, c, (x, d), sampler, MAX_SCATTERINGS)
}

/// [`trace_from`] with the path cut after `max_scatterings` collisions (the light of
/// longer paths left out).
pub fn trace_from_cut(
    paths: &VolumePaths,
    c: usize,
    (mut x, mut d): (DVec3, DVec3),
    sampler: &mut Sampler,
    max_scatterings: u32,
) -> [f64; 3] {
    let beta = paths.extinction(c);
    let s = paths.sun_direction;
    let mut weight = 1.0;
    let [mut sun_single, mut sun_multiple] = [0.0; 2];
    let mut light = [0.0; 3];
    for order in 0..max_scatterings {
        paths.sun.irradiance(x, s, &mut light);
        if light[c] > 0.0 {
            let shadow = (-beta * paths.volume.exit_distance(x, s)).exp();
            let sun = weight * paths.phase.phase(d.dot(s))[c] * light[c] * shadow;
            if order == 0 {
                sun_single += sun;
            } else {
                sun_multiple += sun;
            }
        }
        let (cos, factor) = paths.phase.sample(c, sampler);
        weight *= factor;
        if weight.abs() < ROULETTE_WEIGHT {
            if sampler.uniform() * ROULETTE_WEIGHT >= weight.abs() {
                return [sun_single, sun_multiple, 0.0];
            }
            weight = ROULETTE_WEIGHT * weight.signum();
        }
        d = direction_around(d, cos, 2.0 * std::f64::consts::PI * sampler.uniform());
        let free = -(1.0 - sampler.uniform()).ln() / beta;
        if free >= paths.volume.exit_distance(x, d) {
            let sky = paths.environment.map_or(0.0, |environment| {
                environment.radiance(d, &mut light);
                weight * light[c]
            });
            return [sun_single, sun_multiple, sky];
        }
        x += d * free;
    }
    [sun_single, sun_multiple, 0.0]
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
