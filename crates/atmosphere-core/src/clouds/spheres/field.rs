//! The cloud spheres of one frame: the shells, their cloud textures and the attenuation
//! textures of the frame's sun, and the light one crossing of a view ray through a shell
//! sends towards the camera.
//!
//! Dobashi, Yamamoto and Nishita 2002, section 5.4 draw each sphere as a thin layer of
//! opacity alpha_i from its cloud texture, coloured by the sun times the attenuation
//! texture G_i times the droplets' phase function. Here a crossing of shell k of length
//! l has the view optical depth tau_v = sigma_k l (sigma_k the shell's mean extinction,
//! `cloud_textures.rs`), so alpha = 1 - exp(-tau_v), and its light is integrated over
//! the crossing, not taken at the sphere: the sun's optical depth at a point p of the
//! shell is G_k(p) - sigma_k l_s(p_k) + sigma_k l_s(p), with l_s the distance from a
//! point along the sun to the shell's outer sphere and p_k the point of sphere k under
//! p (the texel's own path through the shell swapped for p's), taken linearly between
//! the crossing's ends, tau_a to tau_b. With Wrenninge et al. 2013's octaves (the
//! layer's `octaves`, weights a^i, b^i, c^i of `layer/march.rs`), each octave's
//! integral is in closed form:
//!     L_sun = albedo E_sun sum_i w_i exp(-b^i tau_a) tau_v E(tau_v + b^i (tau_b - tau_a)),
//!     w_i = a^i (c^i A_1(theta) + (1 - c^i) / (4 pi)),  E(k) = (1 - exp(-k)) / k,
//! A_1 the droplets' phase function (Riley et al. 2004's first order). One octave at a
//! point is the paper's G_i times the phase function. The sky's light is the layer's
//! (`layer/march.rs`): isotropic from above, E_sky / (2 pi) per steradian, dimmed by the
//! local extinction times the distance up to the layer's top, here sigma_k (R_top - r),
//! taken linearly between the crossing's ends (u_a to u_b) and integrated the same way:
//!     L_sky = albedo E_sky / (2 pi) exp(-u_a) tau_v E(tau_v + u_b - u_a).

use glam::DVec3;

use super::attenuation::{AttenuationTextures, SHADOWED_DEPTH};
use super::cloud_textures::CloudTextures;
use super::crossing::{ShellSegment, SphereCrossing};
use super::settings::SphereSettings;
use super::shells::{Crossing, Shells, roots};
use super::slab_light::{SlabColumn, shade_slab};
use crate::clouds::error::CloudError;
use crate::clouds::layer::field::CloudLayer;
use crate::clouds::layer::march::{CloudLight, OCTAVE_A, OCTAVE_B, OCTAVE_C};
use crate::clouds::layer::orders::ScatteringOrders;
use crate::clouds::layer::settings::LayerMethod;

/// The spheres of a layer, lit by one sun.
#[derive(Clone, Debug)]
pub struct CloudSpheres {
    shells: Shells,
    clouds: CloudTextures,
    attenuation: AttenuationTextures,
    albedo: f64,
    octaves: u32,
    method: LayerMethod,
    extinction_per_m: f64,
}

impl CloudSpheres {
    /// The `settings.count` spheres of `layer`'s cloud with the attenuation textures of
    /// the unit, planet-fixed `sun_direction`; settings out of range are refused by name.
    pub fn new(
        layer: &CloudLayer,
        settings: &SphereSettings,
        sun_direction: DVec3,
    ) -> Result<CloudSpheres, CloudError> {
        settings.check()?;
        let shell = layer.shell();
        let shells = Shells {
            ground_radius_m: shell.ground_radius_m,
            base_radius_m: shell.base_radius_m,
            thickness_m: layer.settings().thickness_m,
            count: settings.count,
        };
        let clouds = CloudTextures::new(layer, &shells)?;
        let attenuation = AttenuationTextures::render(&shells, &clouds, sun_direction, settings)?;
        Ok(CloudSpheres {
            shells,
            clouds,
            attenuation,
            albedo: layer.settings().albedo,
            octaves: layer.settings().octaves,
            method: layer.settings().method,
            extinction_per_m: layer.settings().extinction_per_m,
        })
    }

    pub fn shells(&self) -> &Shells {
        &self.shells
    }

    pub fn clouds(&self) -> &CloudTextures {
        &self.clouds
    }

    pub fn attenuation(&self) -> &AttenuationTextures {
        &self.attenuation
    }

    pub fn albedo(&self) -> f64 {
        self.albedo
    }

    pub fn octaves(&self) -> u32 {
        self.octaves
    }

    /// The layer's method: the slab methods shade by their slab (`slab_light.rs`), the
    /// others by the octaves.
    pub fn method(&self) -> LayerMethod {
        self.method
    }

