//! `atmos probe --terrain`: the probe's rays placed over the Earth's relief, so that the
//! terrain's shadow in the air (light shafts, docs/shafts.md) reaches them, and the
//! reference and the models answer the same rays.
//!
//! Each ray of the probe's local frame (`ViewRay::from_angles`: the camera above the
//! local vertical, the sun at `view_sun_azimuth_deg` from the view) is turned so that the
//! sun stands at the geographic azimuth `--sun-azimuth-deg` (from north towards east) and
//! the view at that azimuth plus `view_sun_azimuth_deg`, then moved to `--latitude-deg`,
//! `--longitude-deg`. The relief is the terrain pass's (the built-in height map, refined,
//! at true scale, the sea surface at 0); a ray that meets it ends there, as a pixel's
//! ray ends on the terrain (`HeightFieldShadow::first_hit_m`; no light of the surface
//! itself is added, by the models or the reference). The reference tests the sun's visibility by the
//! exact march through the relief at each quadrature node
//! (`Reference::radiance_shadowed`); hillaire, nishita, oneil and bruneton get the shadow
//! map a frame with its camera at the ray's origin would have (`FrameShadow`).

use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, bail};
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::bruneton::Bruneton;
use atmosphere_core::models::dobashi::{Dobashi, DobashiSettings};
use atmosphere_core::models::error::ModelError;
use atmosphere_core::models::hillaire::{Hillaire, HillaireSettings};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::nishita::{Nishita, NishitaSettings};
use atmosphere_core::models::oneil::{Oneil, OneilSettings};
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance, SkyModel, ViewRay};
use atmosphere_core::reference::Reference;
use atmosphere_core::shafts::{HeightFieldShadow, ShadowMap};
use glam::DQuat;
use render_wgpu::frame::location_rotation;
use render_wgpu::shafts::terrain::frame_map::FrameShadow;
use render_wgpu::terrain::EarthData;
use render_wgpu::terrain::refined_heights::RefinedHeights;
use render_wgpu::terrain::surface::TerrainSurface;

use crate::location_flags::check_lat_lon;
use crate::progress::map_with_progress;

/// Where the rays stand and where the sun is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TerrainPlace {
    pub latitude_deg: f64,
    pub longitude_deg: f64,
    /// The sun's geographic azimuth, degrees from north towards east, in [-360, 360].
    pub sun_azimuth_deg: f64,
}

impl TerrainPlace {
    /// The place of the flags; errors name the flag and its range.
    pub fn new(
        latitude_deg: f64,
        longitude_deg: f64,
        sun_azimuth_deg: f64,
    ) -> anyhow::Result<Self> {
        let (latitude_deg, longitude_deg) = check_lat_lon(latitude_deg, longitude_deg)?;
        if !(sun_azimuth_deg.is_finite() && (-360.0..=360.0).contains(&sun_azimuth_deg)) {
            bail!("--sun-azimuth-deg {sun_azimuth_deg} must lie in [-360, 360]");
        }
        Ok(TerrainPlace {
            latitude_deg,
            longitude_deg,
            sun_azimuth_deg,
        })
    }

    /// `ray` of the probe's local frame placed here (see the module's documentation).
    pub fn placed(&self, ray: &ViewRay) -> ViewRay {
        // Angles from the local x axis towards y are geographic azimuths the other way
        // (`location_rotation`): turn the sun's local azimuth to the flag's.
        let sun_local = ray.sun_direction.y.atan2(ray.sun_direction.x);
        let turn = DQuat::from_rotation_z(-self.sun_azimuth_deg.to_radians() - sun_local);
        let rotation = location_rotation(self.latitude_deg, self.longitude_deg) * turn;
        ViewRay {
            origin_m: rotation * ray.origin_m,
            direction: rotation * ray.direction,
            sun_direction: rotation * ray.sun_direction,
            max_distance_m: ray.max_distance_m,
        }
    }
}

