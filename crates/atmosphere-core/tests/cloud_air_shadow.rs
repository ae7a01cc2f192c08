//! The cloud layer's shadow in the air (`clouds/layer/air_shadow.rs`): under
//! an opaque deck with one gap a ray keeps the single scattering of its lit part only,
//! against a fine march of the same visibility along the whole ray; an opaque deck takes
//! all of it below the base; a block of terrain whose shadow falls in the gap takes its
//! part too, once; a clear map, or a ray above the base, changes nothing; every model
//! loses the same light (the march is the model's answer less one term, through the
//! atmosphere's own table).

use atmosphere_core::atmosphere::presets::earth;
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::clouds::layer::air_shadow::{AirShadow, CloudAirShadow};
use atmosphere_core::clouds::layer::sun_map::CloudSunMap;
use atmosphere_core::models::hillaire::Hillaire;
use atmosphere_core::models::hillaire::medium::Medium;
use atmosphere_core::models::hillaire::settings::HillaireSettings;
use atmosphere_core::models::hillaire::shafts::shadowed_single_over;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry;
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance, SkyModel, ViewRay};
use atmosphere_core::optics::phase::rayleigh;
use atmosphere_core::optics::view_segment::ViewSegment;
use atmosphere_core::shafts::{GnomonicGrid, SHAFT_SAMPLES, ShadowMap, SunVisibility};
use glam::DVec3;

const BOTTOM_M: f64 = 6_360_000.0;
const BASE_M: f64 = 3_000.0;
const CELLS: usize = 50;
const CELL_M: f64 = 2_000.0;
/// An optical depth no sunlight gets through.
const OPAQUE: f32 = 50.0;

fn model() -> Hillaire {
    let settings = ModelSettings {
        wavelengths_nm: vec![680.0, 550.0, 440.0],
        ..ModelSettings::default()
    };
    Hillaire::prepare(&earth(), &settings, HillaireSettings::default()).unwrap()
}

/// From 1 km up, 3 degrees above the horizon, the sun 55 degrees from the zenith at 40
/// degrees from the view's azimuth: the ray stays under a 3 km base for about 40 km.
fn ray(altitude_m: f64) -> ViewRay {
    ViewRay::from_angles(BOTTOM_M, altitude_m, 87.0, 55.0, 40.0, None).unwrap()
}

/// A deck of one level over the base sphere under the camera, `depth(column, row)` deep.
fn deck(ray: &ViewRay, depth: impl Fn(usize, usize) -> f32) -> CloudSunMap {
    let base = BOTTOM_M + BASE_M;
    let grid = GnomonicGrid::new(ray.origin_m, base, CELL_M, CELLS).unwrap();
    let depths = (0..CELLS * CELLS)
        .map(|k| depth(k % CELLS, k / CELLS))
        .collect();
    CloudSunMap {
        grid,
        sun: ray.sun_direction,
        base_radius_m: base,
        top_radius_m: base + 1_000.0,
        levels: 1,
        depths,
    }
}

/// The deck with a square gap 8 cells wide where the sun ray from the view ray's point 15 km
/// out crosses the base.
fn deck_with_gap(ray: &ViewRay) -> CloudSunMap {
    let open = deck(ray, |_, _| 0.0);
    let point = ray.origin_m + 15_000.0 * ray.direction;
    let r = point.length();
    let mu = point.dot(ray.sun_direction) / r;
    let base = open.base_radius_m;
    let to_base = -r * mu + (r * r * (mu * mu - 1.0) + base * base).sqrt();
    let at = open
        .grid
        .locate(point + to_base * ray.sun_direction)
        .unwrap();
    deck(ray, move |i, j| {
        if (i as f64 - at.column).abs() < 4.0 && (j as f64 - at.row).abs() < 4.0 {
            0.0
        } else {
            OPAQUE
        }
    })
}

