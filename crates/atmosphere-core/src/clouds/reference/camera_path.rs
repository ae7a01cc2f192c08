//! One path of the cloud path tracer, followed from a collision inside a cloud medium
//! back towards the light, all orders of scattering:
//! - at every real collision x (delta tracking, Woodcock et al. 1965), next-event
//!   estimation of the sun: albedo p_w(nu) E_sun,w(x) T_cloud(x -> sun), with p_w the
//!   droplets' phase function at wavelength w (A_1 of Riley et al. 2004, Eq. 20), nu
//!   the cosine between the path's direction and the sun, E_sun the sun's irradiance
//!   outside the cloud ([`PathLight`]: for the layer the sun through the atmosphere) and
//!   T_cloud the cloud's transmittance towards the sun by ratio tracking (Novak, Selle
//!   and Jarosz 2014);
//! - the path then scatters: a direction drawn from p_w exactly (`phase_sampler.rs`),
//!   the weight multiplied by the albedo. Each wavelength follows its own paths.
//! - where it leaves the medium it takes the light around it from that direction
//!   ([`PathLight::surroundings`]: for the layer the sky model's radiance, the sun disk
//!   excluded, so the sun is counted once: `environment.rs`).
//!
//! The medium is any [`CloudMedium`]: the layer on the planet, or a voxel cloud in a
//! scene of its own (`volume/path_traced.rs`). Russian roulette ends paths whose weight
//! has fallen below [`ROULETTE_WEIGHT`], unbiased; a path of more than
//! [`MAX_SCATTERINGS`] collisions is cut (none of the layer's optical depths comes near
//! it).

use glam::DVec3;

use super::environment::Environment;
use super::phase_sampler::PhaseTableSampler;
use super::sun_light::SunThroughAtmosphere;
use crate::clouds::layer::field::CloudLayer;
use crate::clouds::layer::orders::ScatteringOrders;
use crate::clouds::medium::CloudMedium;
use crate::models::sky_model::SkyModel;
use crate::numerics::sampling::{Sampler, direction_around};

/// Below this weight a path survives with probability weight /
/// this, its weight raised to this.
pub const ROULETTE_WEIGHT: f64 = 0.1;
/// Collisions at most per path.
pub const MAX_SCATTERINGS: u32 = 100_000;

/// The light a path meets outside the cloud.
pub trait PathLight {
    /// Unit vector towards the sun.
    fn sun_direction(&self) -> DVec3;

    /// The sun's irradiance at `x` at each wavelength, W m^-2 nm^-1, before the cloud's
    /// own attenuation (0 where something else hides the sun).
    fn sun_irradiance(&self, x: DVec3, out: &mut [f64]);

    /// The radiance at each wavelength that arrives from beyond the medium along a path
    /// that leaves it in the unit `direction`, W m^-2 sr^-1 nm^-1.
    fn surroundings(&self, direction: DVec3, out: &mut [f64]);
}

/// A cloud medium with its droplets' phase function at each wavelength: what a path
/// scatters by.
pub struct PathMedium<'a, M: CloudMedium + ?Sized> {
    pub medium: &'a M,
    /// The phase function (A_1) at each wavelength, read by the sun's next-event
    /// estimate and drawn from when a path scatters.
    pub phases: &'a [PhaseTableSampler],
}

impl<M: CloudMedium + ?Sized> std::fmt::Debug for PathMedium<'_, M> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PathMedium")
            .field("wavelengths", &self.phases.len())
            .finish_non_exhaustive()
    }
}

/// The layer's light for one view ray: the sun through the atmosphere, and the sky
/// model's radiance tabulated about the ray's entry into the layer.
#[derive(Debug)]
pub struct LayerLight<'a> {
    pub sun: &'a SunThroughAtmosphere,
    pub environment: &'a Environment,
    pub sun_direction: DVec3,
}

impl PathLight for LayerLight<'_> {
    fn sun_direction(&self) -> DVec3 {
        self.sun_direction
    }

    fn sun_irradiance(&self, x: DVec3, out: &mut [f64]) {
        self.sun.irradiance(x, self.sun_direction, out);
    }

    fn surroundings(&self, direction: DVec3, out: &mut [f64]) {
        self.environment.radiance(direction, out);
    }
}

/// What every path of one view ray through the layer shares.
pub struct PathScene<'a> {
    pub layer: &'a CloudLayer,
    /// A_1 (the phase function) at each wavelength of the sky model.
    pub orders: &'a ScatteringOrders,
    /// Its sampler at each wavelength.
    pub phases: &'a [PhaseTableSampler],
    pub sun: &'a SunThroughAtmosphere,
    /// The air around the cloud: the composite's answers, and the light where a path
    /// leaves the layer (tabulated per view ray, `environment.rs`).
    pub sky: &'a dyn SkyModel,
    /// The view ray's own air for the composite (L_full, L_front) where it differs from
    /// `sky`: the cloud's shadow in it (`layer/shadowed_air.rs`); `None`: `sky`'s.
    pub view_air: Option<&'a dyn SkyModel>,
    /// Unit vector towards the sun.
    pub sun_direction: DVec3,
}

