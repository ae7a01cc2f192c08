//! The hillaire model's similarity-scaled multiple scattering (`ms_delta`,
//! `models/hillaire/similarity.rs`): the scaled coefficients against the delta-M
//! relations, no change without aerosol, the setting's reading, and the term against the
//! reference in haze and on clear skies. Tolerances are the measured errors with a margin
//! (docs/models/hillaire.md).

mod common;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::models::hillaire::similarity::scaled;
use atmosphere_core::models::hillaire::{Hillaire, HillaireSettings};
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};

use common::{all_orders_reference, earth, ray_to};

/// The delta fraction the docs recommend.
const DELTA: f64 = 0.45;

#[test]
fn scaled_coefficients_follow_the_delta_m_relations() {
    let a = Atmosphere::preset("hazy").unwrap();
    let spectra = Spectra::new(&a, &[680.0, 550.0, 440.0]);
    for f in [0.0, 0.45, 1.0] {
        let s = scaled(&spectra, f);
        for w in 0..3 {
            let (e, e_s) = (spectra.extinction[w], s.extinction[w]);
            let (m, m_s) = (spectra.mie_scattering[w], s.mie_scattering[w]);
            // sigma_s' = (1 - f) sigma_s, sigma_t' = sigma_t - f sigma_s; Rayleigh and
            // ozone unchanged.
            assert!(
                (m_s - (1.0 - f) * m).abs() <= 1e-15 * m,
                "f {f}: {m_s} vs {m}"
            );
            assert!(
                (e_s[1] - (e[1] - f * m)).abs() <= 1e-15 * e[1],
                "f {f}: {e_s:?}"
            );
            assert_eq!((e_s[0], e_s[2]), (e[0], e[2]));
            assert_eq!(s.rayleigh_scattering[w], spectra.rayleigh_scattering[w]);
            // The single-scattering albedo of the rest, (1 - f) w / (1 - f w), is at most
            // the true one; with f = 1 only absorption is left.
            if f == 1.0 {
                assert!((e_s[1] - (e[1] - m)).abs() <= 1e-15 * e[1]);
                assert_eq!(m_s, 0.0);
            }
            assert!(m_s / e_s[1] <= m / e[1] + 1e-15, "f {f}");
        }
    }
}

#[test]
fn the_delta_fraction_is_read_with_its_range() {
    let settings = |pairs: &[(&str, &str)]| {
        let mut options = ModelOptions::default();
        for (k, v) in pairs {
            options.set(k, v);
        }
        HillaireSettings::from_options(&options)
    };
    let read = settings(&[("ms_delta", "0.45")]).unwrap();
    assert_eq!(read.multiple_scattering_delta, 0.45);
    assert_eq!(HillaireSettings::default().multiple_scattering_delta, 0.0);
    for bad in ["1.5", "-0.1", "NaN"] {
        let error = settings(&[("ms_delta", bad)]).unwrap_err().to_string();
        assert!(
            error.contains("ms_delta") && error.contains("0..=1"),
            "{error}"
        );
    }
    let error = settings(&[("ms_delta", "0.45"), ("ms_order", "2")])
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("ms_delta=0.45") && error.contains("ms_order=0"),
        "{error}"
    );
}

fn model(a: &Atmosphere, delta: f64) -> Hillaire {
    let settings = HillaireSettings {
        multiple_scattering_delta: delta,
        ..HillaireSettings::default()
    };
    Hillaire::prepare(a, &ModelSettings::default(), settings).unwrap()
}

/// Only Mie is scaled: without aerosol every ray is the paper's to the last bit, and
/// with it the hazy sky is not (so the comparison can fail).
#[test]
fn without_aerosol_the_scaling_changes_nothing() {
    let clean = earth().with_aerosol_scale(0.0);
    let hazy = Atmosphere::preset("hazy").unwrap();
    let rays = |a: &Atmosphere| -> Vec<ViewRay> {
        [
            (2.0, 0.0, 30.0, 0.0),
            (2.0, 85.0, 45.0, 20.0),
            (10_000.0, 95.0, 40.0, 90.0),
        ]
        .into_iter()
        .map(|(h, view, sun, azimuth)| ray_to(a, h, view, sun, azimuth, None))
        .collect()
    };
    for (a, same) in [(&clean, true), (&hazy, false)] {
        let (paper, scaled) = (model(a, 0.0), model(a, DELTA));
        for ray in rays(a) {
            let p = paper.radiance(&ray).unwrap();
            let s = scaled.radiance(&ray).unwrap();
            assert_eq!(p.transmittance, s.transmittance);
            assert_eq!(
                p.radiance == s.radiance,
                same,
                "{:?} vs {:?}",
                p.radiance,
                s.radiance
            );
        }
    }
}

