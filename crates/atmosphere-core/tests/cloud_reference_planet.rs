//! The cloud path tracer on the planet (`clouds/reference/`): its parts against
//! independent numbers. The exact phase sampler's mean cosine against the table's
//! asymmetry; the sun through the atmosphere against the columns by direct quadrature;
//! a layer without cloud answering the sky model's own answer; bad settings by name.

use atmosphere_core::atmosphere::presets::earth;
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::estimate::Tally;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::reference::camera_path::PathScene;
use atmosphere_core::clouds::reference::phase_sampler::PhaseTableSampler;
use atmosphere_core::clouds::reference::ray::radiance_path_traced;
use atmosphere_core::clouds::reference::settings::PathSettings;
use atmosphere_core::clouds::reference::sun_light::SunThroughAtmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, ViewRay};
use atmosphere_core::numerics::sampling::Sampler;
use atmosphere_core::optics::column::optical_depth;
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;
use atmosphere_core::optics::transmittance_table::table_column;
use glam::DVec3;

const BOTTOM_M: f64 = 6_360_000.0;

fn orders(g: f64) -> ScatteringOrders {
    ScatteringOrders::new(&vec![LegendreSeries::henyey_greenstein(g, 300); 3]).unwrap()
}

#[test]
fn the_phase_sampler_draws_the_tables_mean_cosine() {
    // Henyey-Greenstein's mean cosine is g; the table (0.176 degree steps) keeps it to
    // 1e-3, and 200,000 draws know it to about 4e-4.
    for g in [0.5, 0.85] {
        let sampler = PhaseTableSampler::new(&orders(g), 1);
        assert!(
            (sampler.integral() - 1.0).abs() < 1e-3,
            "{}",
            sampler.integral()
        );
        let mut random = Sampler::new(7);
        let mut tally = Tally::default();
        for _ in 0..200_000 {
            let (cos, weight) = sampler.sample(&mut random);
            assert!((-1.0..=1.0).contains(&cos));
            assert_eq!(weight, sampler.integral());
            tally.add(cos);
        }
        let e = tally.estimate();
        assert!(
            (e.mean - g).abs() < 4.0 * e.standard_error + 1e-3,
            "g = {g}: drawn {} +- {}",
            e.mean,
            e.standard_error
        );
    }
}

#[test]
fn the_sun_through_the_atmosphere_is_the_direct_columns_transmittance() {
    let atmosphere = earth();
    let model = prepare(ModelId::Riley, &atmosphere, &ModelSettings::default()).unwrap();
    let spectra = model.spectra();
    let sun = SunThroughAtmosphere::new(&atmosphere, spectra);
    let mut out = vec![0.0; 3];
    for (altitude, zenith_deg) in [
        (0.0f64, 0.0f64),
        (2000.0, 60.0),
        (5000.0, 85.0),
        (30_000.0, 30.0),
    ] {
        let r = BOTTOM_M + altitude;
        let mu = zenith_deg.to_radians().cos();
        let point = DVec3::new(0.0, 0.0, r);
        let direction = DVec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        sun.irradiance(point, direction, &mut out);
        let column = table_column(&atmosphere, r, mu);
        for w in 0..3 {
            let exact =
                spectra.solar_irradiance[w] * (-optical_depth(column, spectra.extinction[w])).exp();
            assert!(
                (out[w] - exact).abs() < 2e-3 * exact,
                "{altitude} m, sun {zenith_deg} deg, wavelength {w}: {} against {exact}",
                out[w]
            );
        }
    }
    // Below the horizon the ground hides the sun.
    sun.irradiance(
        DVec3::new(0.0, 0.0, BOTTOM_M + 1000.0),
        DVec3::new(1.0, 0.0, -0.2).normalize(),
        &mut out,
    );
    assert_eq!(out, [0.0; 3]);
}

fn layer(cover: f32) -> CloudLayer {
    let grid = CoverGrid::from_values("uniform cover", 4, 2, vec![cover; 8]).unwrap();
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    CloudLayer::new(LayerSettings::default(), BOTTOM_M, grid, phase).unwrap()
}

#[test]
fn without_cloud_the_answer_is_the_models_and_bad_settings_are_named() {
    let atmosphere = earth();
    let sky = prepare(ModelId::Hillaire, &atmosphere, &ModelSettings::default()).unwrap();
    let orders = orders(0.85);
    let phases: Vec<PhaseTableSampler> =
        (0..3).map(|w| PhaseTableSampler::new(&orders, w)).collect();
    let sun = SunThroughAtmosphere::new(&atmosphere, sky.spectra());
    let clear = layer(0.0);
    let ray = ViewRay::from_angles(BOTTOM_M, 100.0, 30.0, 40.0, 20.0, None).unwrap();
    let scene = PathScene {
        layer: &clear,
        orders: &orders,
        phases: &phases,
        sun: &sun,
        sky: sky.as_ref(),
        view_air: None,
        sun_direction: ray.sun_direction,
    };
    let traced = radiance_path_traced(&scene, &ray, &PathSettings::default()).unwrap();
    assert_eq!(traced.radiance, sky.radiance(&ray).unwrap());
    assert_eq!(traced.cloud_transmittance, 1.0);
    let bad = PathSettings {
        target_relative_error: 0.0,
        ..PathSettings::default()
    };
    let message = radiance_path_traced(&scene, &ray, &bad)
        .unwrap_err()
        .to_string();
    assert!(message.contains("target_relative_error = 0"), "{message}");
    let few = PathSettings {
        max_paths: 10,
        ..PathSettings::default()
    };
    let message = radiance_path_traced(&scene, &ray, &few)
        .unwrap_err()
        .to_string();
    assert!(message.contains("max_paths = 10"), "{message}");
}
