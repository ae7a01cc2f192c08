//! The cloud spheres of a renderer's frames, made on the CPU from the cover and kept
//! while nothing they depend on changes: the attenuation textures G_i hold one sun
//! (Dobashi, Yamamoto and Nishita 2002, section 5.4), so a new sun, new layer or sphere
//! settings, or a new cover (a new cache) remakes them; the same sun reuses them.

use std::sync::{Mutex, MutexGuard};

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;

use crate::clouds::spheres::sphere_inputs::SphereInputs;
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;

/// What the spheres were made for: the layer's settings, the spheres' own, the ground's
/// radius and the sun.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SphereKey {
    layer: LayerSettings,
    spheres: SphereSettings,
    bottom_radius_m: f64,
    sun: DVec3,
}

/// The spheres made for a key, on the CPU and on the GPU.
#[derive(Debug)]
pub struct MadeSpheres {
    key: SphereKey,
    pub spheres: CloudSpheres,
    pub inputs: SphereInputs,
}

/// The cover and the droplets' tables the spheres are made from, and the last spheres
/// made.
#[derive(Debug)]
pub struct SphereCache {
    cover: CoverGrid,
    orders: ScatteringOrders,
    made: Mutex<Option<MadeSpheres>>,
}

impl SphereCache {
    pub fn new(cover: CoverGrid, orders: ScatteringOrders) -> SphereCache {
        SphereCache {
            cover,
            orders,
            made: Mutex::new(None),
        }
    }

    /// The spheres of `layer` and `spheres` over a ground of `bottom_radius_m` with the
    /// unit `sun`, made now unless the last ones were made for the same.
    pub fn get(
        &self,
        gpu: &GpuContext,
        layer: &LayerSettings,
        spheres: &SphereSettings,
        bottom_radius_m: f64,
        sun: DVec3,
    ) -> Result<MutexGuard<'_, Option<MadeSpheres>>, RenderError> {
        // The resolution divisor is how a frame shades them, not what they are.
        let key = SphereKey {
            layer: *layer,
            spheres: SphereSettings {
                resolution_divisor: 1,
                ..*spheres
            },
            bottom_radius_m,
            sun,
        };
        let mut made = self
            .made
            .lock()
            .map_err(|_| RenderError::Frame("the cloud spheres' cache was poisoned".into()))?;
        if made.as_ref().is_some_and(|m| m.key == key) {
            return Ok(made);
        }
        *made = None;
        let frame_error =
            |e: atmosphere_core::clouds::error::CloudError| RenderError::Frame(e.to_string());
        // The spheres take the density of the layer's cover and profile; their light
        // takes A_1 from `orders`, so the layer's own phase function is not read.
        let phase =
            CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.0 }).map_err(frame_error)?;
        let field = CloudLayer::new(*layer, bottom_radius_m, self.cover.clone(), phase)
            .map_err(frame_error)?;
        let cloud_spheres = CloudSpheres::new(&field, spheres, sun).map_err(frame_error)?;
        let inputs = SphereInputs::new(gpu, &cloud_spheres, &self.orders)?;
        *made = Some(MadeSpheres {
            key,
            spheres: cloud_spheres,
            inputs,
        });
        Ok(made)
    }
}
