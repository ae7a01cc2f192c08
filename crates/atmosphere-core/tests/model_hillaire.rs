//! The Hillaire 2020 model as a whole: against the reference (single scattering and all
//! orders), in twilight, its ground light, pruning, settings, updates and the cache of
//! per-view tables (its tables are tested in model_hillaire_tables.rs, the stability
//! sweep in stability.rs). Tolerances are the measured errors with a margin
//! (docs/models/hillaire.md).

mod common;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::density::DensityProfile;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::hillaire::ground::{HemisphereQuadrature, sky_irradiance};
use atmosphere_core::models::hillaire::{Hillaire, HillaireSettings};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};
use atmosphere_core::optics::phase::PhaseFunction;

use common::hillaire::{directions, full_model};
use common::{all_orders_reference, earth, luminance_errors, ray_to, single, worst_relative};

fn daytime_rays(a: &Atmosphere) -> Vec<(&'static str, ViewRay)> {
    vec![
        ("ground zenith", ray_to(a, 0.0, 0.0, 30.0, 0.0, None)),
        ("ground 45", ray_to(a, 0.0, 45.0, 30.0, 90.0, None)),
        ("ground 80 away", ray_to(a, 0.0, 80.0, 30.0, 180.0, None)),
        ("ground 89", ray_to(a, 0.0, 89.0, 30.0, 60.0, None)),
        (
            "ground object 20 km",
            ray_to(a, 0.0, 85.0, 30.0, 30.0, Some(20_000.0)),
        ),
        ("10 km up", ray_to(a, 10_000.0, 70.0, 50.0, 45.0, None)),
        ("10 km down", ray_to(a, 10_000.0, 120.0, 30.0, 90.0, None)),
        (
            "10 km far ground",
            ray_to(a, 10_000.0, 95.0, 40.0, 0.0, None),
        ),
        ("100 km nadir", ray_to(a, 100_000.0, 180.0, 30.0, 0.0, None)),
        ("100 km limb", ray_to(a, 100_000.0, 100.0, 40.0, 90.0, None)),
        ("orbit nadir", ray_to(a, 400_000.0, 180.0, 40.0, 0.0, None)),
        ("orbit limb", ray_to(a, 400_000.0, 109.5, 50.0, 45.0, None)),
    ]
}

fn sunset_rays(a: &Atmosphere) -> Vec<(&'static str, ViewRay)> {
    vec![
        ("sunset towards sun", ray_to(a, 0.0, 85.0, 88.0, 0.0, None)),
        ("sunset away", ray_to(a, 0.0, 60.0, 88.0, 180.0, None)),
        ("sunset zenith", ray_to(a, 0.0, 0.0, 88.0, 0.0, None)),
    ]
}

/// Relative luminance errors of `model` against `reference`, and their RMS.
/// Signed relative luminance errors per named ray, and their RMS.
fn errors(
    model: &dyn SkyModel,
    reference: &dyn SkyModel,
    rays: &[(&str, ViewRay)],
) -> (Vec<f64>, f64) {
    let (e, stats) = luminance_errors(
        model,
        reference,
        rays.iter().map(|(n, r)| (n.to_string(), r)),
    );
    (e, stats.rms)
}

#[test]
fn hillaire_is_registered_with_the_papers_settings() {
    let a = earth();
    let m = prepare(ModelId::Hillaire, &a, &ModelSettings::default()).unwrap();
    assert_eq!(m.id(), ModelId::Hillaire);
    assert_eq!(m.wavelengths_nm(), &[680.0, 550.0, 440.0]);
    let d = HillaireSettings::default();
    assert_eq!(d.transmittance_size, (256, 64));
    assert_eq!(d.multiple_scattering_size, (32, 32));
    assert_eq!(d.multiple_scattering_directions, 64);
    assert_eq!(d.sky_view_size, (192, 108));
    assert_eq!(d.sky_view_samples, 30);
    assert_eq!(d.aerial_size.2, 32);
    assert_eq!(d.aerial_range_m, 32_000.0);
    // Global tables plus one view's: T (f64 x 3), Psi_ms and E_sky (f32 x 3), the
    // sky view (f32 x 3) and the volume (radiance and transmittance, f32 x 3).
    let (aw, ah, slices) = d.aerial_size;
    let expected =
        256 * 64 * 24 + 32 * 32 * 12 + d.ground_size * 12 + 192 * 108 * 12 + aw * ah * slices * 24;
    assert_eq!(m.table_bytes(), expected);
}