/// A model whose view rays see the terrain's shadow.
enum Shafted {
    Reference(Box<Reference>),
    Hillaire(Box<Hillaire>),
    Nishita(Box<Nishita>),
    Oneil(Box<Oneil>),
    Bruneton(Box<Bruneton>),
    Dobashi(Box<Dobashi>),
}

impl Shafted {
    fn prepare(id: ModelId, a: &Atmosphere, s: &ModelSettings) -> anyhow::Result<Shafted> {
        let options = &s.options;
        Ok(match id {
            ModelId::Reference => Shafted::Reference(Box::new(Reference::prepare(a, s)?)),
            ModelId::Hillaire => {
                let settings = HillaireSettings::from_options(options)?;
                Shafted::Hillaire(Box::new(Hillaire::prepare(a, s, settings)?))
            }
            ModelId::Nishita => {
                let settings = NishitaSettings::from_options(options)?;
                Shafted::Nishita(Box::new(Nishita::prepare(a, s, settings)?))
            }
            ModelId::Oneil => {
                let settings = OneilSettings::from_options(options)?;
                Shafted::Oneil(Box::new(Oneil::prepare(a, s, settings)?))
            }
            ModelId::Bruneton => Shafted::Bruneton(Box::new(Bruneton::prepare(a, s)?)),
            ModelId::Dobashi => {
                let settings = DobashiSettings::from_options(options)?;
                Shafted::Dobashi(Box::new(Dobashi::prepare(a, s, settings)?))
            }
            other => bail!(
                "--terrain: {other} has no light shafts (reference, hillaire, nishita, oneil, bruneton and dobashi have; docs/shafts.md)"
            ),
        })
    }

    fn model(&self) -> &dyn SkyModel {
        match self {
            Shafted::Reference(m) => m.as_ref(),
            Shafted::Hillaire(m) => m.as_ref(),
            Shafted::Nishita(m) => m.as_ref(),
            Shafted::Oneil(m) => m.as_ref(),
            Shafted::Bruneton(m) => m.as_ref(),
            Shafted::Dobashi(m) => m.as_ref(),
        }
    }

    fn set_terrain_shadow(&mut self, map: ShadowMap) {
        match self {
            Shafted::Reference(_) => {}
            Shafted::Hillaire(m) => m.set_terrain_shadow(Some(map)),
            Shafted::Nishita(m) => m.set_terrain_shadow(Some(map)),
            Shafted::Oneil(m) => m.set_terrain_shadow(Some(map)),
            Shafted::Bruneton(m) => m.set_terrain_shadow(Some(map)),
            Shafted::Dobashi(m) => m.set_terrain_shadow(Some(map)),
        }
    }
}

/// The relief the terrain pass draws, at true scale, on the sphere of `radius_m`.
fn earth_relief(radius_m: f64) -> anyhow::Result<TerrainSurface<Arc<RefinedHeights>>> {
    let heights = EarthData::BuiltIn
        .refined_heights()
        .context("--terrain: the built-in height map")?;
    Ok(TerrainSurface::new(Arc::new(heights), radius_m))
}

/// Refuses a ray whose origin lies inside the relief.
fn check_above(
    relief: &TerrainSurface<Arc<RefinedHeights>>,
    ray: &ViewRay,
) -> Result<(), ModelError> {
    let ground_m = relief.radius_m + relief.elevation_m(ray.origin_m.normalize());
    let altitude_m = ray.origin_m.length();
    if altitude_m < ground_m {
        return Err(ModelError::Ray(format!(
            "the ray starts {:.1} m below the terrain here (its surface is {:.1} m above sea level)",
            ground_m - altitude_m,
            ground_m - relief.radius_m
        )));
    }
    Ok(())
}

/// A model's solar irradiance and its answer to each ray, in the order of the rays.
pub type Answers = (Vec<f64>, Vec<Result<RayRadiance, ModelError>>);