    /// The layer's densest extinction, m^-1 (at full cover, no erosion).
    pub fn extinction_per_m(&self) -> f64 {
        self.extinction_per_m
    }

    /// The light `crossing` of the ray from `origin` along the unit `direction` sends
    /// towards its start, and its transmittance, lit by `light` (the module's
    /// equations, or `slab_light.rs`'s under a slab method), with the droplets' tables
    /// `orders`.
    pub fn shade(
        &self,
        origin: DVec3,
        direction: DVec3,
        crossing: &Crossing,
        light: &CloudLight,
        orders: &ScatteringOrders,
    ) -> SphereCrossing {
        let k = crossing.shell;
        let start = origin + direction * crossing.t0;
        let end = origin + direction * crossing.t1;
        let middle = (start + end) / 2.0;
        let sigma = self.clouds.extinction(k, middle);
        let waves = light.sun_irradiance.len();
        if sigma <= 0.0 {
            return SphereCrossing::clear(waves);
        }
        if self.method.is_slab() {
            let segment = ShellSegment {
                shell: k,
                start,
                end,
                direction,
                extinction: sigma,
            };
            return shade_slab(self, &segment, light, orders);
        }
        let tau_v = sigma * (crossing.t1 - crossing.t0);
        let sun = light.sun_direction;
        let tau_a = self.sun_depth_at(k, start, sigma, sun);
        let tau_b = self.sun_depth_at(k, end, sigma, sun);
        let top = self.shells.base_radius_m + self.shells.thickness_m;
        let (up_a, up_b) = (
            sigma * (top - start.length()).max(0.0),
            sigma * (top - end.length()).max(0.0),
        );
        let sky =
            (-up_a).exp() * tau_v * exp_ratio(tau_v + up_b - up_a) / (2.0 * std::f64::consts::PI);
        let nu = direction.dot(sun);
        let isotropic = 1.0 / (4.0 * std::f64::consts::PI);
        let radiance = (0..waves)
            .map(|w| {
                let single = orders.distribution(w, 1, nu);
                let sun_part: f64 = (0..self.octaves as i32)
                    .map(|i| {
                        let (a, b, c) = (OCTAVE_A.powi(i), OCTAVE_B.powi(i), OCTAVE_C.powi(i));
                        let weight = a * (c * single + (1.0 - c) * isotropic);
                        weight * (-b * tau_a).exp() * tau_v * exp_ratio(tau_v + b * (tau_b - tau_a))
                    })
                    .sum();
                self.albedo * (light.sun_irradiance[w] * sun_part + light.sky_irradiance[w] * sky)
            })
            .collect();
        SphereCrossing {
            radiance,
            scaled_radiance: vec![0.0; waves],
            transmittance: vec![(-tau_v).exp(); waves],
            scaled_transmittance: vec![(-tau_v).exp(); waves],
        }
    }

    /// The sun's optical depth at `point` inside shell `k` of mean extinction `sigma`:
    /// the attenuation texture at the sphere under it, its own path through the shell
    /// swapped for the point's.
    fn sun_depth_at(&self, k: usize, point: DVec3, sigma: f64, sun: DVec3) -> f64 {
        let g = self.attenuation.depth(k, point);
        if g >= SHADOWED_DEPTH {
            return SHADOWED_DEPTH;
        }
        let sphere = point.normalize() * self.shells.sphere_radius_m(k);
        let outer = self.shells.bounds_m(k).1;
        let path = |p: DVec3| {
            let r = p.length();
            roots(r, p.dot(sun) / r, outer).map_or(0.0, |(_, far)| far.max(0.0))
        };
        (g + sigma * (path(point) - path(sphere))).clamp(0.0, SHADOWED_DEPTH)
    }
}

impl SlabColumn for CloudSpheres {
    fn method(&self) -> LayerMethod {
        self.method
    }

    fn albedo(&self) -> f64 {
        self.albedo
    }

    fn inner_radius_m(&self, k: usize) -> f64 {
        self.shells.bounds_m(k).0
    }

    fn sun_depth_at(&self, k: usize, point: DVec3, sigma: f64, sun: DVec3) -> f64 {
        CloudSpheres::sun_depth_at(self, k, point, sigma, sun)
    }

    fn depth_below(&self, k: usize, point: DVec3) -> f64 {
        (0..k).map(|j| self.clouds.depth(j, point)).sum()
    }
}

/// (1 - exp(-k)) / k, 1 at k = 0 (its series below 1e-4 in magnitude).
pub fn exp_ratio(k: f64) -> f64 {
    if k.abs() < 1e-4 {
        1.0 - k / 2.0
    } else {
        -(-k).exp_m1() / k
    }
}
