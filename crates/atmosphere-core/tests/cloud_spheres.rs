//! The cloud spheres (Dobashi, Yamamoto and Nishita 2002, section 5.4) against closed
//! forms: a uniform deck's transmittance is exp of its profile's integral, and under an
//! overhead sun its single scattering is the slab's, (1 - exp(-2 tau)) / 2 times the
//! phase function, for any number of spheres; the attenuation textures hold the
//! vertical and slant columns above each sphere and the planet's shadow; a clear cover
//! leaves the model's answer as it is; bad settings and a sun other than the
//! textures' are refused by name.

use std::f64::consts::PI;

use atmosphere_core::atmosphere::presets::earth;
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::spheres::attenuation::SHADOWED_DEPTH;
use atmosphere_core::clouds::spheres::composite::{radiance_with_spheres, spheres_only};
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::geo::equirectangular::{direction, texel_centre};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, ViewRay};
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;

const BOTTOM_M: f64 = 6_360_000.0;
const G: f64 = 0.85;

fn orders(waves: usize) -> ScatteringOrders {
    ScatteringOrders::new(&vec![LegendreSeries::henyey_greenstein(G, 300); waves]).unwrap()
}

fn deck(cover: f32, extinction_per_m: f64, octaves: u32) -> CloudLayer {
    let grid = CoverGrid::from_values("uniform cover", 8, 4, vec![cover; 32]).unwrap();
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: G }).unwrap();
    let settings = LayerSettings {
        extinction_per_m,
        detail_strength: 0.0,
        method: LayerMethod::Octaves,
        octaves,
        ..LayerSettings::default()
    };
    CloudLayer::new(settings, BOTTOM_M, grid, phase).unwrap()
}

/// The spheres of `layer` with attenuation textures of 256 texels around: their read,
/// a quadratic B-spline, blurs the sun's column by about a texel, 1.4 degrees here, where
/// the closed forms below hold to 1e-3 (at 16 texels, 22.5 degrees, the slant columns
/// of the texels around an overhead sun's put 4 % into the read at its texel).
fn spheres(layer: &CloudLayer, count: u32, sun: DVec3) -> CloudSpheres {
    let settings = SphereSettings {
        count,
        attenuation_width: 256,
        ..SphereSettings::default()
    };
    CloudSpheres::new(layer, &settings, sun).unwrap()
}

fn sun_only(sun: DVec3) -> CloudLight {
    CloudLight {
        sun_direction: sun,
        sun_irradiance: vec![1.0],
        sky_irradiance: vec![0.0],
        up: DVec3::Z,
    }
}

/// The centre of texel (8, 5) of the 16 x 8 attenuation grid (33.75 S, 11.25 E): a
/// place where the textures' grid is exact, away from the poles' clamped rows.
fn texel_up() -> DVec3 {
    let (lat, lon) = texel_centre(16, 8, 8, 5);
    direction(lat, lon)
}

/// The vertical optical depth from sphere `k` (the middle of its shell) to the top.
fn column_above(s: &CloudSpheres, k: usize, point: DVec3) -> f64 {
    s.clouds().depth(k, point) / 2.0 + (k + 1..5).map(|q| s.clouds().depth(q, point)).sum::<f64>()
}

fn hg(nu: f64) -> f64 {
    (1.0 - G * G) / (4.0 * PI * (1.0 + G * G - 2.0 * G * nu).powf(1.5))
}

/// The default profile at full cover integrates to 0.75 of the thickness: a rise of
/// 0.05 over the lowest tenth, 0.5 flat, 0.2 over the fall from 0.6 to 1.
#[test]
fn a_uniform_deck_has_the_profiles_closed_form_transmittance() {
    let layer = deck(1.0, 0.002, 1);
    let tau: f64 = 0.002 * 1500.0 * 0.75;
    let up = texel_up();
    for count in [1, 5, 16] {
        let s = spheres(&layer, count, up);
        let (cloud, first) = spheres_only(
            &s,
            &orders(1),
            &sun_only(up),
            up * (BOTTOM_M + 4e5),
            -up,
            f64::INFINITY,
        );
        let t = cloud.transmittance[0];
        assert!(
            (t / (-tau).exp() - 1.0).abs() < 1e-4,
            "{count} spheres: T {t} against {}",
            (-tau).exp()
        );
        assert!((first.unwrap() - (4e5 - 3000.0)).abs() < 1e-6);
    }
}

/// Sun overhead, looking straight down: each depth below the top sees the sun and the
/// eye through the same column, so the single scattering is
/// E p(180 deg) int_0^tau exp(-2 t) dt = E p (1 - exp(-2 tau)) / 2, for every m: the
/// light integrated over each shell, not taken at its sphere, makes it exact.
#[test]
fn under_an_overhead_sun_the_spheres_scatter_as_the_slab() {
    for (extinction, count) in [(0.0005, 1), (0.002, 5), (0.002, 16), (0.04, 5)] {
        let layer = deck(1.0, extinction, 1);
        let tau = extinction * 1500.0 * 0.75;
        let up = texel_up();
        let s = spheres(&layer, count, up);
        let (cloud, _) = spheres_only(
            &s,
            &orders(1),
            &sun_only(up),
            up * (BOTTOM_M + 4e5),
            -up,
            f64::INFINITY,
        );
        let exact = hg(-1.0) * (1.0 - (-2.0 * tau).exp()) / 2.0;
        let l = cloud.radiance[0];
        assert!(
            (l / exact - 1.0).abs() < 2e-3,
            "tau {tau}, {count} spheres: {l} against {exact}"
        );
    }
}

