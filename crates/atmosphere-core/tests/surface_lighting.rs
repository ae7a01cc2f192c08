//! Every model lights surface elements (`SkyModel::surface_irradiance`) as its own ground:
//! a ray ending on the ground equals the same ray ended there as an object plus the
//! element's reflection (`radiance_with_surface`); at the top of the atmosphere an element
//! facing the sun receives the solar irradiance; an element facing the ground and away
//! from the sun receives nothing; and the reference says it does not light surfaces.

mod common;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::error::ModelError;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, SurfacePoint, ViewRay};
use atmosphere_core::optics::surface_lighting::{SurfaceHit, radiance_with_surface};
use atmosphere_core::optics::view_segment::{SegmentEnd, ViewSegment};
use common::all_orders_reference;
use glam::DVec3;

/// The models that light surfaces.
const MODELS: &[ModelId] = &[
    ModelId::Nishita,
    ModelId::Oneil,
    ModelId::Riley,
    ModelId::Dobashi,
    ModelId::Bruneton,
    ModelId::Hillaire,
];

fn models(a: &Atmosphere) -> Vec<Box<dyn SkyModel>> {
    MODELS
        .iter()
        .map(|&id| prepare(id, a, &ModelSettings::default()).unwrap())
        .collect()
}

fn element(point_m: DVec3, normal: DVec3, sun_direction: DVec3) -> SurfacePoint {
    SurfacePoint {
        point_m,
        normal,
        sun_direction,
    }
}

/// Rays from 2 m to 30 km down to the ground, the sun high, low and just set.
fn ground_rays(a: &Atmosphere) -> Vec<ViewRay> {
    let mut rays = Vec::new();
    for (altitude, view) in [(2.0, 95.0), (1_000.0, 120.0), (30_000.0, 170.0)] {
        for sun in [20.0, 80.0, 91.0] {
            rays.push(
                ViewRay::from_angles(a.bottom_radius_m, altitude, view, sun, 40.0, None).unwrap(),
            );
        }
    }
    rays
}

#[test]
fn each_model_lights_its_ground_as_a_surface() {
    let a = Atmosphere::preset("hazy").unwrap();
    for model in models(&a) {
        for ray in ground_rays(&a) {
            let segment = ViewSegment::new(&a, &ray).unwrap().unwrap();
            assert_eq!(segment.end, SegmentEnd::Ground);
            let ground = model.radiance(&ray).unwrap();
            let end = segment.end_point();
            // Any distance beyond the ground ends the ray there, as an object.
            let hit = SurfaceHit {
                distance_m: (segment.t_enter + segment.length) * 1.5,
                normal: end.normalize(),
                albedo: vec![a.ground_albedo; 3],
            };
            let lit = radiance_with_surface(model.as_ref(), &a, &ray, &hit).unwrap();
            for w in 0..3 {
                let (g, s) = (ground.radiance[w], lit.radiance[w]);
                assert!(
                    (g - s).abs() <= 1e-9 * g.abs() + 1e-15,
                    "{} {ray:?} channel {w}: ground {g:e}, as a surface {s:e}",
                    model.id()
                );
                assert_eq!(ground.transmittance[w], lit.transmittance[w]);
            }
        }
    }
}

#[test]
fn outside_the_atmosphere_a_surface_facing_the_sun_receives_the_solar_irradiance() {
    let a = Atmosphere::preset("earth").unwrap();
    let sun = DVec3::new(0.3, -0.2, 0.9).normalize();
    let top = DVec3::new(0.0, 0.0, a.top_radius_m + 1.0);
    for model in models(&a) {
        let facing = model.surface_irradiance(&element(top, sun, sun)).unwrap();
        let bottom = DVec3::new(0.0, 0.0, a.bottom_radius_m);
        let away = model
            .surface_irradiance(&element(bottom, -DVec3::Z, sun))
            .unwrap();
        for w in 0..3 {
            let e = model.solar_irradiance_w_m2_nm()[w];
            assert!(
                (facing[w] / e - 1.0).abs() < 1e-3,
                "{} channel {w}: {} of {e}",
                model.id(),
                facing[w]
            );
            assert_eq!(away[w], 0.0, "{} channel {w}", model.id());
        }
    }
}

#[test]
fn the_reference_does_not_light_surfaces() {
    let a = Atmosphere::preset("earth").unwrap();
    let reference = all_orders_reference(&a, 0.5);
    let err = reference
        .surface_irradiance(&SurfacePoint::facing_up(
            DVec3::new(0.0, 0.0, a.bottom_radius_m),
            DVec3::Z,
        ))
        .unwrap_err();
    assert!(matches!(err, ModelError::Unsupported { .. }), "{err}");
    assert!(err.to_string().contains("reference"), "{err}");
}
