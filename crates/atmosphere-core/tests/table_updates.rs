//! Tables are rebuilt only when an input they depend on changes: for each model with quick tables, a change of the sun's
//! direction, the ground albedo, the aerosol amount, the aerosol profile or the solar
//! spectrum rebuilds exactly the tables named here, and the updated model answers as a
//! model prepared from scratch. bruneton, whose build takes seconds, has its own test in
//! model_bruneton.rs.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::density::DensityProfile;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};

fn settings() -> ModelSettings {
    ModelSettings {
        max_orders: Some(1),
        target_relative_error: 0.05,
        ..ModelSettings::default()
    }
}

/// A few rays: ground and 10 km, sky and ground, sun high and low.
fn rays(a: &Atmosphere) -> Vec<ViewRay> {
    let mut rays = Vec::new();
    for (altitude, view, sun) in [
        (2.0, 60.0, 30.0),
        (2.0, 89.0, 85.0),
        (10_000.0, 120.0, 45.0),
    ] {
        rays.push(
            ViewRay::from_angles(a.bottom_radius_m, altitude, view, sun, 40.0, None).unwrap(),
        );
    }
    rays
}

fn answers(model: &dyn SkyModel, rays: &[ViewRay]) -> Vec<Vec<f64>> {
    rays.iter()
        .map(|r| {
            let a = model.radiance(r).unwrap();
            a.radiance.into_iter().chain(a.transmittance).collect()
        })
        .collect()
}

/// A change of the atmosphere, and the tables each model must rebuild for it.
struct Change {
    name: &'static str,
    atmosphere: Atmosphere,
    rebuilt: [(ModelId, Vec<&'static str>); 4],
}

fn changes() -> Vec<Change> {
    let earth = Atmosphere::preset("earth").unwrap();
    let mut albedo = earth.clone();
    albedo.ground_albedo = 0.3;
    let aerosol = earth.with_aerosol_scale(3.0);
    let mut profile = earth.clone();
    profile.mie.density = DensityProfile::exponential(2_000.0);
    let mut sun = earth.clone();
    sun.sun.irradiance_w_m2_nm = sun.sun.irradiance_w_m2_nm.scaled(0.9);
    let columns = vec!["g_l"];
    vec![
        Change {
            name: "ground albedo",
            atmosphere: albedo,
            rebuilt: [
                (ModelId::Nishita, vec![]),
                (ModelId::Oneil, vec![]),
                (ModelId::Riley, vec![]),
                (ModelId::Reference, vec![]),
            ],
        },
        Change {
            name: "aerosol amount",
            atmosphere: aerosol,
            rebuilt: [
                (ModelId::Nishita, vec![]),
                (ModelId::Oneil, vec![]),
                (ModelId::Riley, vec![]),
                (ModelId::Reference, vec![]),
            ],
        },
        Change {
            name: "aerosol profile",
            atmosphere: profile,
            rebuilt: [
                (ModelId::Nishita, columns),
                (ModelId::Oneil, vec!["optical depth"]),
                (ModelId::Riley, vec![]),
                (ModelId::Reference, vec!["transmittance"]),
            ],
        },
        Change {
            name: "solar spectrum",
            atmosphere: sun,
            rebuilt: [
                (ModelId::Nishita, vec![]),
                (ModelId::Oneil, vec![]),
                (ModelId::Riley, vec![]),
                (ModelId::Reference, vec![]),
            ],
        },
    ]
}

#[test]
fn each_change_rebuilds_only_what_depends_on_it_and_answers_as_a_fresh_model() {
    let earth = Atmosphere::preset("earth").unwrap();
    for Change {
        name: change,
        atmosphere: changed,
        rebuilt: expected,
    } in changes()
    {
        for (id, tables) in expected {
            let mut model = prepare(id, &earth, &settings()).unwrap();
            let rebuilt = model.update(&changed).unwrap();
            assert_eq!(rebuilt, tables, "{id}, {change}");
            let fresh = prepare(id, &changed, &settings()).unwrap();
            let (a, b) = (
                answers(model.as_ref(), &rays(&changed)),
                answers(fresh.as_ref(), &rays(&changed)),
            );
            if id == ModelId::Reference {
                // Deterministic at order 1: equal to rounding.
                for (x, y) in a.iter().flatten().zip(b.iter().flatten()) {
                    assert!(
                        (x - y).abs() <= 1e-12 * y.abs().max(1e-30),
                        "{id}, {change}: {x} vs {y}"
                    );
                }
            } else {
                assert_eq!(a, b, "{id}, {change}");
            }
            // The change shows in the answers (it is not a no-op).
            let before = answers(
                prepare(id, &earth, &settings()).unwrap().as_ref(),
                &rays(&changed),
            );
            assert_ne!(a, before, "{id}: {change} changed nothing");
        }
    }
}

#[test]
fn the_sun_direction_and_an_unchanged_atmosphere_rebuild_nothing() {
    let earth = Atmosphere::preset("earth").unwrap();
    for id in [
        ModelId::Nishita,
        ModelId::Oneil,
        ModelId::Riley,
        ModelId::Reference,
    ] {
        let mut model = prepare(id, &earth, &settings()).unwrap();
        assert!(model.update(&earth).unwrap().is_empty(), "{id}");
        // The sun's direction is part of each ray: two suns, one model, no update.
        let low = ViewRay::from_angles(earth.bottom_radius_m, 2.0, 60.0, 85.0, 0.0, None).unwrap();
        let high = ViewRay {
            sun_direction: glam::DVec3::Z,
            ..low
        };
        let (a, b) = (
            model.radiance(&low).unwrap(),
            model.radiance(&high).unwrap(),
        );
        assert_ne!(a.radiance, b.radiance, "{id}");
    }
}
