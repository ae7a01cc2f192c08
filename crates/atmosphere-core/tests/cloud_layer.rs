//! The cloud layer on the planet composited with a sky model: limits and stability.
//! Cover 0 changes nothing; a thousand times the density stays finite and opaque; a
//! camera inside a cloud, on its top, and under a sun 10 degrees below the horizon gets
//! finite, bounded, continuous answers; bad settings are refused by name.

use atmosphere_core::atmosphere::presets::earth;
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::composite::radiance_with_clouds;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::presets::MarchQuality;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings, SunLight};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance, SkyModel, ViewRay};
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;

const BOTTOM_M: f64 = 6_360_000.0;

fn model() -> Box<dyn SkyModel> {
    prepare(ModelId::Riley, &earth(), &ModelSettings::default()).unwrap()
}

fn orders(waves: usize) -> ScatteringOrders {
    let series = LegendreSeries::henyey_greenstein(0.85, 300);
    ScatteringOrders::new(&vec![series; waves]).unwrap()
}

fn layer(cover: f32, settings: LayerSettings) -> CloudLayer {
    let grid = CoverGrid::from_values("uniform cover", 4, 2, vec![cover; 8]).unwrap();
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    CloudLayer::new(settings, BOTTOM_M, grid, phase).unwrap()
}

/// The interactive preset with its sun's light from a shadow march: the composite here
/// has no frame's sun map (`cloud_sun_light.rs` lights the layer through one).
fn interactive(settings: LayerSettings) -> LayerSettings {
    LayerSettings {
        sun_light: SunLight::March,
        ..MarchQuality::Interactive.apply(settings)
    }
}

fn ray(altitude_m: f64, view_zenith_deg: f64, sun_zenith_deg: f64) -> ViewRay {
    ViewRay::from_angles(
        BOTTOM_M,
        altitude_m,
        view_zenith_deg,
        sun_zenith_deg,
        40.0,
        None,
    )
    .unwrap()
}

fn assert_sane(what: &str, r: &RayRadiance, bound: f64) {
    for (l, t) in r.radiance.iter().zip(&r.transmittance) {
        assert!(
            l.is_finite() && *l >= 0.0 && *l < bound,
            "{what}: radiance {l}"
        );
        assert!((0.0..=1.0).contains(t), "{what}: transmittance {t}");
    }
}

#[test]
fn no_cover_changes_nothing() {
    let model = model();
    let orders = orders(model.wavelengths_nm().len());
    let clear = layer(0.0, LayerSettings::default());
    for r in [
        ray(10.0, 30.0, 40.0),
        ray(5000.0, 120.0, 60.0),
        ray(2000.0, 85.0, 20.0),
    ] {
        let with = radiance_with_clouds(model.as_ref(), &clear, &orders, &r).unwrap();
        assert_eq!(with, model.radiance(&r).unwrap());
    }
}

/// Seen from below, an overcast layer hides the sky behind it; seen from above, the
/// white deck outshines the dark ground (albedo 0.1) the clear view ends on.
#[test]
fn overcast_hides_the_sky_from_below_and_shines_from_above() {
    let model = model();
    let orders = orders(model.wavelengths_nm().len());
    let overcast = layer(1.0, LayerSettings::default());
    let up = ray(10.0, 0.0, 40.0);
    let sky = model.radiance(&up).unwrap();
    let cloudy = radiance_with_clouds(model.as_ref(), &overcast, &orders, &up).unwrap();
    for w in 0..sky.radiance.len() {
        assert!(cloudy.transmittance[w] < 1e-3 * sky.transmittance[w]);
        assert!(cloudy.radiance[w] > 0.0);
    }
    let down = ray(6000.0, 150.0, 40.0);
    let ground = model.radiance(&down).unwrap();
    let deck = radiance_with_clouds(model.as_ref(), &overcast, &orders, &down).unwrap();
    for w in 0..ground.radiance.len() {
        assert!(
            deck.radiance[w] > 2.0 * ground.radiance[w],
            "{deck:?} against {ground:?}"
        );
    }
}

#[test]
fn a_thousand_times_the_density_stays_finite_and_opaque() {
    let model = model();
    let orders = orders(model.wavelengths_nm().len());
    let interactive = interactive(LayerSettings::default());
    for (method, base) in [
        (LayerMethod::Riley, LayerSettings::default()),
        (LayerMethod::Octaves, LayerSettings::default()),
        (LayerMethod::Eddington, LayerSettings::default()),
        (LayerMethod::FourStream, LayerSettings::default()),
        (LayerMethod::Riley, interactive),
        (LayerMethod::Octaves, interactive),
        (LayerMethod::Eddington, interactive),
        (LayerMethod::FourStream, interactive),
    ] {
        for extinction_per_m in [0.001, 1.0] {
            let l = layer(
                1.0,
                LayerSettings {
                    extinction_per_m,
                    method,
                    ..base
                },
            );
            for r in [
                ray(10.0, 10.0, 30.0),
                ray(8000.0, 170.0, 30.0),
                ray(2200.0, 80.0, 85.0),
            ] {
                let a = radiance_with_clouds(model.as_ref(), &l, &orders, &r).unwrap();
                assert_sane(&format!("{method} {extinction_per_m}"), &a, 10.0);
                // Opaque: below 1e-3, or below where the march stops (what lies
                // behind is then seen through the transmittance marched so far).
                if extinction_per_m == 1.0 {
                    let opaque = base.min_transmittance.max(1e-3);
                    assert!(a.transmittance.iter().all(|t| *t < opaque), "{a:?}");
                }
            }
        }
    }
}

