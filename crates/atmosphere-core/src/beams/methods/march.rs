//! The per-pixel ray march with shadow maps, the common modern way and the baseline of
//! the beams methods: `steps` evenly spaced samples at the midpoints of equal pieces of
//! the ray up to its end, each light's visibility read from its shadow map
//! (`shadow_map.rs`), the integrand of `in_scattering.rs` summed. One loop over steps
//! and one over lights per pixel, no recursion: a shader's loop.

use crate::beams::error::BeamError;
use crate::beams::in_scattering::InScattering;
use crate::beams::methods::method::{BeamMethod, BeamSettings};
use crate::beams::ray::SceneRay;
use crate::beams::scene::BeamScene;
use crate::beams::shadow_map::ShadowMap;
use crate::models::options::Setting;

/// Samples along each ray.
pub const STEPS: Setting<usize> = Setting {
    model: "march",
    key: "steps",
    range: 1..=65_536,
};
/// Texels on a side of each shadow map (a point light has six).
pub const SHADOW_MAP_PX: Setting<usize> = Setting {
    model: "march",
    key: "shadow_map_px",
    range: 16..=8192,
};

/// The march's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarchSettings {
    pub steps: usize,
    pub shadow_map_px: usize,
}

impl Default for MarchSettings {
    fn default() -> Self {
        MarchSettings {
            steps: 128,
            shadow_map_px: 512,
        }
    }
}

/// The march, prepared for a scene: its shadow maps rendered.
#[derive(Debug)]
pub struct March {
    scattering: InScattering,
    shadow_maps: Vec<ShadowMap>,
    settings: MarchSettings,
}

impl March {
    /// The march for `scene`, its `steps` and `shadow_map_px` read from the options.
    pub fn new(scene: &BeamScene, settings: &BeamSettings) -> Result<March, BeamError> {
        let defaults = MarchSettings::default();
        let own = settings.options.read_settings(
            "march",
            |_: &MarchSettings| Ok(()),
            |r, _| {
                Ok(MarchSettings {
                    steps: r.count(&STEPS, defaults.steps)?,
                    shadow_map_px: r.count(&SHADOW_MAP_PX, defaults.shadow_map_px)?,
                })
            },
        )?;
        let shadow_maps = scene
            .lights
            .iter()
            .map(|l| ShadowMap::new(l, &scene.occluders, own.shadow_map_px))
            .collect();
        Ok(March {
            scattering: InScattering::new(scene, &settings.wavelengths_nm),
            shadow_maps,
            settings: own,
        })
    }

    /// The settings read from the options.
    pub fn settings(&self) -> MarchSettings {
        self.settings
    }

    /// The scene's lights and medium at the method's wavelengths.
    pub fn scattering(&self) -> &InScattering {
        &self.scattering
    }

    /// Each light's shadow map, in the scene's order.
    pub fn shadow_maps(&self) -> &[ShadowMap] {
        &self.shadow_maps
    }
}

impl BeamMethod for March {
    fn radiance(&self, ray: &SceneRay) -> Result<Vec<f64>, BeamError> {
        let n = self.scattering.wavelengths_nm.len();
        let t_end = self.scattering.ray_end_m(ray);
        let step = t_end / self.settings.steps as f64;
        let occluders = &self.scattering.scene.occluders;
        let mut visibility = |light: usize, point, path: &_| {
            self.shadow_maps[light].visibility(occluders, point, path)
        };
        let mut sum = vec![0.0; n];
        for i in 0..self.settings.steps {
            let t = (i as f64 + 0.5) * step;
            self.scattering.add_at(ray, t, &mut visibility, &mut sum);
        }
        Ok(sum.into_iter().map(|s| s * step).collect())
    }
}
