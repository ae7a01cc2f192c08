//! One view of the clouds section made ready to answer: its placed rays, its cover's
//! grid, the droplets' tables, the air model (the path tracer's, `probe_clouds.rs`'s
//! `AIR_MODEL`, which every method runs on too, so that the differences are the
//! cloud's) and the layer the reference traces.

use anyhow::Context;
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};

use crate::cloud_rays::{CloudAnswer, CloudRays};
use crate::probe_clouds::{AIR_MODEL, air_settings};
use crate::report::clouds_views::CloudView;

/// A view, its rays and what answers them.
pub struct ViewScene {
    pub view: CloudView,
    pub rays: Vec<ViewRay>,
    atmosphere: Atmosphere,
    cover: CoverGrid,
    orders: ScatteringOrders,
    air: Box<dyn SkyModel>,
    traced: CloudRays,
}

impl std::fmt::Debug for ViewScene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ViewScene")
            .field("view", &self.view)
            .field("rays", &self.rays.len())
            .finish_non_exhaustive()
    }
}

impl ViewScene {
    /// `view` with the droplets' `orders` at the wavelengths of `settings`.
    pub fn new(
        view: CloudView,
        settings: &ModelSettings,
        orders: &ScatteringOrders,
    ) -> anyhow::Result<ViewScene> {
        let atmosphere = Atmosphere::preset(view.camera.atmosphere)?;
        let air = prepare(AIR_MODEL, &atmosphere, &air_settings(settings))?;
        let cover = view.cover.grid()?;
        let traced = CloudRays::new(
            view.cloud,
            cover.clone(),
            orders.clone(),
            &atmosphere,
            air.as_ref(),
        )
        .with_context(|| format!("view {}", view.id()))?
        .shading_air(view.shafts, &atmosphere, air.as_ref());
        Ok(ViewScene {
            rays: view.rays()?,
            view,
            atmosphere,
            cover,
            orders: orders.clone(),
            air,
            traced,
        })
    }

    pub fn air(&self) -> &dyn SkyModel {
        self.air.as_ref()
    }

    pub fn atmosphere(&self) -> &Atmosphere {
        &self.atmosphere
    }

    pub fn cover(&self) -> &CoverGrid {
        &self.cover
    }

    /// The view's cloud marched with the march settings of `march` (its method,
    /// steps, sun light, octaves and stops; the cloud itself stays the view's).
    pub fn cloud_with(&self, march: &LayerSettings) -> LayerSettings {
        LayerSettings {
            base_m: self.view.cloud.base_m,
            thickness_m: self.view.cloud.thickness_m,
            extinction_per_m: self.view.cloud.extinction_per_m,
            albedo: self.view.cloud.albedo,
            coverage_scale: self.view.cloud.coverage_scale,
            detail_scale_m: self.view.cloud.detail_scale_m,
            detail_strength: self.view.cloud.detail_strength,
            ..*march
        }
    }

    /// The rays of the layer marched with `march`'s settings ([`ViewScene::cloud_with`]).
    pub fn marched(&self, march: &LayerSettings) -> anyhow::Result<CloudRays> {
        let rays = CloudRays::new(
            self.cloud_with(march),
            self.cover.clone(),
            self.orders.clone(),
            &self.atmosphere,
            self.air(),
        )?;
        Ok(rays.shading_air(self.view.shafts, &self.atmosphere, self.air()))
    }

    /// The path tracer's answer for `ray`, to the view's stopping rule.
    pub fn reference(&self, ray: &ViewRay) -> anyhow::Result<CloudAnswer> {
        Ok(self.traced.reference(self.air(), ray, &self.view.paths)?)
    }
}