#[test]
fn settings_are_read_and_checked() {
    let o = ModelOptions::parse(&[
        "sky_view_samples=12",
        "ap_range_m=16000",
        "ms_directions=16",
    ])
    .unwrap();
    let s = HillaireSettings::from_options(&o).unwrap();
    assert_eq!(s.sky_view_samples, 12);
    assert_eq!(s.aerial_range_m, 16_000.0);
    assert_eq!(s.multiple_scattering_directions, 16);
    for bad in [
        "ms_directions=10",
        "sky_view_height=107",
        "ap_slices=1",
        "ap_range_m=0",
        "march_samples=0",
        "colour=blue",
    ] {
        let o = ModelOptions::parse(&[bad]).unwrap();
        assert!(HillaireSettings::from_options(&o).is_err(), "{bad}");
    }
    let settings = ModelSettings {
        options: ModelOptions::parse(&["sky_view_width=1"]).unwrap(),
        ..ModelSettings::default()
    };
    assert!(prepare(ModelId::Hillaire, &earth(), &settings).is_err());
}

/// Single scattering (`max_orders = Some(1)`: no Psi_ms, no sky light on the ground)
/// against the reference's converged single scattering: measured RMS 0.43 %, worst
/// 1.2 % (towards the sun 2 degrees above the horizon, the point sun against the
/// reference's disk), on daytime and sunset views.
#[test]
fn single_scattering_matches_the_reference() {
    let a = earth();
    let model = Hillaire::prepare(&a, &single(), HillaireSettings::default()).unwrap();
    assert!(model.multiple_scattering().is_none() && model.ground_irradiance().is_none());
    let reference = prepare(ModelId::Reference, &a, &single()).unwrap();
    let mut rays = daytime_rays(&a);
    rays.extend(sunset_rays(&a));
    let (e, rms) = errors(&model, reference.as_ref(), &rays);
    let worst = e.iter().fold(0.0f64, |m, e| m.max(e.abs()));
    eprintln!("single scattering: RMS {rms:.4}, worst {worst:.4}");
    assert!(rms < 0.008 && worst < 0.02, "rms {rms}, worst {worst}");
}

/// All orders against the reference (Monte Carlo to 1 %): measured on the daytime views
/// RMS 2.6 %, worst -5.4 % (the object 20 km away, near the horizon), every near-ground
/// view low (the isotropic multiple scattering of 64 directions, see
/// `multiple_scattering_lut_matches_brute_force`); sunset views -4.7 %, -3.3 %, -1.1 %.
#[test]
fn all_orders_match_the_reference() {
    let a = earth();
    let reference = all_orders_reference(&a, 0.01);
    let (e, rms) = errors(full_model(), reference.as_ref(), &daytime_rays(&a));
    let worst = e.iter().fold(0.0f64, |m, e| m.max(e.abs()));
    eprintln!("all orders, daytime: RMS {rms:.4}, worst {worst:.4}");
    assert!(rms < 0.035 && worst < 0.07, "rms {rms}, worst {worst}");
    let (e, rms) = errors(full_model(), reference.as_ref(), &sunset_rays(&a));
    let worst = e.iter().fold(0.0f64, |m, e| m.max(e.abs()));
    eprintln!("all orders, sunset: RMS {rms:.4}, worst {worst:.4}");
    assert!(worst < 0.07, "rms {rms}, worst {worst}");
}

