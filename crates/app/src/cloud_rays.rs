//! Rays through the planet's cloud layer, answered by a sky model with the layer's
//! march (the CPU composite the frames' cloud steps are the twin of,
//! `clouds/layer/composite.rs`) or by the cloud path tracer (`clouds/reference/`), so
//! that `atmos probe --clouds` and `atmos report`'s clouds section ask both the same
//! rays over the same cover (docs/clouds.md, "The path-traced reference on the planet").
//!
//! The path tracer walks the layer's finest field (all `detail_octaves`, 3); a method
//! marches the field of its own settings (the interactive preset's one octave). The
//! same field as Dobashi, Yamamoto and Nishita 2002's cloud spheres (section 5.4;
//! `clouds/spheres/`) answers through `radiance_with_spheres`, and the spheres' share
//! of a ray whose camera stands in the hand-over band is blended with the layer's as
//! frames blend them (`clouds/spheres/handover.rs`).

use anyhow::Context;
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::air_shadow::{AirShadow, CloudAirShadow, CloudShade};
use atmosphere_core::clouds::layer::composite::radiance_with_cloud_segment;
use atmosphere_core::clouds::layer::direct_shade::DirectCloudShade;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::orders::{ANGLES, ScatteringOrders};
use atmosphere_core::clouds::layer::settings::{LayerSettings, MAX_DETAIL_OCTAVES};
use atmosphere_core::clouds::layer::shadowed_air::ShadowedAir;
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::reference::camera_path::PathScene;
use atmosphere_core::clouds::reference::phase_sampler::PhaseTableSampler;
use atmosphere_core::clouds::reference::ray::radiance_path_traced;
use atmosphere_core::clouds::reference::settings::PathSettings;
use atmosphere_core::clouds::reference::sun_light::SunThroughAtmosphere;
use atmosphere_core::clouds::spheres::composite::{radiance_with_spheres, spheres_only};
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use atmosphere_core::clouds::spheres::handover::{CloudForm, sphere_weight};
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::models::error::ModelError;
use atmosphere_core::models::sky_model::{RayRadiance, SkyModel, ViewRay};
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;

/// One ray's answer with the cloud.
#[derive(Clone, Debug, PartialEq)]
pub struct CloudAnswer {
    pub radiance: RayRadiance,
    /// The cloud's transmittance along the ray (1 where it misses the layer).
    pub cloud_transmittance: f64,
    /// Paths the path tracer followed; `None` for a method.
    pub paths: Option<u64>,
}

/// The layer as a method marches it and as the path tracer walks it.
#[derive(Debug)]
pub struct CloudRays {
    layer: CloudLayer,
    finest: CloudLayer,
    orders: ScatteringOrders,
    phases: Vec<PhaseTableSampler>,
    sun: SunThroughAtmosphere,
    /// The medium of the cloud's shadow in the air below the base, when the rays take
    /// it ([`CloudRays::shading_air`]).
    air_shadow: Option<CloudAirShadow>,
}

/// The sun maps of a frame whose camera stands at a ray's origin: the one its layer is
/// lit by (`sun_light = map`), and the one of the cloud's shadow in the air.
#[derive(Debug, Default)]
pub struct RayMaps {
    pub light: Option<CloudSunMap>,
    pub air: Option<CloudSunMap>,
}

impl CloudRays {
    /// The layer of `settings` over `cover` on `atmosphere`'s planet; `orders` (A_n and
    /// F_n) at the wavelengths of `sky`, the model whose spectra light the path tracer.
    pub fn new(
        settings: LayerSettings,
        cover: CoverGrid,
        orders: ScatteringOrders,
        atmosphere: &Atmosphere,
        sky: &dyn SkyModel,
    ) -> anyhow::Result<CloudRays> {
        if orders.wavelengths() != sky.wavelengths_nm().len() {
            anyhow::bail!(
                "cloud phase tables for {} wavelengths, the model answers {}",
                orders.wavelengths(),
                sky.wavelengths_nm().len()
            );
        }
        // The layer's own phase function (the march reads `orders` instead): the middle
        // wavelength's A_1.
        let middle = &orders.table(orders.wavelengths() / 2)[..ANGLES];
        let angles_deg = (0..ANGLES)
            .map(|k| k as f64 * 180.0 / (ANGLES - 1) as f64)
            .collect();
        let phase = CloudPhase::new(PhaseFunction::Tabulated {
            angles_deg,
            values: middle.to_vec(),
        })?;
        let radius = atmosphere.bottom_radius_m;
        let finest_settings = LayerSettings {
            detail_octaves: MAX_DETAIL_OCTAVES,
            ..settings
        };
        Ok(CloudRays {
            layer: CloudLayer::new(settings, radius, cover.clone(), phase.clone())
                .context("cloud layer")?,
            finest: CloudLayer::new(finest_settings, radius, cover, phase)
                .context("cloud layer")?,
            phases: (0..orders.wavelengths())
                .map(|w| PhaseTableSampler::new(&orders, w))
                .collect(),
            orders,
            sun: SunThroughAtmosphere::new(atmosphere, sky.spectra()),
            air_shadow: None,
        })
    }

