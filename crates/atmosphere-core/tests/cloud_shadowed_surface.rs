//! A surface in the cloud layer's shadow (`clouds/layer/shadowed_surface.rs`): the sun's
//! part of the model's irradiance, and only it, multiplied by the sun map's
//! transmittance at the surface point.

use atmosphere_core::atmosphere::presets::earth;
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::layer::shadowed_surface::radiance_with_shadowed_surface;
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};
use atmosphere_core::optics::phase::PhaseFunction;
use atmosphere_core::optics::surface_lighting::{SurfaceHit, radiance_with_surface};
use glam::DVec3;

const BOTTOM_M: f64 = 6_360_000.0;

/// A uniform cover `cover` under a camera 500 m up on the z axis, the sun 60 degrees
/// from the zenith.
fn map(cover: f32, extinction_per_m: f64, ray: &ViewRay) -> CloudSunMap {
    let grid = CoverGrid::from_values("uniform cover", 4, 2, vec![cover; 8]).unwrap();
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let settings = LayerSettings {
        extinction_per_m,
        detail_strength: 0.0,
        ..LayerSettings::default()
    };
    let layer = CloudLayer::new(settings, BOTTOM_M, grid, phase).unwrap();
    let resolution = SunMapResolution {
        cells: 16,
        levels: 2,
        steps: 64,
    };
    let grid = CloudSunMap::grid_for(layer.shell(), ray.origin_m, &resolution).unwrap();
    CloudSunMap::new(&layer, grid, ray.sun_direction, &resolution).unwrap()
}

/// Looking 30 degrees below the horizon at a slope facing the sun at 2 km.
fn scene() -> (ViewRay, SurfaceHit) {
    let ray = ViewRay::from_angles(BOTTOM_M, 500.0, 120.0, 60.0, 20.0, None).unwrap();
    let hit = SurfaceHit {
        distance_m: 900.0,
        normal: (DVec3::Z + 0.4 * ray.sun_direction).normalize(),
        albedo: vec![0.3; 3],
    };
    (ray, hit)
}

/// The surface's own term: the answer less the ray's radiance in front of it.
fn surface_term(
    model: &dyn SkyModel,
    ray: &ViewRay,
    hit: &SurfaceHit,
    map: Option<&CloudSunMap>,
) -> Vec<f64> {
    let a = earth();
    let answer = match map {
        Some(m) => radiance_with_shadowed_surface(model, &a, ray, hit, m).unwrap(),
        None => radiance_with_surface(model, &a, ray, hit).unwrap(),
    };
    let path = model
        .radiance(&ViewRay {
            max_distance_m: Some(hit.distance_m),
            ..*ray
        })
        .unwrap();
    answer
        .radiance
        .iter()
        .zip(&path.radiance)
        .map(|(l, p)| l - p)
        .collect()
}

fn model(id: ModelId) -> Box<dyn SkyModel> {
    let settings = ModelSettings {
        wavelengths_nm: vec![680.0, 550.0, 440.0],
        ..ModelSettings::default()
    };
    prepare(id, &earth(), &settings).unwrap()
}

#[test]
fn without_cloud_the_surface_is_lit_as_before() {
    let (ray, hit) = scene();
    let clear = map(0.0, 0.04, &ray);
    for id in [ModelId::Nishita, ModelId::Hillaire] {
        let m = model(id);
        let plain = surface_term(m.as_ref(), &ray, &hit, None);
        let shaded = surface_term(m.as_ref(), &ray, &hit, Some(&clear));
        for (p, s) in plain.iter().zip(&shaded) {
            assert!(*p > 0.0 && (p - s).abs() <= 1e-12 * p, "{id}: {p} {s}");
        }
    }
}

#[test]
fn the_cloud_dims_the_sun_by_the_maps_transmittance_and_leaves_the_sky() {
    let (ray, hit) = scene();
    let cloudy = map(0.6, 0.002, &ray);
    let end = ray.origin_m + ray.direction * hit.distance_m;
    let t = cloudy.transmittance(end);
    assert!(t > 0.05 && t < 0.8, "{t}");
    // Nishita lights a surface by the sun alone: the whole term scales by T.
    let nishita = model(ModelId::Nishita);
    let plain = surface_term(nishita.as_ref(), &ray, &hit, None);
    let shaded = surface_term(nishita.as_ref(), &ray, &hit, Some(&cloudy));
    for (p, s) in plain.iter().zip(&shaded) {
        assert!((s - t * p).abs() <= 1e-9 * p, "{s} {}", t * p);
    }
    // Hillaire adds its sky: under an opaque cloud the sky's light stays, and in the
    // blue more of the light is the sky's.
    let hillaire = model(ModelId::Hillaire);
    let opaque = map(1.0, 1.0, &ray);
    assert!(opaque.transmittance(end) < 1e-9);
    let plain = surface_term(hillaire.as_ref(), &ray, &hit, None);
    let dark = surface_term(hillaire.as_ref(), &ray, &hit, Some(&opaque));
    let shaded = surface_term(hillaire.as_ref(), &ray, &hit, Some(&cloudy));
    let ratio: Vec<f64> = dark.iter().zip(&plain).map(|(d, p)| d / p).collect();
    println!("hillaire: sky's share of the surface's light {ratio:?}, T = {t:.4}");
    assert!(ratio.iter().all(|&r| r > 0.01 && r < 0.6), "{ratio:?}");
    assert!(ratio[2] > ratio[0]);
    for w in 0..3 {
        let expected = dark[w] + t * (plain[w] - dark[w]);
        assert!((shaded[w] - expected).abs() <= 1e-9 * plain[w], "{w}");
    }
}