#[test]
fn the_attenuation_textures_hold_the_columns_towards_the_sun() {
    let layer = deck(0.8, 0.002, 1);
    // Overhead: the column above each sphere.
    let point = texel_up();
    let s = spheres(&layer, 5, point);
    for k in 0..5 {
        let g = s.attenuation().depth(k, point);
        let above = column_above(&s, k, point);
        assert!(
            (g / above - 1.0).abs() < 1e-3,
            "sphere {k}: {g} against {above}"
        );
    }
    // The sun 60 degrees from the zenith: the slant column, 1 / cos 60 = 2 times the
    // vertical (the curvature adds 1e-4 over 1.5 km).
    let up = texel_up();
    let side = up.cross(DVec3::Z).normalize();
    let sun = up * 0.5 + side * 0.75f64.sqrt();
    let s = spheres(&layer, 5, sun);
    for k in 0..5 {
        let g = s.attenuation().depth(k, up);
        let slant = 2.0 * column_above(&s, k, up);
        assert!(
            (g / slant - 1.0).abs() < 2e-3,
            "sphere {k}: {g} against {slant}"
        );
    }
    // Opposite the sun the spheres lie in the planet's shadow.
    assert_eq!(s.attenuation().depth(2, -sun), SHADOWED_DEPTH);
}

#[test]
fn a_clear_cover_leaves_the_models_answer() {
    let model = prepare(ModelId::Riley, &earth(), &ModelSettings::default()).unwrap();
    let orders = orders(model.wavelengths_nm().len());
    let layer = deck(0.0, 0.04, 4);
    for (altitude, view, sun) in [(4e5, 170.0, 30.0), (5e4, 100.0, 60.0), (800.0, 60.0, 20.0)] {
        let ray = ViewRay::from_angles(BOTTOM_M, altitude, view, sun, 40.0, None).unwrap();
        let s = spheres(&layer, 5, ray.sun_direction);
        assert_eq!(
            radiance_with_spheres(model.as_ref(), &s, &orders, &ray).unwrap(),
            model.radiance(&ray).unwrap()
        );
    }
}

#[test]
fn bad_settings_and_a_foreign_sun_are_refused_by_name() {
    let layer = deck(0.5, 0.01, 4);
    let e = CloudSpheres::new(
        &layer,
        &SphereSettings {
            count: 17,
            ..SphereSettings::default()
        },
        DVec3::Z,
    )
    .unwrap_err();
    assert!(
        e.0.contains("cloud sphere count = 17 must lie in [1, 16]"),
        "{e}"
    );
    let e = CloudSpheres::new(
        &layer,
        &SphereSettings::default(),
        DVec3::new(0.0, 0.0, 2.0),
    )
    .unwrap_err();
    assert!(e.0.contains("is not a unit vector"), "{e}");
    let model = prepare(ModelId::Riley, &earth(), &ModelSettings::default()).unwrap();
    let ray = ViewRay::from_angles(BOTTOM_M, 4e5, 170.0, 30.0, 40.0, None).unwrap();
    let s = spheres(&layer, 5, DVec3::Z);
    let e = radiance_with_spheres(model.as_ref(), &s, &orders(3), &ray).unwrap_err();
    assert!(
        e.to_string()
            .contains("attenuation textures made for the sun"),
        "{e}"
    );
}

/// From orbit, a thick deck seen through the model: finite, bounded, and brighter than
/// the clear view's ground (albedo 0.1) where the sun is up (by 1.36, 1.29 and 1.16 at
/// 680, 550, 440 nm: the octaves keep little of a thick cloud's light, docs/clouds.md);
/// dark on the night side.
#[test]
fn from_orbit_a_deck_outshines_the_ground_by_day_and_not_by_night() {
    let model = prepare(ModelId::Riley, &earth(), &ModelSettings::default()).unwrap();
    let orders = orders(model.wavelengths_nm().len());
    let layer = deck(1.0, 0.04, 4);
    let day = ViewRay::from_angles(BOTTOM_M, 4e5, 175.0, 40.0, 30.0, None).unwrap();
    let s = spheres(&layer, 5, day.sun_direction);
    let cloudy = radiance_with_spheres(model.as_ref(), &s, &orders, &day).unwrap();
    let clear = model.radiance(&day).unwrap();
    for w in 0..3 {
        assert!(cloudy.radiance[w].is_finite() && cloudy.radiance[w] < 1.0);
        assert!(
            cloudy.radiance[w] > 1.1 * clear.radiance[w],
            "{cloudy:?} {clear:?}"
        );
        assert!(cloudy.transmittance[w] < 1e-4);
    }
    let night = ViewRay::from_angles(BOTTOM_M, 4e5, 175.0, 110.0, 30.0, None).unwrap();
    let s = spheres(&layer, 5, night.sun_direction);
    let dark = radiance_with_spheres(model.as_ref(), &s, &orders, &night).unwrap();
    for w in 0..3 {
        assert!(dark.radiance[w] < 0.01 * cloudy.radiance[w], "{dark:?}");
    }
}