#[test]
fn inside_a_cloud_and_at_its_top_the_answers_are_finite_and_continuous() {
    let model = model();
    let orders = orders(model.wavelengths_nm().len());
    let default = LayerSettings::default();
    for s in [default, interactive(default)] {
        let l = layer(1.0, s);
        let top = s.base_m + s.thickness_m;
        for view in [0.0, 60.0, 90.0, 120.0, 180.0] {
            let inside = radiance_with_clouds(
                model.as_ref(),
                &l,
                &orders,
                &ray(s.base_m + 500.0, view, 30.0),
            )
            .unwrap();
            assert_sane("inside", &inside, 10.0);
            assert!(inside.transmittance[1] < 0.999, "view {view}: {inside:?}");
            let at =
                radiance_with_clouds(model.as_ref(), &l, &orders, &ray(top, view, 30.0)).unwrap();
            let above =
                radiance_with_clouds(model.as_ref(), &l, &orders, &ray(top + 0.5, view, 30.0))
                    .unwrap();
            assert_sane("at the top", &at, 10.0);
            for w in 0..at.radiance.len() {
                let scale = at.radiance[w].max(above.radiance[w]).max(1e-6);
                assert!(
                    (at.radiance[w] - above.radiance[w]).abs() < 0.02 * scale,
                    "view {view}: {} at the top, {} 0.5 m above",
                    at.radiance[w],
                    above.radiance[w]
                );
            }
        }
    }
}

#[test]
fn a_sun_ten_degrees_below_the_horizon_leaves_only_a_dim_cloud() {
    let model = model();
    let orders = orders(model.wavelengths_nm().len());
    let l = layer(1.0, LayerSettings::default());
    let day = radiance_with_clouds(model.as_ref(), &l, &orders, &ray(10.0, 0.0, 60.0)).unwrap();
    for method in [
        LayerMethod::Riley,
        LayerMethod::Octaves,
        LayerMethod::Eddington,
        LayerMethod::FourStream,
    ] {
        let l = layer(
            1.0,
            LayerSettings {
                method,
                ..LayerSettings::default()
            },
        );
        for view in [0.0, 80.0] {
            let night =
                radiance_with_clouds(model.as_ref(), &l, &orders, &ray(10.0, view, 100.0)).unwrap();
            assert_sane("sun below the horizon", &night, 10.0);
            assert!(
                night.radiance[1] < 0.05 * day.radiance[1],
                "{night:?} against {day:?}"
            );
        }
    }
}

#[test]
fn bad_settings_and_tables_are_refused_by_name() {
    let cases = [
        (
            LayerSettings {
                base_m: -1.0,
                ..LayerSettings::default()
            },
            "cloud base_m = -1",
        ),
        (
            LayerSettings {
                thickness_m: 5.0,
                ..LayerSettings::default()
            },
            "cloud thickness_m = 5",
        ),
        (
            LayerSettings {
                extinction_per_m: f64::NAN,
                ..LayerSettings::default()
            },
            "cloud extinction_per_m = NaN",
        ),
        (
            LayerSettings {
                steps: 0,
                ..LayerSettings::default()
            },
            "cloud steps = 0 must lie in [1, 512]",
        ),
        (
            LayerSettings {
                shadow_steps: 65,
                ..LayerSettings::default()
            },
            "cloud shadow_steps = 65",
        ),
        (
            LayerSettings {
                octaves: 9,
                ..LayerSettings::default()
            },
            "cloud octaves = 9",
        ),
        (
            LayerSettings {
                coverage_scale: 5.0,
                ..LayerSettings::default()
            },
            "cloud coverage_scale = 5",
        ),
        (
            LayerSettings {
                detail_octaves: 0,
                ..LayerSettings::default()
            },
            "cloud detail_octaves = 0 must lie in [1, 3]",
        ),
        (
            LayerSettings {
                shadow_octaves: 4,
                ..LayerSettings::default()
            },
            "cloud shadow_octaves = 4 must lie in [0, 3]",
        ),
        (
            LayerSettings {
                min_transmittance: 0.5,
                ..LayerSettings::default()
            },
            "cloud min_transmittance = 0.5 must lie in [0.000001, 0.1]",
        ),
        (
            LayerSettings {
                resolution_divisor: 5,
                ..LayerSettings::default()
            },
            "cloud resolution_divisor = 5 must lie in [1, 4]",
        ),
        (
            LayerSettings {
                air_shadow_divisor: 9,
                ..LayerSettings::default()
            },
            "cloud air_shadow_divisor = 9 must lie in [1, 8]",
        ),
    ];
    for (settings, message) in cases {
        let e = settings.check().unwrap_err();
        assert!(e.0.contains(message), "{e}");
    }
    assert!(
        "puffy"
            .parse::<LayerMethod>()
            .unwrap_err()
            .0
            .contains("\"puffy\" is not one of riley, octaves")
    );
    let model = model();
    let e = radiance_with_clouds(
        model.as_ref(),
        &layer(1.0, LayerSettings::default()),
        &orders(1),
        &ray(10.0, 0.0, 30.0),
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("cloud phase tables for 1 wavelengths"),
        "{e}"
    );
    let lit = LayerSettings {
        sun_light: SunLight::Map,
        ..LayerSettings::default()
    };
    let e = radiance_with_clouds(
        model.as_ref(),
        &layer(1.0, lit),
        &orders(model.wavelengths_nm().len()),
        &ray(10.0, 0.0, 30.0),
    )
    .unwrap_err();
    assert!(e.to_string().contains("sun_light = map"), "{e}");
}
