//! The dobashi model against the reference and against itself: its single scattering
//! converges to the reference's as the planes and spheres grow, its error at the paper's
//! settings and with the ambient term against all orders is what docs/models/dobashi.md
//! states, pruning and table updates change nothing (the stability sweep is in stability.rs).

mod common;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::dobashi::settings::MAX_PLANES;
use atmosphere_core::models::dobashi::{Dobashi, DobashiSettings};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, ViewRay};
use atmosphere_core::optics::view_segment::{SegmentEnd, ViewSegment};
use common::{
    all_orders_reference, assert_impossible_rays_are_errors, assert_sane, ray, ray_to,
    relative_radiance, single, worst,
};

fn dobashi(a: &Atmosphere, settings: &ModelSettings, d: DobashiSettings) -> Dobashi {
    Dobashi::prepare(a, settings, d).unwrap()
}

#[test]
fn dobashi_is_registered_and_reads_its_options() {
    let a = Atmosphere::preset("earth").unwrap();
    let mut settings = single();
    settings.options = ModelOptions::parse(&["planes=50", "spheres=4"]).unwrap();
    let m = prepare(ModelId::Dobashi, &a, &settings).unwrap();
    assert_eq!(m.id(), ModelId::Dobashi);
    assert_eq!(m.wavelengths_nm(), &[680.0, 550.0, 440.0]);
    assert!(m.table_bytes() > 0);
    settings.options = ModelOptions::parse(&["samples=16"]).unwrap();
    assert!(prepare(ModelId::Dobashi, &a, &settings).is_err());
}

/// The daytime views of the measured table (docs/models/dobashi.md).
fn daytime(a: &Atmosphere) -> Vec<ViewRay> {
    vec![
        ray(a, 0.0, 0.0, 30.0, 0.0),
        ray(a, 0.0, 60.0, 45.0, 90.0),
        ray(a, 0.0, 89.9, 60.0, 0.0),
        ray(a, 10_000.0, 95.0, 40.0, 20.0),
        ray(a, 100_000.0, 107.0, 50.0, 0.0),
        ray(a, 3e7, 179.5, 10.0, 0.0),
        ray(a, 1e8, 180.0 - 3.4, 30.0, 0.0),
        ViewRay {
            max_distance_m: Some(20_000.0),
            ..ray(a, 500.0, 88.0, 50.0, 45.0)
        },
    ]
}

/// Single scattering (no ambient term) converges to the reference's as the planes and
/// the spheres grow, at first order (the sun's attenuation g_l is taken at each plane,
/// Eq. 12): measured worst error over the daytime views 7.3e-2, 2.1e-2, 5.2e-3 for 100,
/// 400, 1600 planes (10, 40, 160 spheres). Each fourfold step must cut it at least 2.5
/// times, on every view, and the finest be within 6e-3.
#[test]
fn single_scattering_converges_to_the_reference() {
    let a = Atmosphere::preset("earth").unwrap();
    let reference = prepare(ModelId::Reference, &a, &single()).unwrap();
    let views = daytime(&a);
    let errors: Vec<Vec<f64>> = [100, 400, 1600]
        .into_iter()
        .map(|planes| {
            let m = dobashi(
                &a,
                &single(),
                DobashiSettings {
                    planes,
                    spheres: planes / 10,
                    ..DobashiSettings::default()
                },
            );
            views
                .iter()
                .map(|r| worst(&relative_radiance(&m, reference.as_ref(), r)))
                .collect()
        })
        .collect();
    for v in 0..views.len() {
        assert!(
            errors[1][v] < errors[0][v] / 2.5 && errors[2][v] < errors[1][v] / 2.5,
            "{:?}: {errors:?}",
            views[v]
        );
        assert!(errors[2][v] < 6e-3, "{:?}: {errors:?}", views[v]);
    }
}

/// At the paper's settings, single scattering against the reference's: measured worst
/// 7.3 % (the zenith from the ground, too dark: g_l at each plane's start is the dimmest
/// sunlight of its 8.8 km segment), transmittance within 1.6e-4 (8.7e-4 for the object,
/// whose last segment is cut as if uniform). Bounds 8 %, 3e-4 and 1.5e-3.
#[test]
fn paper_settings_against_the_reference_single_scattering() {
    let a = Atmosphere::preset("earth").unwrap();
    let reference = prepare(ModelId::Reference, &a, &single()).unwrap();
    let m = prepare(ModelId::Dobashi, &a, &single()).unwrap();
    for ray in daytime(&a) {
        let e = relative_radiance(m.as_ref(), reference.as_ref(), &ray);
        assert!(worst(&e) < 0.08, "{ray:?}: {e:?}");
        let (x, y) = (m.radiance(&ray).unwrap(), reference.radiance(&ray).unwrap());
        let bound = if ray.max_distance_m.is_some() {
            1.5e-3
        } else {
            3e-4
        };
        for w in 0..3 {
            let dt = (x.transmittance[w] - y.transmittance[w]).abs();
            assert!(dt < bound, "{ray:?}: transmittance off by {dt:e}");
        }
    }
}