/// RMS over `rays` of the relative error of `model` against `reference`, of the sum of
/// the three wavelengths' radiances.
fn rms_error(model: &dyn SkyModel, reference: &dyn SkyModel, rays: &[ViewRay]) -> f64 {
    let mut sum = 0.0;
    for ray in rays {
        let m = model.radiance(ray).unwrap().radiance;
        let r = reference.radiance(ray).unwrap().radiance;
        let e = m.iter().sum::<f64>() / r.iter().sum::<f64>() - 1.0;
        sum += e * e;
    }
    (sum / rays.len() as f64).sqrt()
}

/// In haze (the `hazy` preset, Cornette-Shanks g = 0.7), ground, sun 45 degrees from the
/// zenith, rays 15 to 135 degrees from the sun, against the reference to 1 %.
#[test]
fn the_scaled_term_follows_the_reference_in_haze() {
    let a = Atmosphere::preset("hazy").unwrap();
    let reference = all_orders_reference(&a, 0.01);
    let rays: Vec<ViewRay> = [
        (30.0, 0.0),
        (60.0, 0.0),
        (80.0, 0.0),
        (0.0, 0.0),
        (60.0, 90.0),
        (85.0, 90.0),
        (45.0, 180.0),
        (80.0, 180.0),
    ]
    .into_iter()
    .map(|(view, azimuth)| ray_to(&a, 2.0, view, 45.0, azimuth, None))
    .collect();
    let paper = rms_error(&model(&a, 0.0), reference.as_ref(), &rays);
    let scaled = rms_error(&model(&a, DELTA), reference.as_ref(), &rays);
    eprintln!("hazy RMS, paper vs ms_delta={DELTA}: {paper:.4} {scaled:.4}");
    assert!(scaled < 0.5 * paper, "{scaled} vs {paper}");
    assert!(scaled < 0.07, "{scaled}");
}

/// On the clear Earth, daytime rays from the ground, 10 km and 100 km, and sunset.
#[test]
fn the_scaled_term_stays_close_on_clear_skies() {
    let a = earth();
    let reference = all_orders_reference(&a, 0.01);
    let day: Vec<ViewRay> = [
        (0.0, 0.0, 30.0, 0.0),
        (0.0, 45.0, 30.0, 90.0),
        (0.0, 80.0, 30.0, 180.0),
        (0.0, 89.0, 30.0, 60.0),
        (10_000.0, 70.0, 50.0, 45.0),
        (100_000.0, 100.0, 40.0, 90.0),
    ]
    .into_iter()
    .map(|(h, view, sun, azimuth)| ray_to(&a, h, view, sun, azimuth, None))
    .collect();
    let sunset: Vec<ViewRay> = [(85.0, 0.0), (60.0, 180.0), (0.0, 0.0), (80.0, 30.0)]
        .into_iter()
        .map(|(view, azimuth)| ray_to(&a, 0.0, view, 88.0, azimuth, None))
        .collect();
    let (paper, scaled) = (model(&a, 0.0), model(&a, DELTA));
    let day_errors = [
        rms_error(&paper, reference.as_ref(), &day),
        rms_error(&scaled, reference.as_ref(), &day),
    ];
    let sunset_errors = [
        rms_error(&paper, reference.as_ref(), &sunset),
        rms_error(&scaled, reference.as_ref(), &sunset),
    ];
    eprintln!(
        "earth RMS, paper vs ms_delta={DELTA}: daytime {day_errors:.4?}, sunset {sunset_errors:.4?}"
    );
    assert!(day_errors[1] < 0.035, "{day_errors:?}");
    assert!(sunset_errors[1] < 0.05, "{sunset_errors:?}");
}

/// The stability sweep (extreme rays and atmospheres, the sun crossing the horizon, the
/// top boundary) with the scaled term on, at the 100 directions of the report's setting
/// that meets its daytime target.
#[test]
fn the_scaled_term_passes_the_stability_sweep() {
    let mut settings = ModelSettings::default();
    settings.options.set("ms_delta", DELTA);
    settings.options.set("ms_directions", "100");
    let results = atmosphere_core::analysis::stability::run_with(
        atmosphere_core::models::id::ModelId::Hillaire,
        &settings,
    )
    .unwrap();
    let failed: Vec<_> = results.iter().filter(|r| !r.passed).collect();
    assert!(failed.is_empty(), "{failed:#?}");
}