/// The single scattering per unit solar irradiance that `1 - V` takes out of the whole
/// segment, by `steps` midpoint steps in planet-centred coordinates.
fn fine_shadowed_single(
    medium: &Medium<'_>,
    segment: &ViewSegment,
    visibility: &dyn SunVisibility,
    steps: usize,
) -> Vec<f64> {
    let n = medium.wavelengths();
    let sun = segment.sun_direction;
    let nu = segment.direction.dot(sun);
    let phase_m = medium.atmosphere.mie.phase.eval(nu);
    let dt = segment.length / steps as f64;
    let mut depth = vec![0.0; n];
    let mut out = vec![0.0; n];
    let mut sun_t = vec![0.0; n];
    for k in 0..steps {
        let x = segment.start + (k as f64 + 0.5) * dt * segment.direction;
        let r = x.length();
        let rho = medium.densities(r);
        let shadow = 1.0 - visibility.sun_visible(x, sun);
        medium.sun_transmittance(r, x.dot(sun) / r, &mut sun_t);
        for w in 0..n {
            let (s_r, s_m, extinction) = medium.coefficients(rho, w);
            let half = (-(depth[w] + 0.5 * extinction * dt)).exp();
            out[w] += half * shadow * sun_t[w] * (s_r * rayleigh(nu) + s_m * phase_m) * dt;
            depth[w] += extinction * dt;
        }
    }
    out
}

/// `ray`'s radiance in `model` with the cloud of `map` shadowing the air, beside the
/// model's terrain shadow.
fn with_cloud(model: &Hillaire, ray: &ViewRay, map: &CloudSunMap) -> RayRadiance {
    let air = AirShadow {
        terrain: model.terrain_shadow(),
        clouds: map,
    };
    CloudAirShadow::new(&earth(), model)
        .radiance(model, ray, &air)
        .unwrap()
}

/// What the cloud takes out of `ray`'s radiance per unit solar irradiance.
fn lost(model: &Hillaire, ray: &ViewRay, map: &CloudSunMap) -> Vec<f64> {
    let plain = model.radiance(ray).unwrap();
    let shaded = with_cloud(model, ray, map);
    let solar = &model.medium().spectra.solar_irradiance;
    (0..solar.len())
        .map(|w| (plain.radiance[w] - shaded.radiance[w]) / solar[w])
        .collect()
}

#[test]
fn a_gap_in_an_opaque_deck_keeps_the_light_of_the_lit_part_only() {
    let (model, ray) = (model(), ray(1_000.0));
    let medium = model.medium();
    let segment = ViewSegment::new(medium.atmosphere, &ray).unwrap().unwrap();
    let gap = deck_with_gap(&ray);
    let shaded = lost(&model, &ray, &gap);
    let air = AirShadow {
        terrain: None,
        clouds: &gap,
    };
    let expected = fine_shadowed_single(&medium, &segment, &air, 40_000);
    let opaque = deck(&ray, |_, _| OPAQUE);
    let all = fine_shadowed_single(
        &medium,
        &segment,
        &AirShadow {
            terrain: None,
            clouds: &opaque,
        },
        40_000,
    );
    let all_lost = lost(&model, &ray, &opaque);
    // The same march with 2,000 samples over its span: the error is the samples'.
    let (span, samples) = air.span(&segment).unwrap();
    assert_eq!(samples, SHAFT_SAMPLES);
    let mut dense = vec![0.0; 3];
    shadowed_single_over(&medium, &segment, &air, span, 2_000, &mut dense);
    for w in 0..3 {
        let (s, e, a) = (shaded[w], expected[w], all[w]);
        eprintln!(
            "w{w}: gap lost {s:.4e} fine {e:.4e} ({:.4}), 2000 samples ({:.5}), opaque lost {:.4e} fine {a:.4e} ({:.4}), lit share {:.3}",
            s / e - 1.0,
            dense[w] / e - 1.0,
            all_lost[w],
            all_lost[w] / a - 1.0,
            1.0 - e / a
        );
        // The gap lets through a real share of the light below the base.
        assert!(e > 0.1 * a && e < 0.9 * a, "w{w}: {e} of {a}");
        // Sample-limited: 32 samples across the gap's two edges.
        assert!((s - e).abs() <= 0.03 * a, "w{w}: gap {s} against {e}");
        assert!(
            (all_lost[w] - a).abs() <= 0.01 * a,
            "w{w}: opaque {} against {a}",
            all_lost[w]
        );
    }
}

#[test]
fn a_clear_map_or_a_ray_above_the_base_changes_nothing() {
    let model = model();
    for altitude in [1_000.0, 6_000.0] {
        let ray = ViewRay {
            direction: DVec3::new(0.2, 0.0, 1.0).normalize(),
            ..ray(altitude)
        };
        for map in [deck(&ray, |_, _| 0.0), deck(&ray, |_, _| OPAQUE)] {
            if altitude < BASE_M && map.depths[0] > 0.0 {
                continue;
            }
            let plain = model.radiance(&ray).unwrap();
            let shaded = with_cloud(&model, &ray, &map);
            assert_eq!(plain.radiance, shaded.radiance, "altitude {altitude}");
            assert_eq!(plain.transmittance, shaded.transmittance);
        }
    }
    let ray = ray(1_000.0);
    let plain = model.radiance(&ray).unwrap();
    let clear = with_cloud(&model, &ray, &deck(&ray, |_, _| 0.0));
    assert_eq!(plain.radiance, clear.radiance);
}