/// Cameras far above the atmosphere use sample spheres, nearer ones planes (section
/// 4.2.1's plane count against `max_planes`: the switch is near 315 km for the earth);
/// from 30,000 km (nadir) and 1e8 m (limb) both methods are within 4 % of the reference
/// (measured spheres 0.9 % and 2.2 %, planes 3.2 % and 1.0 %).
#[test]
fn spheres_far_out_and_planes_near() {
    let a = Atmosphere::preset("earth").unwrap();
    let m = dobashi(&a, &single(), DobashiSettings::default());
    let t = m.tracer();
    let r = |h: f64| a.bottom_radius_m + h;
    assert!(!t.uses_spheres(r(0.0)) && !t.uses_spheres(r(60_000.0)));
    assert!(!t.uses_spheres(r(300_000.0)) && t.uses_spheres(r(330_000.0)));
    assert!(t.uses_spheres(r(1e8)));
    let planes_only = dobashi(
        &a,
        &single(),
        DobashiSettings {
            max_planes: *MAX_PLANES.range.end(),
            ..DobashiSettings::default()
        },
    );
    assert!(!planes_only.tracer().uses_spheres(r(1e8)));
    let reference = prepare(ModelId::Reference, &a, &single()).unwrap();
    for ray in [
        ray(&a, 3e7, 179.5, 10.0, 0.0),
        ray(&a, 1e8, 176.6, 30.0, 0.0),
    ] {
        for model in [&m, &planes_only] {
            let e = relative_radiance(model, reference.as_ref(), &ray);
            assert!(worst(&e) < 0.04, "{ray:?}: {e:?}");
        }
    }
}

/// With the ambient term, against the reference with all orders (target 1 % standard
/// error): measured -9.5 % to +3.0 % on these daytime views (docs/models/dobashi.md),
/// where single scattering alone misses 22 % to 44 % of the blue. Asserted: within 12 %
/// (plus three standard errors), and closer than without the ambient term at every
/// wavelength.
#[test]
fn ambient_term_against_all_orders() {
    let a = Atmosphere::preset("earth").unwrap();
    let reference = all_orders_reference(&a, 0.01);
    let with = prepare(ModelId::Dobashi, &a, &ModelSettings::default()).unwrap();
    let without = prepare(ModelId::Dobashi, &a, &single()).unwrap();
    let views = daytime(&a);
    for ray in [&views[0], &views[1], &views[3], &views[5], &views[7]] {
        let r = reference.radiance(ray).unwrap();
        let e = relative_radiance(with.as_ref(), reference.as_ref(), ray);
        let e1 = relative_radiance(without.as_ref(), reference.as_ref(), ray);
        for w in 0..3 {
            let noise = 3.0 * r.radiance_std_error[w] / r.radiance[w];
            assert!(e[w].abs() < 0.12 + noise, "{ray:?}: {e:?}");
            assert!(e[w].abs() < e1[w].abs(), "{ray:?}: {e:?} vs {e1:?}");
        }
    }
}

/// The ambient radiance: zero for single scattering; for orders up to 2 it is psi_1, for
/// all orders psi_1 / (1 - f) with f, the mean transfer at the ground, between half the
/// albedo (the ground below) and 1; it vanishes with the sun far below the horizon and
/// grows with the sun's elevation.
#[test]
fn ambient_radiance_follows_its_definition() {
    let a = Atmosphere::preset("earth").unwrap();
    let d = DobashiSettings::default();
    assert!(dobashi(&a, &single(), d).ambient().is_none());
    let two = ModelSettings {
        max_orders: Some(2),
        ..ModelSettings::default()
    };
    let m2 = dobashi(&a, &two, d);
    let all = dobashi(&a, &ModelSettings::default(), d);
    let (t2, tall) = (m2.ambient().unwrap(), all.ambient().unwrap());
    let mut p2 = [0.0; 3];
    let mut pall = [0.0; 3];
    for w in 0..3 {
        let f = tall.transfer[w];
        assert!(f > 0.5 * a.ground_albedo && f < 1.0, "{f}");
    }
    let mut previous = [0.0; 3];
    for mu_sun in [-0.5, -0.1, 0.0, 0.3, 0.7, 1.0] {
        t2.lookup(mu_sun, &mut p2);
        tall.lookup(mu_sun, &mut pall);
        for w in 0..3 {
            let expected = p2[w] / (1.0 - tall.transfer[w]);
            assert!((pall[w] / expected - 1.0).abs() < 1e-5 || p2[w] == 0.0);
            assert!(p2[w] >= previous[w], "mu_sun {mu_sun}");
            previous[w] = p2[w];
        }
        if mu_sun == -0.5 {
            assert!(p2.iter().all(|p| *p < 1e-9), "{p2:?}");
        }
    }
}

