//! One path of the cloud path tracer, followed from a collision inside the layer back
//! towards the light, all orders of scattering:
//! - at every real collision x (delta tracking, Woodcock et al. 1965), next-event
//!   estimation of the sun: albedo p_w(nu) E_sun,w(x) T_cloud(x -> sun), with p_w the
//!   droplets' phase function at wavelength w (A_1 of Riley et al. 2004, Eq. 20), nu
//!   the cosine between the path's direction and the sun, E_sun the sun through the
//!   atmosphere and T_cloud the cloud's transmittance towards the sun by ratio tracking
//!   (Novak, Selle and Jarosz 2014);
//! - the path then scatters: a direction drawn from p_w exactly (`phase_sampler.rs`),
//!   the weight multiplied by the albedo. Each wavelength follows its own paths.
//! - where it leaves the layer it takes the light around the cloud from that direction
//!   (`environment.rs`: the sky model's radiance, the sun disk excluded, so the sun is
//!   counted once).
//!
//! Russian roulette ends paths whose weight has fallen below [`ROULETTE_WEIGHT`],
//! unbiased; a path of more than [`MAX_SCATTERINGS`] collisions is cut (none of the
//! layer's optical depths comes near it).

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

/// What every path of one view ray shares.
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

/// Where a free flight from inside the layer ends.
enum Flight {
    /// A real collision at this point.
    Collision(DVec3),
    /// Out of the layer.
    Escape,
}

/// A free flight from `x` along the unit `d` by delta tracking.
fn fly(layer: &CloudLayer, mut x: DVec3, d: DVec3, sampler: &mut Sampler) -> Flight {
    let majorant = layer.majorant();
    loop {
        let to_boundary = layer.distance_to_boundary(x, d);
        let free = if majorant > 0.0 {
            -(1.0 - sampler.uniform()).ln() / majorant
        } else {
            f64::INFINITY
        };
        if free >= to_boundary {
            return Flight::Escape;
        }
        x += d * free;
        if sampler.uniform() * majorant < layer.extinction(x) {
            return Flight::Collision(x);
        }
    }
}

/// The cloud's transmittance from `x` along the unit `d` to the layer's boundary, by
/// ratio tracking with Russian roulette below 0.01 (unbiased).
pub fn transmittance_to_boundary(
    layer: &CloudLayer,
    mut x: DVec3,
    d: DVec3,
    sampler: &mut Sampler,
) -> f64 {
    let majorant = layer.majorant();
    if majorant <= 0.0 {
        return 1.0;
    }
    let mut t = 1.0;
    loop {
        let to_boundary = layer.distance_to_boundary(x, d);
        let free = -(1.0 - sampler.uniform()).ln() / majorant;
        if free >= to_boundary {
            return t;
        }
        x += d * free;
        t *= 1.0 - (layer.extinction(x) / majorant).min(1.0);
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
pub fn trace_from(
    scene: &PathScene,
    environment: &Environment,
    w: usize,
    mut x: DVec3,
    mut d: DVec3,
    sampler: &mut Sampler,
) -> f64 {
    let layer = scene.layer;
    let phase = &scene.phases[w];
    let mut weight = 1.0;
    let mut score = 0.0;
    let mut light = vec![0.0; scene.sun.wavelengths()];
    for _ in 0..MAX_SCATTERINGS {
        let albedo = layer.single_scattering_albedo(x);
        let nu = d.dot(scene.sun_direction);
        scene.sun.irradiance(x, scene.sun_direction, &mut light);
        if light[w] > 0.0 {
            let t_cloud = transmittance_to_boundary(layer, x, scene.sun_direction, sampler);
            score += weight * albedo * scene.orders.distribution(w, 1, nu) * light[w] * t_cloud;
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
        match fly(layer, x, d, sampler) {
            Flight::Collision(y) => x = y,
            Flight::Escape => {
                environment.radiance(d, &mut light);
                return score + weight * light[w];
            }
        }
    }
    score
}