/// With the sun below the horizon the sky stays lit by the Psi_ms term and by single
/// scattering high up, falls smoothly as the sun sinks, and against the reference at
/// 6 degrees below the horizon (civil twilight) the zenith's luminance is measured
/// -4.7 %.
#[test]
fn twilight_is_lit_and_falls_smoothly() {
    let a = earth();
    let model = full_model();
    let color = SpectrumToColor::new(model.wavelengths_nm()).unwrap();
    let zenith = |sun: f64| {
        color.luminance_cd_m2(
            &model
                .radiance(&ray_to(&a, 0.0, 0.0, sun, 0.0, None))
                .unwrap()
                .radiance,
        )
    };
    let mut last = zenith(89.0);
    for sun in [90.0, 91.0, 93.0, 96.0, 100.0, 110.0] {
        let l = zenith(sun);
        assert!(l > 0.0 && l < last, "sun {sun}: {l} after {last}");
        last = l;
    }
    // No jump as the sun's centre crosses the horizon.
    let (below, above) = (zenith(90.01), zenith(89.99));
    assert!((below / above - 1.0).abs() < 0.01, "{below} vs {above}");
    let reference = all_orders_reference(&a, 0.02);
    let twilight = [(
        "civil twilight zenith",
        ray_to(&a, 0.0, 0.0, 96.0, 0.0, None),
    )];
    let (e, _) = errors(model, reference.as_ref(), &twilight);
    assert!(e[0].abs() < 0.1, "{e:?}");
}

/// At zero aerosol, pruning leaves out the Mie terms and changes no answer.
#[test]
fn pruning_changes_nothing() {
    let a = earth().with_aerosol_scale(0.0);
    let prepare_with = |prune: bool| {
        Hillaire::prepare(
            &a,
            &ModelSettings {
                prune,
                ..ModelSettings::default()
            },
            HillaireSettings::default(),
        )
        .unwrap()
    };
    let (pruned, full) = (prepare_with(true), prepare_with(false));
    assert!(!pruned.medium().mie && full.medium().mie);
    let mut rays = daytime_rays(&a);
    rays.extend(sunset_rays(&a));
    for (name, ray) in &rays {
        assert_eq!(
            pruned.radiance(ray).unwrap(),
            full.radiance(ray).unwrap(),
            "{name}"
        );
    }
    // With aerosol, pruning has nothing to leave out.
    let hazy = Hillaire::prepare(
        &earth(),
        &ModelSettings::default(),
        HillaireSettings::default(),
    )
    .unwrap();
    assert!(hazy.medium().mie);
}

/// The paper's settings with small per-view tables: quick to rebuild, for the tests of
/// updates and of the view cache.
fn small_views() -> HillaireSettings {
    HillaireSettings {
        sky_view_size: (48, 28),
        aerial_size: (24, 24, 8),
        ..HillaireSettings::default()
    }
}

/// Fails unless `model` answers each of `rays` exactly as a model prepared from scratch
/// for `atmosphere` with `settings`.
fn assert_answers_as_prepared(
    model: &Hillaire,
    atmosphere: &Atmosphere,
    settings: HillaireSettings,
    rays: &[(&str, ViewRay)],
) {
    let fresh = Hillaire::prepare(atmosphere, &ModelSettings::default(), settings).unwrap();
    for (name, ray) in rays {
        assert_eq!(
            model.radiance(ray).unwrap(),
            fresh.radiance(ray).unwrap(),
            "{name}"
        );
    }
}

/// An update rebuilds the tables whose inputs changed, drops the per-view tables, and
/// answers as a model prepared from scratch.
#[test]
fn update_rebuilds_what_changed() {
    let a = earth();
    let settings = small_views();
    let mut model = Hillaire::prepare(&a, &ModelSettings::default(), settings).unwrap();
    let rays = daytime_rays(&a);
    for (_, ray) in &rays {
        model.radiance(ray).unwrap();
    }
    assert!(model.cached_views() > 0);
    assert!(model.update(&a).unwrap().is_empty());
    assert!(model.cached_views() > 0);

    let mut brighter = a.clone();
    brighter.ground_albedo = 0.3;
    let rebuilt = model.update(&brighter).unwrap();
    assert!(!rebuilt.contains(&"transmittance"), "{rebuilt:?}");
    assert!(rebuilt.contains(&"multiple scattering"), "{rebuilt:?}");
    assert_eq!(model.cached_views(), 0);
    assert_answers_as_prepared(&model, &brighter, settings, &rays);

    // The table of columns does not depend on coefficients, only on profiles.
    let hazy = brighter.with_aerosol_scale(3.0);
    let rebuilt = model.update(&hazy).unwrap();
    assert!(!rebuilt.contains(&"transmittance"), "{rebuilt:?}");
    let mut taller = hazy.clone();
    taller.rayleigh.density = DensityProfile::exponential(8_500.0);
    let rebuilt = model.update(&taller).unwrap();
    assert!(rebuilt.contains(&"transmittance"), "{rebuilt:?}");
    assert_answers_as_prepared(&model, &taller, settings, &rays);
    // Psi_ms takes every scattering as isotropic: the Mie phase function is not its input.
    let mut rounder = taller.clone();
    rounder.mie.phase = PhaseFunction::CornetteShanks { g: 0.7 };
    let rebuilt = model.update(&rounder).unwrap();
    assert_eq!(
        rebuilt,
        ["ground irradiance", "sky view and aerial perspective"],
        "{rebuilt:?}"
    );
    assert_answers_as_prepared(&model, &rounder, settings, &rays);
    let taller = rounder;
    // The solar spectrum scales the answers without a rebuild.
    let mut dimmer = taller.clone();
    dimmer.sun.irradiance_w_m2_nm = dimmer.sun.irradiance_w_m2_nm.scaled(0.5);
    let before = model.radiance(&rays[0].1).unwrap().radiance;
    assert!(model.update(&dimmer).unwrap().is_empty());
    let after = model.radiance(&rays[0].1).unwrap().radiance;
    for w in 0..3 {
        assert!((after[w] / before[w] - 0.5).abs() < 1e-12);
    }
}

