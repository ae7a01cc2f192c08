//! The light a beams scene's medium scatters toward the camera per metre of a view ray:
//! the integrand of Dobashi et al. 2002 Eq. 2-3 summed over the lights,
//!
//!   sigma_s F(alpha) I_l(lambda) H exp(-sigma_t (s + t)) / s^2,
//!
//! with I_l the light's emission times its light map and spot profile, s the path of
//! the light to the point (its inverse square dropped for a parallel light), t the
//! distance from the camera and H the visibility the method supplies (exact shadow rays,
//! a shadow map). Every method integrates this along the ray its own way.

use glam::DVec3;

use crate::beams::light::{Light, LightPath};
use crate::beams::light_map::channel_weights;
use crate::beams::medium::MediumSpectra;
use crate::beams::ray::SceneRay;
use crate::beams::scene::BeamScene;

/// The optical depth past which a ray's light is taken as extinguished: exp(-20.7) is
/// 1e-9, so the radiance left beyond is below a billionth of the light reaching there.
pub const EXTINGUISHED_OPTICAL_DEPTH: f64 = 20.7;

/// A scene's lights and medium at a method's wavelengths.
#[derive(Clone, Debug, PartialEq)]
pub struct InScattering {
    pub scene: BeamScene,
    pub wavelengths_nm: Vec<f64>,
    pub medium: MediumSpectra,
    /// Each light's emission at each wavelength.
    pub emission: Vec<Vec<f64>>,
    /// The weights of a light map's red, green and blue at each wavelength.
    pub channel_weights: Vec<[f64; 3]>,
}

impl InScattering {
    /// `scene` at `wavelengths_nm`.
    pub fn new(scene: &BeamScene, wavelengths_nm: &[f64]) -> InScattering {
        InScattering {
            medium: scene.medium.at(wavelengths_nm),
            emission: scene
                .lights
                .iter()
                .map(|l| wavelengths_nm.iter().map(|&w| l.emission.at(w)).collect())
                .collect(),
            channel_weights: wavelengths_nm.iter().map(|&w| channel_weights(w)).collect(),
            wavelengths_nm: wavelengths_nm.to_vec(),
            scene: scene.clone(),
        }
    }

    /// Where the integral along `ray` ends, m: its given distance, the first occluder,
    /// or where the medium has extinguished the light (0 in a medium that neither
    /// scatters nor absorbs, where nothing is scattered).
    pub fn ray_end_m(&self, ray: &SceneRay) -> f64 {
        let thinnest = self.medium.thinnest_extinction_per_m();
        let extinguished = if thinnest.is_finite() {
            EXTINGUISHED_OPTICAL_DEPTH / thinnest
        } else {
            0.0
        };
        let end = ray
            .max_distance_m
            .unwrap_or(f64::INFINITY)
            .min(extinguished);
        self.scene
            .occluders
            .nearest(ray.origin_m, ray.direction, end)
            .unwrap_or(end)
    }

    /// Adds to `out` (one value per wavelength, W m^-3 sr^-1 nm^-1) the light scattered
    /// toward the camera at distance `t_m` along `ray`, each light weighted by
    /// `visibility(light index, point, path)` in [0, 1].
    pub fn add_at(
        &self,
        ray: &SceneRay,
        t_m: f64,
        visibility: &mut impl FnMut(usize, DVec3, &LightPath) -> f64,
        out: &mut [f64],
    ) {
        let point = ray.at(t_m);
        for (i, light) in self.scene.lights.iter().enumerate() {
            let Some(path) = light.path_from(point) else {
                continue;
            };
            let seen = visibility(i, point, &path);
            if seen <= 0.0 {
                continue;
            }
            let phase = self
                .scene
                .medium
                .phase
                .eval(path.to_light.dot(ray.direction));
            let common = phase * path.factor() * seen;
            let map = light_map_rgb(light, &path);
            let emission = &self.emission[i];
            for k in 0..out.len() {
                let filter = self.filter(map, k);
                let extinction = self.medium.extinction_per_m[k];
                out[k] += self.medium.scattering_per_m[k]
                    * emission[k]
                    * common
                    * filter
                    * (-extinction * (path.distance_m + t_m)).exp();
            }
        }
    }

    /// The transmission of a light map's linear RGB (none: 1) at wavelength `k`.
    pub fn filter(&self, rgb: Option<[f64; 3]>, k: usize) -> f64 {
        rgb.map_or(1.0, |rgb| {
            let w = self.channel_weights[k];
            w[0] * rgb[0] + w[1] * rgb[1] + w[2] * rgb[2]
        })
    }

    /// Exact visibility: a shadow ray from the point toward the light, tested against
    /// every occluder.
    pub fn shadow_ray(&self, point: DVec3, path: &LightPath) -> f64 {
        if self
            .scene
            .occluders
            .blocks(point, path.to_light, path.distance_m)
        {
            0.0
        } else {
            1.0
        }
    }
}

/// The light map's linear RGB where the path leaves the light, if it has a map.
pub fn light_map_rgb(light: &Light, path: &LightPath) -> Option<[f64; 3]> {
    let (u, v, wrap) = path.map_uv;
    light.light_map.as_ref().map(|m| m.sample(u, v, wrap))
}