/// `ray` ended where it first meets the relief, if it does before its own end.
fn ended_on_relief(
    march: &HeightFieldShadow<TerrainSurface<Arc<RefinedHeights>>>,
    ray: ViewRay,
) -> ViewRay {
    let hit = march.first_hit_m(ray.origin_m, ray.direction.normalize());
    let max_distance_m = match (hit, ray.max_distance_m) {
        (Some(h), Some(d)) => Some(h.min(d)),
        (Some(h), None) if h > 0.0 => Some(h),
        (_, given) => given,
    };
    ViewRay {
        max_distance_m,
        ..ray
    }
}

/// Whether the rays see the terrain's shadow in the air: as `atmos probe --terrain` does,
/// or not (the same placed and ended rays without shafts, as `atmos report` compares).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shadows {
    Terrain,
    Off,
}

/// Wall-clock seconds of one evaluation: the model's preparation (with the frame's
/// shadow map where the rays see it), then the rays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    pub prepare_s: f64,
    pub rays_s: f64,
}

/// The solar irradiance of model `id` and its answers to `rays` (of the probe's local
/// frame) placed at `place` over the relief, in the order of the rays.
pub fn evaluate(
    id: ModelId,
    atmosphere: &Atmosphere,
    settings: &ModelSettings,
    rays: &[ViewRay],
    place: &TerrainPlace,
) -> anyhow::Result<Answers> {
    Ok(evaluate_timed(id, atmosphere, settings, rays, place, Shadows::Terrain)?.0)
}