/// The rays of one view share its tables; the cache keeps at most `view_cache` views.
#[test]
fn views_share_their_tables_in_a_bounded_cache() {
    let a = earth();
    let settings = HillaireSettings {
        view_cache: 2,
        ..small_views()
    };
    let model = Hillaire::prepare(&a, &ModelSettings::default(), settings).unwrap();
    for (view, azimuth) in directions() {
        model
            .radiance(&ray_to(&a, 2_000.0, view, 50.0, azimuth, Some(9_000.0)))
            .unwrap();
        model
            .radiance(&ray_to(&a, 2_000.0, view, 50.0, azimuth, None))
            .unwrap();
    }
    assert_eq!(model.cached_views(), 1);
    for sun in [10.0, 20.0, 30.0] {
        model
            .radiance(&ray_to(&a, 2_000.0, 0.0, sun, 0.0, None))
            .unwrap();
    }
    assert_eq!(model.cached_views(), 2);
    // A camera in space uses no per-view table.
    let fresh = Hillaire::prepare(&a, &ModelSettings::default(), settings).unwrap();
    fresh
        .radiance(&ray_to(&a, 400_000.0, 180.0, 30.0, 0.0, None))
        .unwrap();
    assert_eq!(fresh.cached_views(), 0);
}

/// The ground's sky irradiance: the table against a finer quadrature of the same sky
/// (4 x 8 zenith nodes, 32 azimuths, 200 segments per ray), measured within 2.2 % from
/// the sun at the zenith to 3 degrees below the horizon; and the ground's light seen
/// from 1 m against the reference (all orders): the sun's direct light plus the sky's,
/// measured +1.2 % (sun 30 degrees from the zenith) and -1.2 % (75 degrees).
#[test]
fn ground_light_matches_a_finer_quadrature_and_the_reference() {
    let a = earth();
    let model = full_model();
    let table = model.ground_irradiance().unwrap();
    let fine = HemisphereQuadrature {
        zenith_panels: 4,
        azimuths: 32,
        samples: 200,
    };
    let mut worst = 0.0f64;
    for mu_s in [1.0, 0.5, 0.1, -0.05] {
        let exact = sky_irradiance(&model.medium(), model.multiple_scattering(), mu_s, fine);
        let mut got = vec![0.0; 3];
        table.lookup(mu_s, &mut got);
        let e = worst_relative(&got, &exact);
        eprintln!("mu_s {mu_s}: E_sky/E_sun {got:.4?} vs {exact:.4?}: {e:.2e}");
        worst = worst.max(e);
    }
    assert!(worst < 0.03, "{worst}");
    let reference = all_orders_reference(&a, 0.01);
    let rays = [
        (
            "ground from 1 m, sun 30",
            ray_to(&a, 1.0, 180.0, 30.0, 0.0, None),
        ),
        (
            "ground from 1 m, sun 75",
            ray_to(&a, 1.0, 180.0, 75.0, 0.0, None),
        ),
    ];
    let (e, _) = errors(model, reference.as_ref(), &rays);
    assert!(e.iter().all(|e| e.abs() < 0.03), "{e:?}");
}
