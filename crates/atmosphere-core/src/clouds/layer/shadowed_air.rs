//! A sky model whose air below the cloud layer's base lies in the cloud's shadow: the
//! model's answers less the single scattering the cloud takes out there
//! ([`CloudAirShadow::radiance`]), so that what composites a cloud with a model's air
//! (`composite.rs`'s `L_front + T_front L_cloud + T_cloud (L_full - L_front)`, the path
//! tracer's view ray) takes the air as frames shade it (`air_shadow.rs`).

use super::air_shadow::{AirShadow, CloudAirShadow};
use crate::atmosphere::Atmosphere;
use crate::models::error::ModelError;
use crate::models::model_base::ModelBase;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};

/// `model`'s air in the shadow `air`, marched through `shadow`'s medium.
#[derive(Clone, Copy)]
pub struct ShadowedAir<'a> {
    pub model: &'a dyn SkyModel,
    pub shadow: &'a CloudAirShadow,
    pub air: AirShadow<'a>,
}

impl std::fmt::Debug for ShadowedAir<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ShadowedAir")
            .field("model", &self.model.id())
            .field("air", &self.air)
            .finish()
    }
}

impl SkyModel for ShadowedAir<'_> {
    fn base(&self) -> &ModelBase {
        self.model.base()
    }

    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError> {
        self.shadow.radiance(self.model, ray, &self.air)
    }

    /// The model's: the cloud's shadow on a surface is the sun map's business
    /// (`shadowed_surface.rs`).
    fn surface_irradiance(&self, surface: &SurfacePoint) -> Result<Vec<f64>, ModelError> {
        self.model.surface_irradiance(surface)
    }

    fn table_bytes(&self) -> usize {
        self.model.table_bytes()
    }

    fn update(&mut self, _atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError> {
        Err(ModelError::Unsupported {
            model: self.id(),
            what: "update through the cloud's shadow in its air (update the model itself)",
        })
    }
}