    /// These rays with the cloud's shadow in the air below the base when `shafts`, as
    /// frames shade it (docs/clouds.md, "Cloud shadows in the air"): a method's air from
    /// the frame's sun map, the path tracer's from the field itself (`direct_shade.rs`),
    /// through `atmosphere` at `sky`'s wavelengths.
    pub fn shading_air(
        mut self,
        shafts: bool,
        atmosphere: &Atmosphere,
        sky: &dyn SkyModel,
    ) -> CloudRays {
        self.air_shadow = shafts.then(|| CloudAirShadow::new(atmosphere, sky));
        self
    }

    /// `model` with its air in the shadow of `shade`, when the rays take the shadow and
    /// a shade is given.
    fn shaded<'a>(
        &'a self,
        model: &'a dyn SkyModel,
        shade: Option<&'a dyn CloudShade>,
    ) -> Option<ShadowedAir<'a>> {
        let (shadow, clouds) = (self.air_shadow.as_ref()?, shade?);
        Some(ShadowedAir {
            model,
            shadow,
            air: AirShadow {
                terrain: None,
                clouds,
            },
        })
    }

    pub fn settings(&self) -> &LayerSettings {
        self.layer.settings()
    }

    /// The planet's radius under the layer, m.
    pub fn ground_radius_m(&self) -> f64 {
        self.layer.shell().ground_radius_m
    }

    /// The sun maps of a frame whose camera is at `camera_m` with the unit `sun`: the
    /// one it lights its layer with when the layer is lit by the map
    /// (`SunMapResolution::LIT`), and the one of the shadow in the air when the rays
    /// take it (one level, as frames without a surface make it).
    pub fn maps(&self, camera_m: DVec3, sun: DVec3) -> anyhow::Result<RayMaps> {
        use atmosphere_core::clouds::layer::settings::SunLight;
        let map = |resolution: SunMapResolution| -> anyhow::Result<CloudSunMap> {
            let grid = CloudSunMap::grid_for(self.layer.shell(), camera_m, &resolution)?;
            Ok(CloudSunMap::new(&self.layer, grid, sun, &resolution)?)
        };
        let lit = self.settings().sun_light == SunLight::Map;
        let air = SunMapResolution {
            levels: 1,
            ..SunMapResolution::default()
        };
        Ok(RayMaps {
            light: lit.then(|| map(SunMapResolution::LIT)).transpose()?,
            air: self.air_shadow.as_ref().map(|_| map(air)).transpose()?,
        })
    }

    /// `ray` by `model` with the layer's march; `sun_map` is [`CloudRays::sun_map`] at
    /// the ray's origin when the layer is lit by it.
    pub fn method(
        &self,
        model: &dyn SkyModel,
        ray: &ViewRay,
        sun_map: Option<&CloudSunMap>,
    ) -> Result<CloudAnswer, ModelError> {
        let (radiance, segment) =
            radiance_with_cloud_segment(model, &self.layer, &self.orders, ray, sun_map)?;
        Ok(CloudAnswer {
            radiance,
            cloud_transmittance: segment.map_or(1.0, |s| s.transmittance[0]),
            paths: None,
        })
    }

    /// `ray` by the path tracer through the finest field, with `air` the sky model in
    /// front of, behind and around the cloud, the view ray's own air in the field's
    /// shadow when the rays take it.
    pub fn reference(
        &self,
        air: &dyn SkyModel,
        ray: &ViewRay,
        paths: &PathSettings,
    ) -> Result<CloudAnswer, ModelError> {
        let direct = DirectCloudShade::reference(&self.finest);
        let shaded = self.shaded(air, Some(&direct));
        let scene = PathScene {
            layer: &self.finest,
            orders: &self.orders,
            phases: &self.phases,
            sun: &self.sun,
            sky: air,
            view_air: shaded.as_ref().map(|s| s as &dyn SkyModel),
            sun_direction: ray.sun_direction.normalize(),
        };
        let traced = radiance_path_traced(&scene, ray, paths)?;
        Ok(CloudAnswer {
            radiance: traced.radiance,
            cloud_transmittance: traced.cloud_transmittance,
            paths: Some(traced.paths),
        })
    }

    /// The cloud spheres of the layer lit by the unit `sun`, with frames' settings
    /// (`SphereSettings::default`: 5 spheres, attenuation textures 1024 x 512).
    pub fn spheres(&self, sun: DVec3) -> anyhow::Result<CloudSpheres> {
        CloudSpheres::new(&self.layer, &SphereSettings::default(), sun).context("cloud spheres")
    }

    /// `ray` by `model` with the cloud `spheres` ([`CloudRays::spheres`] of the ray's
    /// sun); `T_cloud` is the product of the crossings' transmittances.
    pub fn with_spheres(
        &self,
        model: &dyn SkyModel,
        ray: &ViewRay,
        spheres: &CloudSpheres,
    ) -> Result<CloudAnswer, ModelError> {
        let radiance = radiance_with_spheres(model, spheres, &self.orders, ray)?;
        // The transmittance does not depend on the light: none is given.
        let dark = CloudLight {
            sun_direction: ray.sun_direction.normalize(),
            sun_irradiance: vec![0.0; self.orders.wavelengths()],
            sky_irradiance: vec![0.0; self.orders.wavelengths()],
            up: ray.origin_m.normalize(),
        };
        let (segment, _) = spheres_only(
            spheres,
            &self.orders,
            &dark,
            ray.origin_m,
            ray.direction.normalize(),
            ray.max_distance_m.unwrap_or(f64::INFINITY),
        );
        Ok(CloudAnswer {
            radiance,
            cloud_transmittance: segment.transmittance[0],
            paths: None,
        })
    }

    /// `ray` by `model` in the cloud's `form`: the layer's march, the spheres, or
    /// (`auto`) both blended by the spheres' weight at the ray origin's altitude, as
    /// frames blend the two images; `spheres` must be given where the weight is not 0.
    /// `maps` are [`CloudRays::maps`] at the ray's origin; with the shadow in the air,
    /// the model's air is shaded by `maps.air`.
    pub fn in_form(
        &self,
        model: &dyn SkyModel,
        ray: &ViewRay,
        form: CloudForm,
        maps: &RayMaps,
        spheres: Option<&CloudSpheres>,
    ) -> Result<CloudAnswer, ModelError> {
        let shaded = self.shaded(model, maps.air.as_ref().map(|m| m as &dyn CloudShade));
        let model = shaded.as_ref().map_or(model, |s| s as &dyn SkyModel);
        let sun_map = maps.light.as_ref();
        let altitude_m = ray.origin_m.length() - self.ground_radius_m();
        let w = sphere_weight(form, altitude_m);
        if w <= 0.0 {
            return self.method(model, ray, sun_map);
        }
        let spheres = spheres.ok_or_else(|| {
            ModelError::Settings("the cloud spheres were not made for this ray's sun".into())
        })?;
        let seen = self.with_spheres(model, ray, spheres)?;
        if w >= 1.0 {
            return Ok(seen);
        }
        Ok(blend(&self.method(model, ray, sun_map)?, &seen, w))
    }
}

/// (1 - w) a + w b in radiance and transmittance.
fn blend(a: &CloudAnswer, b: &CloudAnswer, w: f64) -> CloudAnswer {
    let mix = |x: &[f64], y: &[f64]| -> Vec<f64> {
        x.iter()
            .zip(y)
            .map(|(x, y)| (1.0 - w) * x + w * y)
            .collect()
    };
    CloudAnswer {
        radiance: RayRadiance {
            radiance: mix(&a.radiance.radiance, &b.radiance.radiance),
            transmittance: mix(&a.radiance.transmittance, &b.radiance.transmittance),
            radiance_std_error: mix(
                &a.radiance.radiance_std_error,
                &b.radiance.radiance_std_error,
            ),
        },
        cloud_transmittance: (1.0 - w) * a.cloud_transmittance + w * b.cloud_transmittance,
        paths: None,
    }
}
