//! The nishita model against the reference: it converges to the reference's single
//! scattering, its error falls with the number of view samples, it stays finite and
//! bounded on extreme rays, and its error against all orders is what
//! docs/models/nishita.md states.

mod common;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::nishita::{Nishita, NishitaSettings};
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};
use atmosphere_core::optics::geometry::horizon_mu;
use common::{
    all_orders_reference, assert_impossible_rays_are_errors, assert_sane, ray, ray_to, single,
};

fn nishita(a: &Atmosphere, view_samples: usize, heights: usize, angles: usize) -> Nishita {
    Nishita::prepare(
        a,
        &single(),
        NishitaSettings {
            view_samples,
            table_heights: heights,
            table_angles: angles,
        },
    )
    .unwrap()
}

/// Largest relative radiance difference over the wavelengths.
fn worst_relative(model: &dyn SkyModel, reference: &dyn SkyModel, ray: &ViewRay) -> f64 {
    let m = model.radiance(ray).unwrap();
    let r = reference.radiance(ray).unwrap();
    (0..m.radiance.len())
        .map(|w| (m.radiance[w] / r.radiance[w] - 1.0).abs())
        .fold(0.0, f64::max)
}

#[test]
fn nishita_is_registered() {
    let a = Atmosphere::preset("earth").unwrap();
    let m = prepare(ModelId::Nishita, &a, &ModelSettings::default()).unwrap();
    assert_eq!(m.id(), ModelId::Nishita);
    assert_eq!(m.wavelengths_nm(), &[680.0, 550.0, 440.0]);
}

/// With 4096 view samples and a 1024 x 256 table the model matches the reference's single
/// scattering and transmittance wherever the sun is well above the horizon: measured
/// worst 7.6e-6 in radiance (the ray 0.1 degree above the horizon) and 1.1e-7 in
/// transmittance, bound 3e-5 and 1e-6. Near the horizon the point sun of the paper
/// differs from the reference's disk: for the sun 2 degrees up the measured difference is
/// 1.7e-3, bound 3e-3.
#[test]
fn converges_to_the_reference_single_scattering() {
    let a = Atmosphere::preset("earth").unwrap();
    let reference = prepare(ModelId::Reference, &a, &single()).unwrap();
    let fine = nishita(&a, 4096, 256, 1024);
    let daytime = [
        ray(&a, 0.0, 0.0, 30.0, 0.0),
        ray(&a, 0.0, 60.0, 45.0, 90.0),
        ray(&a, 0.0, 89.9, 60.0, 0.0),
        ray(&a, 0.0, 92.0, 60.0, 90.0),
        ray(&a, 10_000.0, 95.0, 40.0, 20.0),
        ray(&a, 100_000.0, 107.0, 50.0, 0.0),
        ray(&a, 3e7, 179.5, 10.0, 0.0),
        ray(&a, 1e8, 180.0 - 3.4, 30.0, 0.0),
        ViewRay {
            max_distance_m: Some(20_000.0),
            ..ray(&a, 500.0, 88.0, 50.0, 45.0)
        },
    ];
    for ray in &daytime {
        let m = fine.radiance(ray).unwrap();
        let r = reference.radiance(ray).unwrap();
        for w in 0..3 {
            assert!(r.radiance[w] > 0.0, "{ray:?}");
            let rel = (m.radiance[w] / r.radiance[w] - 1.0).abs();
            assert!(rel < 3e-5, "{ray:?} wavelength {w}: radiance {rel:e}");
            let dt = (m.transmittance[w] - r.transmittance[w]).abs();
            assert!(dt < 1e-6, "{ray:?} wavelength {w}: transmittance {dt:e}");
        }
    }
    let sunset = ray(&a, 0.0, 85.0, 88.0, 0.0);
    let rel = worst_relative(&fine, reference.as_ref(), &sunset);
    assert!(rel < 3e-3, "sunset: {rel:e}");
}