/// At zero aerosol, pruning (no dI_m tables, no Mie terms) gives the same answers as the
/// full path, with smaller tables.
#[test]
fn pruning_changes_nothing() {
    let a = Atmosphere::preset("earth").unwrap().with_aerosol_scale(0.0);
    let full = ModelSettings {
        prune: false,
        ..ModelSettings::default()
    };
    let pruned = ModelSettings::default();
    let f = prepare(ModelId::Dobashi, &a, &full).unwrap();
    let p = prepare(ModelId::Dobashi, &a, &pruned).unwrap();
    assert!(p.table_bytes() < f.table_bytes());
    let mut views = daytime(&a);
    views.push(ray(&a, 0.0, 60.0, 96.0, 0.0));
    for ray in &views {
        let (x, y) = (f.radiance(ray).unwrap(), p.radiance(ray).unwrap());
        for w in 0..3 {
            assert!((x.radiance[w] - y.radiance[w]).abs() <= 1e-12 * x.radiance[w]);
            assert_eq!(x.transmittance[w], y.transmittance[w]);
        }
    }
}

/// `update` rebuilds only the tables whose inputs changed, and then answers as a model
/// prepared from scratch.
#[test]
fn update_rebuilds_only_what_changed() {
    let earth = Atmosphere::preset("earth").unwrap();
    let settings = ModelSettings::default();
    let mut m = prepare(ModelId::Dobashi, &earth, &settings).unwrap();
    assert!(m.update(&earth).unwrap().is_empty());
    let mut brighter = earth.clone();
    brighter.ground_albedo = 0.3;
    assert_eq!(m.update(&brighter).unwrap(), vec!["ambient"]);
    let hazy = brighter.with_aerosol_scale(3.0);
    let rebuilt = m.update(&hazy).unwrap();
    assert!(!rebuilt.contains(&"g_l"), "{rebuilt:?}");
    for name in ["dI_r", "dI_m", "dg_v", "sphere dI_m", "ambient"] {
        assert!(rebuilt.contains(&name), "{rebuilt:?}");
    }
    let clear = hazy.with_aerosol_scale(0.0);
    let rebuilt = m.update(&clear).unwrap();
    assert!(!rebuilt.contains(&"dI_m"), "{rebuilt:?}");
    let fresh = prepare(ModelId::Dobashi, &clear, &settings).unwrap();
    for ray in daytime(&clear) {
        assert_eq!(m.radiance(&ray).unwrap(), fresh.radiance(&ray).unwrap());
    }
}

/// Rays ending on objects at any distance, on every kind of camera, with the sun from
/// the zenith to 20 degrees below the horizon, on earth, 100 times its aerosol and Mars:
/// finite, non-negative radiance and transmittance in [0, 1]; an object just beyond the
/// ground or the top changes nothing.
#[test]
fn objects_and_extreme_rays_are_finite() {
    let earth = Atmosphere::preset("earth").unwrap();
    for a in [
        earth.clone(),
        earth.with_aerosol_scale(100.0),
        Atmosphere::preset("mars").unwrap(),
    ] {
        let m = prepare(ModelId::Dobashi, &a, &ModelSettings::default()).unwrap();
        let top = a.thickness_m();
        for altitude in [0.0, 1.0, top - 1.0, top + 1.0, 5e5, 1e8] {
            for view in [0.0, 60.0, 90.0, 93.0, 120.0, 180.0] {
                for sun in [0.0, 80.0, 95.0, 110.0] {
                    for distance in [None, Some(1.0), Some(5e3), Some(3e5), Some(1e9)] {
                        let ray = ray_to(&a, altitude, view, sun, 40.0, distance);
                        let out = m.radiance(&ray).unwrap();
                        assert_sane(&format!("{}: {ray:?}", a.name), &out);
                        if distance == Some(1e9) {
                            // An object beyond everything answers as the open ray, except
                            // that one beyond the ground ends the ray there as an object:
                            // the same segments, without the ground's light (its caller
                            // lights it; tests/surface_lighting.rs).
                            let open = ViewRay {
                                max_distance_m: None,
                                ..ray
                            };
                            let open_out = m.radiance(&open).unwrap();
                            let on_ground = ViewSegment::new(&a, &open)
                                .unwrap()
                                .is_some_and(|s| s.end == SegmentEnd::Ground);
                            if on_ground {
                                assert_eq!(out.transmittance, open_out.transmittance);
                                for w in 0..3 {
                                    assert!(out.radiance[w] <= open_out.radiance[w]);
                                }
                            } else {
                                assert_eq!(out, open_out);
                            }
                        }
                    }
                }
            }
        }
    }
}

/// A camera below the ground or a non-finite ray is an error, not a number.
#[test]
fn impossible_rays_are_errors() {
    let a = Atmosphere::preset("earth").unwrap();
    let m = prepare(ModelId::Dobashi, &a, &single()).unwrap();
    assert_impossible_rays_are_errors(m.as_ref(), &a);
}