impl std::fmt::Debug for PathScene<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PathScene")
            .field("layer", self.layer.settings())
            .field("sky", &self.sky.id())
            .field("sun_direction", &self.sun_direction)
            .finish()
    }
}

impl PathScene<'_> {
    /// The layer with its tables, as the paths scatter in it.
    pub fn medium(&self) -> PathMedium<'_, CloudLayer> {
        PathMedium {
            medium: self.layer,
            phases: self.phases,
        }
    }
}

/// Where a free flight from inside the medium ends.
enum Flight {
    /// A real collision at this point.
    Collision(DVec3),
    /// Out of the medium.
    Escape,
}

/// A free flight from `x` along the unit `d` by delta tracking.
fn fly<M: CloudMedium + ?Sized>(
    medium: &M,
    mut x: DVec3,
    d: DVec3,
    sampler: &mut Sampler,
) -> Flight {
    let majorant = medium.majorant();
    loop {
        let to_boundary = medium.distance_to_boundary(x, d);
        let free = if majorant > 0.0 {
            -(1.0 - sampler.uniform()).ln() / majorant
        } else {
            f64::INFINITY
        };
        if free >= to_boundary {
            return Flight::Escape;
        }
        x += d * free;
        if sampler.uniform() * majorant < medium.extinction(x) {
            return Flight::Collision(x);
        }
    }
}

/// The first real collision within `length` of `start` along the unit `d`, if any, by
/// delta tracking.
pub fn first_collision<M: CloudMedium + ?Sized>(
    medium: &M,
    start: DVec3,
    d: DVec3,
    length: f64,
    sampler: &mut Sampler,
) -> Option<DVec3> {
    let majorant = medium.majorant();
    if majorant <= 0.0 {
        return None;
    }
    let mut travelled = 0.0;
    loop {
        travelled += -(1.0 - sampler.uniform()).ln() / majorant;
        if travelled >= length {
            return None;
        }
        let x = start + d * travelled;
        if sampler.uniform() * majorant < medium.extinction(x) {
            return Some(x);
        }
    }
}

/// The cloud's transmittance from `x` along the unit `d` to the medium's boundary, by
/// ratio tracking with Russian roulette below 0.01 (unbiased).
pub fn transmittance_to_boundary<M: CloudMedium + ?Sized>(
    medium: &M,
    mut x: DVec3,
    d: DVec3,
    sampler: &mut Sampler,
) -> f64 {
    let majorant = medium.majorant();
    if majorant <= 0.0 {
        return 1.0;
    }
    let mut t = 1.0;
    loop {
        let to_boundary = medium.distance_to_boundary(x, d);
        let free = -(1.0 - sampler.uniform()).ln() / majorant;
        if free >= to_boundary {
            return t;
        }
        x += d * free;
        t *= 1.0 - (medium.extinction(x) / majorant).min(1.0);
        if t < 0.01 {
            if sampler.uniform() < 0.5 {
                return 0.0;
            }
            t *= 2.0;
        }
    }
}

/// The light at wavelength `w` (W m^-2 sr^-1 nm^-1) that the path from the real
/// collision `x`, reached along the unit `d`, brings back towards `-d`, per unit of the
/// path's weight (see the module's documentation).
pub fn trace_from<M: CloudMedium + ?Sized>(
    scene: &PathMedium<M>,
    light: &impl PathLight,
    w: usize,
    mut x: DVec3,
    mut d: DVec3,
    sampler: &mut Sampler,
) -> f64 {
    let medium = scene.medium;
    let phase = &scene.phases[w];
    let sun_direction = light.sun_direction();
    let mut weight = 1.0;
    let mut score = 0.0;
    let mut radiance = vec![0.0; scene.phases.len()];
    for _ in 0..MAX_SCATTERINGS {
        let albedo = medium.single_scattering_albedo(x);
        let nu = d.dot(sun_direction);
        light.sun_irradiance(x, &mut radiance);
        if radiance[w] > 0.0 {
            let t_cloud = transmittance_to_boundary(medium, x, sun_direction, sampler);
            score += weight * albedo * phase.value(nu) * radiance[w] * t_cloud;
        }
        let (cos, phase_weight) = phase.sample(sampler);
        weight *= albedo * phase_weight;
        if weight < ROULETTE_WEIGHT {
            if sampler.uniform() * ROULETTE_WEIGHT >= weight {
                return score;
            }
            weight = ROULETTE_WEIGHT;
        }
        d = direction_around(d, cos, 2.0 * std::f64::consts::PI * sampler.uniform());
        match fly(medium, x, d, sampler) {
            Flight::Collision(y) => x = y,
            Flight::Escape => {
                light.surroundings(d, &mut radiance);
                return score + weight * radiance[w];
            }
        }
    }
    score
}