/// On a sunset ray (view 85 degrees from the zenith towards a sun 2 degrees up) the error
/// against the reference's single scattering falls with the view samples: measured 0.63,
/// 0.090, 0.0050 for 4, 16, 64 samples (a midpoint rule's 1/N^2, until the point-sun floor
/// of 1.7e-3). Each step must cut it at least threefold.
#[test]
fn error_falls_as_view_samples_grow() {
    let a = Atmosphere::preset("earth").unwrap();
    let reference = prepare(ModelId::Reference, &a, &single()).unwrap();
    let sunset = ray(&a, 0.0, 85.0, 88.0, 0.0);
    let errors: Vec<f64> = [4, 16, 64]
        .into_iter()
        .map(|n| worst_relative(&nishita(&a, n, 64, 256), reference.as_ref(), &sunset))
        .collect();
    assert!(
        errors[1] < errors[0] / 3.0 && errors[2] < errors[1] / 3.0 && errors[2] < 0.01,
        "{errors:?}"
    );
}

/// Extreme rays give finite, non-negative radiance and transmittance in [0, 1]: camera on
/// the ground, on the top boundary and at 1e8 m; rays straight up and down, grazing the
/// horizon on either side, ending on objects; the sun from the zenith to 20 degrees below
/// the horizon; thin, default and coarse settings; earth, 100 times its aerosol, and Mars.
#[test]
fn extreme_rays_are_finite_and_bounded() {
    let earth = Atmosphere::preset("earth").unwrap();
    let atmospheres = [
        earth.clone(),
        earth.with_aerosol_scale(100.0),
        Atmosphere::preset("mars").unwrap(),
    ];
    for a in &atmospheres {
        let models = [
            nishita(a, 1, 2, 2),
            nishita(a, 100, 64, 256),
            nishita(a, 7, 5, 9),
        ];
        let top = a.thickness_m();
        for altitude in [0.0, 1e-3, 1.0, top - 1.0, top, top + 1.0, 1e8] {
            let r = a.bottom_radius_m + altitude;
            let horizon = horizon_mu(r, a.bottom_radius_m).acos().to_degrees();
            let views = [
                0.0,
                45.0,
                89.999_999,
                90.0,
                90.000_001,
                horizon - 1e-7,
                horizon,
                horizon + 1e-7,
                135.0,
                180.0,
            ];
            for view in views {
                for sun in [0.0, 60.0, 89.9, 90.0, 90.3, 95.0, 110.0] {
                    for azimuth in [0.0, 90.0, 180.0] {
                        for distance in [None, Some(1.0), Some(3e4), Some(1e9)] {
                            let ray = ray_to(a, altitude, view, sun, azimuth, distance);
                            for m in &models {
                                let what = format!("{}: {ray:?}", a.name);
                                assert_sane(&what, &m.radiance(&ray).unwrap());
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
    let m = nishita(&a, 16, 8, 16);
    assert_impossible_rays_are_errors(&m, &a);
}

/// With the default settings, against the reference with all orders on daytime views,
/// the model is dark by the missing multiple scattering: measured -6 % to -21 % at
/// 680 nm and -23 % to -41 % at 440 nm (worst: from the ground, 60 degrees from the zenith,
/// the sun 45 degrees up at 90 degrees azimuth). Asserted: between -48 % and 0 % (plus
/// three standard errors of the reference), and bluer light missing more than red.
#[test]
fn error_against_all_orders_on_daytime_views() {
    let a = Atmosphere::preset("earth").unwrap();
    let reference = all_orders_reference(&a, 0.01);
    let model = prepare(ModelId::Nishita, &a, &ModelSettings::default()).unwrap();
    let views = [
        ray(&a, 0.0, 0.0, 30.0, 0.0),
        ray(&a, 0.0, 60.0, 45.0, 90.0),
        ray(&a, 0.0, 89.9, 60.0, 0.0),
        ray(&a, 10_000.0, 95.0, 40.0, 20.0),
        ray(&a, 3e7, 179.5, 10.0, 0.0),
    ];
    for ray in &views {
        let m = model.radiance(ray).unwrap();
        let r = reference.radiance(ray).unwrap();
        let rel: Vec<f64> = (0..3)
            .map(|w| m.radiance[w] / r.radiance[w] - 1.0)
            .collect();
        for w in 0..3 {
            let noise = 3.0 * r.radiance_std_error[w] / r.radiance[w];
            assert!(
                rel[w] > -0.48 && rel[w] < noise,
                "{ray:?} wavelength {w}: {:?}",
                rel
            );
        }
        assert!(rel[2] < rel[0], "{ray:?}: {rel:?}");
    }
}