/// [`evaluate`] with or without the terrain's shadow, and how long it took.
pub fn evaluate_timed(
    id: ModelId,
    atmosphere: &Atmosphere,
    settings: &ModelSettings,
    rays: &[ViewRay],
    place: &TerrainPlace,
    shadows: Shadows,
) -> anyhow::Result<(Answers, Timing)> {
    let relief = earth_relief(atmosphere.bottom_radius_m)?;
    let march = HeightFieldShadow::new(relief.clone(), atmosphere.bottom_radius_m);
    let placed: Vec<ViewRay> = rays
        .iter()
        .map(|r| ended_on_relief(&march, place.placed(r)))
        .collect();
    let start = Instant::now();
    let mut model = Shafted::prepare(id, atmosphere, settings)?;
    let mut shadow = FrameShadow::default();
    let mut shadow_for = |ray: &ViewRay| {
        let sun = ray.sun_direction.normalize();
        shadow
            .update(ray.origin_m, sun, atmosphere.bottom_radius_m, &relief)
            .cloned()
    };
    // The frame's map is built once for the rays' camera, and a model's tables for the
    // view on its first ray: preparation, not ray time.
    if let (Some(first), false) = (placed.first(), matches!(model, Shafted::Reference(_))) {
        if shadows == Shadows::Terrain {
            model.set_terrain_shadow(shadow_for(first)?);
        }
        let _ = model.model().radiance(first);
    }
    let prepare_s = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let results = if let Shafted::Reference(reference) = &model {
        map_with_progress("probe", "rays", &placed, |ray| {
            check_above(&relief, ray)?;
            match shadows {
                Shadows::Terrain => reference.radiance_shadowed(ray, Some(&march)),
                Shadows::Off => reference.radiance(ray),
            }
        })
    } else {
        let mut out = Vec::with_capacity(placed.len());
        for ray in &placed {
            let answer = check_above(&relief, ray).and_then(|()| {
                if shadows == Shadows::Terrain {
                    model.set_terrain_shadow(shadow_for(ray)?);
                }
                model.model().radiance(ray)
            });
            out.push(answer);
        }
        out
    };
    let timing = Timing {
        prepare_s,
        rays_s: start.elapsed().as_secs_f64(),
    };
    let irradiance = model.model().solar_irradiance_w_m2_nm().to_vec();
    Ok(((irradiance, results), timing))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn a_placed_ray_looks_and_sees_the_sun_at_the_geographic_azimuths() {
        let place = TerrainPlace::new(0.0, 0.0, 90.0).unwrap();
        // The sun 90 degrees to the right of the view: the view looks north.
        let ray = ViewRay::from_angles(6_360_000.0, 100.0, 90.0, 90.0, -90.0, None).unwrap();
        let placed = place.placed(&ray);
        // At (0 N, 0 E): up is x, east is y, north is z.
        assert!((placed.origin_m.normalize() - DVec3::X).length() < 1e-12);
        assert!(
            (placed.sun_direction - DVec3::Y).length() < 1e-12,
            "{}",
            placed.sun_direction
        );
        assert!(
            (placed.direction - DVec3::Z).length() < 1e-12,
            "{}",
            placed.direction
        );
    }

    /// Over the Pennine Alps at sunset (the default scene's place and sun), rays from 5.6
    /// km ended on the relief. One the terrain does not shadow: hillaire answers as the
    /// reference within 0.5 % (the same placed and ended ray). One that passes the valleys
    /// the low sun leaves in shadow: the exact march takes out more than a tenth of the
    /// reference's single scattering, and hillaire with the frame's cascaded shadow map is
    /// within 8 % of it (a single map of 2 km cells, which loses the narrower valleys'
    /// shadows, was 13 % off; docs/shafts.md, "Probing").
    #[test]
    fn hillaire_and_the_reference_answer_the_same_rays_over_the_alps() {
        let earth = Atmosphere::preset("earth").unwrap();
        let settings = ModelSettings {
            wavelengths_nm: vec![550.0],
            max_orders: Some(1),
            ..ModelSettings::default()
        };
        let place = TerrainPlace::new(46.0, 7.8, 251.0).unwrap();
        let rays = [(95.0, 0.0), (96.0, -5.0)].map(|(view_zenith_deg, azimuth_deg)| {
            let bottom = earth.bottom_radius_m;
            ViewRay::from_angles(bottom, 5_600.0, view_zenith_deg, 86.0, azimuth_deg, None).unwrap()
        });
        let answer = |id| {
            let (_, results) = evaluate(id, &earth, &settings, &rays, &place).unwrap();
            results
                .into_iter()
                .map(|r| r.unwrap().radiance[0])
                .collect::<Vec<_>>()
        };
        let (reference, hillaire) = (answer(ModelId::Reference), answer(ModelId::Hillaire));
        let unshadowed = Reference::prepare(&earth, &settings).unwrap();
        let relief = earth_relief(earth.bottom_radius_m).unwrap();
        let march = HeightFieldShadow::new(relief, earth.bottom_radius_m);
        let mut taken = Vec::new();
        for (k, ray) in rays.iter().enumerate() {
            let ended = ended_on_relief(&march, place.placed(ray));
            assert!(ended.max_distance_m.is_some(), "ray {k} meets the relief");
            let lit = unshadowed.radiance(&ended).unwrap().radiance[0];
            let error = (hillaire[k] - reference[k]).abs() / reference[k];
            println!(
                "ray {k}: reference {:e} (unshadowed {lit:e}), hillaire {:e}: {error:.3}",
                reference[k], hillaire[k]
            );
            taken.push((1.0 - reference[k] / lit, error));
        }
        assert!(taken[0].0.abs() < 1e-9 && taken[0].1 < 0.005, "{taken:?}");
        assert!(taken[1].0 > 0.1 && taken[1].1 < 0.08, "{taken:?}");
    }

    #[test]
    fn bad_places_and_models_without_shafts_are_named() {
        let err = |lat, lon, az| TerrainPlace::new(lat, lon, az).unwrap_err().to_string();
        assert_eq!(
            err(0.0, 0.0, 400.0),
            "--sun-azimuth-deg 400 must lie in [-360, 360]"
        );
        assert_eq!(
            err(0.0, 0.0, f64::NAN),
            "--sun-azimuth-deg NaN must lie in [-360, 360]"
        );
        assert!(err(91.0, 0.0, 0.0).contains("--latitude-deg 91"));
        let earth = Atmosphere::preset("earth").unwrap();
        let text = Shafted::prepare(ModelId::Riley, &earth, &ModelSettings::default())
            .err()
            .unwrap()
            .to_string();
        assert!(text.contains("riley has no light shafts"), "{text}");
    }
}
