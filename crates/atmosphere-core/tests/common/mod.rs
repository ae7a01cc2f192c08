//! Helpers shared by the model tests. Each test file uses some of them.
#![allow(dead_code)]

pub mod beams;
pub mod bruneton_tables;
pub mod hillaire;
pub mod voxel_ball;

use atmosphere_core::analysis::error_statistics::RelativeErrorStats;
use atmosphere_core::analysis::stability::venus_like;
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance, SkyModel, ViewRay};
use atmosphere_core::optics::geometry::horizon_mu;

pub fn earth() -> Atmosphere {
    Atmosphere::preset("earth").unwrap()
}

/// The ray from `altitude_m` above the ground, `view` degrees from the zenith, the sun
/// `sun` degrees from the zenith and `azimuth` degrees from the view, ending on the
/// ground or in space.
pub fn ray(a: &Atmosphere, altitude_m: f64, view: f64, sun: f64, azimuth: f64) -> ViewRay {
    ray_to(a, altitude_m, view, sun, azimuth, None)
}

/// [`ray`], ending on an object at `distance_m` if given.
pub fn ray_to(
    a: &Atmosphere,
    altitude_m: f64,
    view: f64,
    sun: f64,
    azimuth: f64,
    distance_m: Option<f64>,
) -> ViewRay {
    ViewRay::from_angles(
        a.bottom_radius_m,
        altitude_m,
        view,
        sun,
        azimuth,
        distance_m,
    )
    .unwrap()
}

/// Atmospheres at the edges of what the models take: the Earth, without and with a
/// hundred times its aerosols, Mars, and a Venus-thick atmosphere.
pub fn extreme_atmospheres() -> Vec<Atmosphere> {
    let earth = earth();
    vec![
        earth.clone(),
        earth.with_aerosol_scale(0.0),
        earth.with_aerosol_scale(100.0),
        Atmosphere::preset("mars").unwrap(),
        venus_like(),
    ]
}

/// Extreme rays over `a`, each labelled: the camera on the ground, a hair above it, at
/// and just either side of the top, far out; views up, horizontal and a hair either side,
/// either side of the horizon and down; the sun high, at and below the horizon; each ray
/// ending at every one of `distances` (`None`: on the ground or in space).
pub fn extreme_rays(a: &Atmosphere, distances: &[Option<f64>]) -> Vec<(String, ViewRay)> {
    let top = a.thickness_m();
    let mut rays = Vec::new();
    for altitude in [0.0, 1e-3, 1.0, top - 1e-6, top, top + 1.0, 1e5, 1e8] {
        let r = a.bottom_radius_m + altitude;
        let horizon = horizon_mu(r, a.bottom_radius_m).acos().to_degrees();
        let views = [
            0.0,
            45.0,
            89.999,
            90.0,
            90.001,
            horizon - 1e-9,
            horizon + 1e-9,
            135.0,
            180.0,
        ];
        for view in views {
            for sun in [0.0, 60.0, 89.9, 90.0, 95.0, 110.0] {
                for azimuth in [0.0, 120.0] {
                    for &distance in distances {
                        let label = format!(
                            "{}: altitude {altitude} view {view} sun {sun} azimuth {azimuth} \
                             distance {distance:?}",
                            a.name
                        );
                        rays.push((label, ray_to(a, altitude, view, sun, azimuth, distance)));
                    }
                }
            }
        }
    }
    rays
}

/// Fails unless every radiance of `r` is finite, non-negative and bounded, every
/// transmittance in [0, 1] and every standard error finite; `what` names the ray.
pub fn assert_sane(what: &str, r: &RayRadiance) {
    for w in 0..r.radiance.len() {
        let (l, t) = (r.radiance[w], r.transmittance[w]);
        assert!(l.is_finite() && l >= 0.0, "{what}: radiance {l}");
        // Nothing is brighter than the sun's irradiance spread over a hemisphere, times a
        // generous factor for the forward peak of aerosols.
        assert!(l < 50.0, "{what}: radiance {l} unbounded");
        assert!(
            t.is_finite() && (0.0..=1.0).contains(&t),
            "{what}: transmittance {t}"
        );
        assert!(
            r.radiance_std_error[w].is_finite(),
            "{what}: standard error {}",
            r.radiance_std_error[w]
        );
    }
}

/// Fails unless `model` answers a camera below the ground of `a`, and a ray with a
/// non-finite direction, with an error rather than a number.
pub fn assert_impossible_rays_are_errors(model: &dyn SkyModel, a: &Atmosphere) {
    let mut below = ray(a, 0.0, 0.0, 0.0, 0.0);
    below.origin_m.z -= 10.0;
    assert!(model.radiance(&below).is_err());
    let mut nan = ray(a, 0.0, 0.0, 0.0, 0.0);
    nan.direction.x = f64::NAN;
    assert!(model.radiance(&nan).is_err());
}

/// The default settings with single scattering only.
pub fn single() -> ModelSettings {
    ModelSettings {
        max_orders: Some(1),
        ..ModelSettings::default()
    }
}

/// The reference with all orders, its Monte Carlo run to `target_relative_error`.
pub fn all_orders_reference(a: &Atmosphere, target_relative_error: f64) -> Box<dyn SkyModel> {
    let settings = ModelSettings {
        target_relative_error,
        ..ModelSettings::default()
    };
    prepare(ModelId::Reference, a, &settings).unwrap()
}

/// Relative radiance differences of `model` against `reference` per wavelength.
pub fn relative_radiance(
    model: &dyn SkyModel,
    reference: &dyn SkyModel,
    ray: &ViewRay,
) -> Vec<f64> {
    let m = model.radiance(ray).unwrap();
    let r = reference.radiance(ray).unwrap();
    (0..m.radiance.len())
        .map(|w| m.radiance[w] / r.radiance[w] - 1.0)
        .collect()
}

/// The largest magnitude among `errors`.
pub fn worst(errors: &[f64]) -> f64 {
    errors.iter().fold(0.0, |a, e| a.max(e.abs()))
}

/// The largest relative difference of `a` from `b`, element by element.
pub fn worst_relative(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x / y - 1.0).abs())
        .fold(0.0, f64::max)
}

/// Luminance of `model` against `reference` on labelled rays, each printed: the signed
/// relative error per ray, in order, and their statistics.
pub fn luminance_errors<'a>(
    model: &dyn SkyModel,
    reference: &dyn SkyModel,
    rays: impl IntoIterator<Item = (String, &'a ViewRay)>,
) -> (Vec<f64>, RelativeErrorStats) {
    let color = SpectrumToColor::new(model.wavelengths_nm()).unwrap();
    let pairs: Vec<(f64, f64)> = rays
        .into_iter()
        .map(|(label, ray)| {
            let m = color.luminance_cd_m2(&model.radiance(ray).unwrap().radiance);
            let r = color.luminance_cd_m2(&reference.radiance(ray).unwrap().radiance);
            eprintln!(
                "{label}: model {m:.5} reference {r:.5} error {:+.4}",
                (m - r) / r
            );
            (m, r)
        })
        .collect();
    let signed = pairs.iter().map(|(m, r)| (m - r) / r).collect();
    (signed, RelativeErrorStats::new(pairs))
}