/// A block 3 km high and 8 km across whose near edge stands 1 km sunward of the view
/// ray's point 15 km out, in the deck's gap: its shadow crosses the ray there.
fn block_in_the_gap(ray: &ViewRay) -> ShadowMap {
    let grid = GnomonicGrid::new(ray.origin_m, BOTTOM_M, 500.0, 128).unwrap();
    let point = ray.origin_m + 15_000.0 * ray.direction;
    let up = point.normalize();
    let sunward = (ray.sun_direction - ray.sun_direction.dot(up) * up).normalize();
    let centre = (point + 5_000.0 * sunward).normalize();
    let heights = grid.sample(|d| {
        if (d - centre).length() * BOTTOM_M < 4_000.0 {
            3_000.0
        } else {
            0.0
        }
    });
    ShadowMap::new(grid, &heights, ray.sun_direction).unwrap()
}

#[test]
fn terrain_and_cloud_shadows_multiply() {
    let (mut model, ray) = (model(), ray(1_000.0));
    let gap = deck_with_gap(&ray);
    let cloud_only = lost(&model, &ray, &gap);
    let block = block_in_the_gap(&ray);
    model.set_terrain_shadow(Some(block.clone()));
    let medium = model.medium();
    let segment = ViewSegment::new(medium.atmosphere, &ray).unwrap().unwrap();
    let shaded = with_cloud(&model, &ray, &gap);
    let unshadowed = {
        let mut m = self::model();
        m.set_terrain_shadow(None);
        m.radiance(&ray).unwrap()
    };
    let both = AirShadow {
        terrain: Some(&block),
        clouds: &gap,
    };
    let expected = fine_shadowed_single(&medium, &segment, &both, 40_000);
    let all = fine_shadowed_single(
        &medium,
        &segment,
        &AirShadow {
            terrain: None,
            clouds: &deck(&ray, |_, _| OPAQUE),
        },
        40_000,
    );
    let solar = &medium.spectra.solar_irradiance;
    for w in 0..3 {
        let taken = (unshadowed.radiance[w] - shaded.radiance[w]) / solar[w];
        let e = expected[w];
        eprintln!(
            "w{w}: both lost {taken:.4e} fine {e:.4e} ({:.4}), cloud only {:.4e}",
            taken / e - 1.0,
            cloud_only[w]
        );
        // The block's shadow in the gap takes a real share more than the cloud alone.
        assert!(
            e > cloud_only[w] + 0.05 * all[w],
            "w{w}: {e} {}",
            cloud_only[w]
        );
        // Sample-limited: 32 samples across the gap's and the block's four edges.
        assert!(
            (taken - e).abs() <= 0.05 * all[w],
            "w{w}: {taken} against {e}"
        );
    }
}

#[test]
fn every_model_loses_the_same_light_under_the_deck() {
    let ray = ray(1_000.0);
    let gap = deck_with_gap(&ray);
    let air = AirShadow {
        terrain: None,
        clouds: &gap,
    };
    let settings = ModelSettings {
        wavelengths_nm: vec![680.0, 550.0, 440.0],
        ..ModelSettings::default()
    };
    let expected = lost(&model(), &ray, &gap);
    for id in [ModelId::Nishita, ModelId::Riley] {
        let model = registry::prepare(id, &earth(), &settings).unwrap();
        let plain = model.radiance(&ray).unwrap();
        let shaded = CloudAirShadow::new(&earth(), model.as_ref())
            .radiance(model.as_ref(), &ray, &air)
            .unwrap();
        for w in 0..3 {
            let taken = (plain.radiance[w] - shaded.radiance[w]) / settings_solar(&settings, w);
            eprintln!(
                "{id:?} w{w}: lost {taken:.4e}, hillaire {:.4e}",
                expected[w]
            );
            assert!(expected[w] > 0.0);
            assert!(
                (taken - expected[w]).abs() <= 1e-9 * expected[w],
                "{id:?} w{w}: {taken} against {}",
                expected[w]
            );
        }
    }
}

/// The solar irradiance at wavelength `w` of `settings`.
fn settings_solar(settings: &ModelSettings, w: usize) -> f64 {
    Spectra::new(&earth(), &settings.wavelengths_nm).solar_irradiance[w]
}
