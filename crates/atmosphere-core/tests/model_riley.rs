//! The `riley` model (Riley et al. 2004 section 4.1): its flat-earth limit against the
//! reference's single scattering, for Rayleigh and for aerosol, its stiff directions
//! against a direct integral of Eq. (14), its error on the earth preset against the
//! reference with all orders, and the sun below the horizon.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::density::DensityProfile;
use atmosphere_core::atmosphere::spectral::Spectral;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::riley::{FlatExponential, RileySettings};
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};

/// Earth's radius times 1000: flat for every path in these tests.
const FLAT_RADIUS_M: f64 = 6.36e9;

/// A flat, Rayleigh-only atmosphere, exp(-h / 8 km), 25 scale heights thick.
fn flat_rayleigh(albedo: f64) -> Atmosphere {
    let mut a = Atmosphere::preset("earth").unwrap();
    a.name = "flat".into();
    a.bottom_radius_m = FLAT_RADIUS_M;
    a.top_radius_m = FLAT_RADIUS_M + 25.0 * 8000.0;
    a.rayleigh.density = DensityProfile::exponential(8000.0);
    a.mie.scattering_per_m = Spectral::Constant { value: 0.0 };
    a.mie.extinction_per_m = Spectral::Constant { value: 0.0 };
    a.ozone.absorption_per_m = Spectral::Constant { value: 0.0 };
    a.ground_albedo = albedo;
    a.validate().unwrap();
    a
}

fn settings(orders: Option<u32>, target: f64) -> ModelSettings {
    ModelSettings {
        max_orders: orders,
        target_relative_error: target,
        seed: 11,
        ..ModelSettings::default()
    }
}

/// The model's settings with `riley`'s own options.
fn riley_settings(riley: RileySettings) -> ModelSettings {
    ModelSettings {
        options: riley.to_options(),
        ..settings(None, 0.01)
    }
}

/// A ray with view and sun given by their cosines to the zenith and the azimuth between.
fn ray(
    a: &Atmosphere,
    altitude_m: f64,
    view_up: f64,
    sun_up: f64,
    azimuth_deg: f64,
    distance_m: Option<f64>,
) -> ViewRay {
    ViewRay::from_angles(
        a.bottom_radius_m,
        altitude_m,
        view_up.clamp(-1.0, 1.0).acos().to_degrees(),
        sun_up.clamp(-1.0, 1.0).acos().to_degrees(),
        azimuth_deg,
        distance_m,
    )
    .unwrap()
}

#[test]
fn riley_is_registered() {
    let m = prepare(
        ModelId::Riley,
        &Atmosphere::preset("earth").unwrap(),
        &settings(None, 0.01),
    )
    .unwrap();
    assert_eq!(m.id(), ModelId::Riley);
    assert_eq!(m.wavelengths_nm(), &[680.0, 550.0, 440.0]);
}

/// A flat, aerosol-only atmosphere: the earth preset's Mie (exp(-h / 1.2 km), absorbing:
/// single-scattering albedo 0.9, Cornette-Shanks g = 0.8), no Rayleigh, no ozone.
fn flat_aerosol(albedo: f64) -> Atmosphere {
    let mut a = flat_rayleigh(albedo);
    a.rayleigh.scattering_per_m = Spectral::Constant { value: 0.0 };
    a.mie = Atmosphere::preset("earth").unwrap().mie;
    a.validate().unwrap();
    a
}

/// In the flat-earth limit (radius x1000, one species, so exactly Riley's assumptions)
/// the model, in the paper's form and in the default one, is the reference's order one, ground reflection included, within 1e-4: the
/// reference's planet still curves (1e-4 over 1300 km paths, tests/reference_physics.rs).
/// Sun elevations stay above 15 degrees, where the reference's sun disk is its centre.
/// Returns the worst relative difference.
fn assert_flat_limit(flat: &Atmosphere, form: RileySettings) -> f64 {
    let riley = prepare(ModelId::Riley, flat, &riley_settings(form)).unwrap();
    let reference = prepare(ModelId::Reference, flat, &settings(Some(1), 0.01)).unwrap();
    let top = flat.thickness_m();
    let cases: &[(f64, f64, f64, f64, Option<f64>)] = &[
        (0.0, 1.0, 0.6, 0.0, None),
        (0.0, 0.2, 0.9, 90.0, None),
        // Near the sun, in the aerosol's forward peak.
        (0.0, 0.3, 0.4, 0.0, None),
        (2000.0, 0.5, 0.3, 180.0, None),
        (5000.0, -0.3, 0.7, 30.0, None),
        (20_000.0, -0.8, 0.5, 120.0, None),
        (1000.0, 0.1, 0.5, 60.0, Some(30_000.0)),
        (3000.0, -0.05, 0.8, 10.0, Some(40_000.0)),
        // Above the top: the camera moves to the entry point.
        (top + 50_000.0, -0.6, 0.8, 0.0, None),
    ];
    let mut worst: f64 = 0.0;
    for &(alt, mu, mu0, az, d) in cases {
        let r = ray(flat, alt, mu, mu0, az, d);
        let got = riley.radiance(&r).unwrap();
        let want = reference.radiance(&r).unwrap();
        for w in 0..3 {
            let e_l = got.radiance[w] / want.radiance[w] - 1.0;
            let e_t = got.transmittance[w] / want.transmittance[w] - 1.0;
            worst = worst.max(e_l.abs()).max(e_t.abs());
            assert!(
                e_l.abs() < 1e-4 && e_t.abs() < 1e-4,
                "alt {alt} mu {mu} mu0 {mu0} d {d:?} w {w}: L {} vs {}, T {} vs {}",
                got.radiance[w],
                want.radiance[w],
                got.transmittance[w],
                want.transmittance[w]
            );
        }
    }
    worst
}

/// Rayleigh only: [`assert_flat_limit`].
#[test]
fn flat_earth_limit_equals_the_reference_single_scattering() {
    for form in [RileySettings::PAPER, RileySettings::default()] {
        let worst = assert_flat_limit(&flat_rayleigh(0.3), form);
        eprintln!("flat-earth limit, Rayleigh, {form:?}: worst relative difference {worst:.2e}");
    }
}

/// Aerosol only, absorbing and strongly forward-scattering: [`assert_flat_limit`].
#[test]
fn flat_earth_aerosol_equals_the_reference_single_scattering() {
    for form in [RileySettings::PAPER, RileySettings::default()] {
        let worst = assert_flat_limit(&flat_aerosol(0.3), form);
        eprintln!("flat-earth limit, aerosol, {form:?}: worst relative difference {worst:.2e}");
    }
}

/// Eq. (14) integrated directly: composite Simpson over the ray with the view's optical
/// depth from Eq. (11) and the sun's from Eq. (12), truncated where the integrand is
/// below e^-60 of its scale.
fn eq14_direct(beta: f64, h: f64, y0: f64, p: f64, l: f64, length: f64) -> f64 {
    let u = |s: f64| (-(y0 + p * s) / h).exp();
    let u0 = u(0.0);
    let view_tau = |s: f64| {
        let x = p * s / h;
        let phi = if x == 0.0 { 1.0 } else { -(-x).exp_m1() / x };
        beta * u0 * s * phi
    };
    let integrand = |s: f64| beta * u(s) * (-view_tau(s)).exp() * (-beta * h * u(s) / l).exp();
    // Where the integrand has died out: view optical depth 60, or 60 scale heights up.
    let mut end = length;
    if end.is_infinite() || view_tau(end) > 60.0 {
        let (mut lo, mut hi) = (0.0, 1.0);
        while view_tau(hi) < 60.0 && (p <= 0.0 || p * hi < 60.0 * h) {
            hi *= 2.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if view_tau(mid) < 60.0 && (p <= 0.0 || p * mid < 60.0 * h) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        end = end.min(hi);
    }
    let n = 400_000;
    let ds = end / n as f64;
    let mut sum = integrand(0.0) + integrand(end);
    for i in 1..n {
        sum += integrand(i as f64 * ds) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * ds / 3.0
}

/// Near the singular directions of the printed Eq. (15), p_y -> l_y and p_y -> 0 (both
/// signs, finite and infinite rays), the stable form agrees with the direct integral of
/// Eq. (14) to 1e-6, for a Rayleigh-like and a Mie-like species.
#[test]
fn stiff_directions_match_the_direct_integral() {
    for (beta, h) in [(3.31e-5, 8000.0), (4.44e-6, 1200.0)] {
        let flat = FlatExponential {
            beta_sea_level_per_m: beta,
            scale_height_m: h,
            irradiance: 1.0,
        };
        let l = 0.3;
        let mut cases = Vec::new();
        for eps in [0.0, 1e-12, -1e-12, 1e-8, -1e-8, 1e-4, -1e-4] {
            // View parallel to the sun's elevation: up to space, and a finite piece.
            cases.push((0.0, l + eps, f64::INFINITY));
            cases.push((1000.0, l + eps, 50_000.0));
            // Horizontal: finite rays both ways, infinite only upwards or level.
            cases.push((1000.0, eps, 100_000.0));
            if eps > 0.0 {
                cases.push((500.0, eps, f64::INFINITY));
            }
            // Looking down along the sun's elevation mirrored, to the ground.
            cases.push((2000.0, -l + eps, 2000.0 / (l - eps)));
        }
        for (y0, p, length) in cases {
            let closed = flat.single_scattering(y0, p, l, length, 1.0);
            let direct = eq14_direct(beta, h, y0, p, l, length);
            assert!(
                closed.is_finite() && (closed / direct - 1.0).abs() < 1e-6,
                "beta {beta} y0 {y0} p {p} K {length}: {closed} vs {direct}"
            );
        }
        // The infinite level ray is the limit: sunlight at the camera's height, all of it
        // scattered on the way.
        let level = flat.single_scattering(500.0, 0.0, l, f64::INFINITY, 1.0);
        let limit = (-beta * h * (-500.0 / h).exp() / l).exp();
        assert!((level / limit - 1.0).abs() < 1e-12, "{level} vs {limit}");
    }
}

/// Sweeping the view through the horizon (p_y = 0, where the flattened ray switches from
/// one leg to the two legs past the limb) and through the sun's elevation, the model's
/// radiance on the earth preset stays finite and changes smoothly: no step between
/// neighbours exceeds 1e-3 relative for steps of 1e-6 in p_y and at the singular
/// points themselves.
#[test]
fn stiff_directions_are_finite_and_continuous() {
    for form in [RileySettings::PAPER, RileySettings::default()] {
        stiff_directions_are_finite_and_continuous_in(form);
    }
}

fn stiff_directions_are_finite_and_continuous_in(form: RileySettings) {
    let earth = Atmosphere::preset("earth").unwrap();
    let m = prepare(ModelId::Riley, &earth, &riley_settings(form)).unwrap();
    let sun_up = 0.4f64;
    let sweeps = [(1000.0, 0.0), (0.0, 0.0), (1000.0, sun_up), (20_000.0, 0.0)];
    for (alt, centre) in sweeps {
        let mut previous: Option<Vec<f64>> = None;
        for i in -200..=200 {
            let p = centre + i as f64 * 1e-6;
            // From the ground, below the horizon is ground: sweep the sky side only.
            if alt == 0.0 && p < 0.0 {
                continue;
            }
            // View and sun in the same vertical plane, at the same azimuth.
            let r = ray(&earth, alt, p, sun_up, 0.0, None);
            let out = m.radiance(&r).unwrap();
            for w in 0..3 {
                assert!(
                    out.radiance[w].is_finite() && out.radiance[w] > 0.0,
                    "alt {alt} p {p}: {:?}",
                    out.radiance
                );
                assert!(
                    out.transmittance[w].is_finite() && (0.0..=1.0).contains(&out.transmittance[w])
                );
            }
            if let Some(prev) = &previous {
                for w in 0..3 {
                    let step = (out.radiance[w] / prev[w] - 1.0).abs();
                    assert!(step < 1e-3, "{form:?} alt {alt} p {p} w {w}: step {step}");
                }
            }
            previous = Some(out.radiance.clone());
        }
    }
}

/// In the paper's flat form the sun below the horizon gives no single scattering (the
/// sun term of the closed form is zero for l_y <= 0): radiance is finite and
/// non-negative, and it goes to zero continuously as the sun sets.
#[test]
fn flat_sun_below_the_horizon_gives_finite_non_negative_radiance() {
    let earth = Atmosphere::preset("earth").unwrap();
    let m = prepare(
        ModelId::Riley,
        &earth,
        &riley_settings(RileySettings::PAPER),
    )
    .unwrap();
    for sun_elevation_deg in [-20.0f64, -6.0, -0.5, -1e-9, 0.0, 1e-9] {
        let sun_up = sun_elevation_deg.to_radians().sin();
        for (alt, view_up) in [
            (0.0, 0.5),
            (0.0, 0.0),
            (1000.0, -0.5),
            (1e8, -0.9999),
            (30_000.0, -0.1),
        ] {
            let out = m
                .radiance(&ray(&earth, alt, view_up, sun_up, 45.0, None))
                .unwrap();
            // The air's light alone: the ray ended where it meets the ground as an object,
            // since the ground is lit by the sun at its own point (`surface_irradiance`),
            // which may be up where the camera's is not.
            let air = m
                .radiance(&ray(&earth, alt, view_up, sun_up, 45.0, Some(1e9)))
                .unwrap();
            for w in 0..3 {
                let (l, t) = (out.radiance[w], out.transmittance[w]);
                assert!(
                    l.is_finite() && l >= 0.0,
                    "sun {sun_elevation_deg} alt {alt}: {l}"
                );
                let l = air.radiance[w];
                // From far out the ray enters the air far from under the camera, where
                // the sun may still be up; elsewhere there is no light.
                if alt < earth.thickness_m() {
                    if sun_elevation_deg < 0.0 {
                        assert_eq!(l, 0.0, "sun {sun_elevation_deg} alt {alt}");
                    } else {
                        assert!(l < 1e-6, "sun {sun_elevation_deg} alt {alt}: {l}");
                    }
                }
                assert!(t.is_finite() && (0.0..=1.0).contains(&t));
            }
        }
    }
}

/// Relative errors of `model` against `reference` on daytime views from the ground of
/// the earth preset, grouped by view elevation: (view zenith deg, largest |error| over
/// suns, azimuths and wavelengths, signed mean).
fn daytime_errors(
    earth: &Atmosphere,
    model: &dyn SkyModel,
    reference: &dyn SkyModel,
) -> Vec<(f64, f64, f64)> {
    let mut out = Vec::new();
    for view_zenith in [0.0f64, 45.0, 70.0, 85.0] {
        let (mut worst, mut sum, mut n) = (0.0f64, 0.0, 0);
        for sun_zenith in [30.0f64, 60.0] {
            for azimuth in [0.0, 180.0] {
                let r = ViewRay::from_angles(
                    earth.bottom_radius_m,
                    0.0,
                    view_zenith,
                    sun_zenith,
                    azimuth,
                    None,
                )
                .unwrap();
                let got = model.radiance(&r).unwrap();
                let want = reference.radiance(&r).unwrap();
                for w in 0..3 {
                    let e = got.radiance[w] / want.radiance[w] - 1.0;
                    eprintln!(
                        "view {view_zenith} sun {sun_zenith} az {azimuth} w {w}: riley {:.4e} reference {:.4e} ({:+.1} %)",
                        got.radiance[w],
                        want.radiance[w],
                        100.0 * e
                    );
                    worst = worst.max(e.abs());
                    sum += e;
                    n += 1;
                }
            }
        }
        out.push((view_zenith, worst, sum / n as f64));
    }
    out
}

/// On the earth preset at daytime, from the ground, with the default settings (on the
/// sphere, shared extinction, ozone): against the reference with all orders (1 % standard
/// error) the model lacks multiple scattering, most of its error, in the blue above all.
/// Measured per view zenith angle (0, 45, 70, 85 deg; suns at 30 and 60 deg, azimuths 0
/// and 180, 680/550/440 nm): worst 35, 43, 46, 44 % (440 nm, away from the sun), means
/// -23, -23, -25, -29 %. Against the reference's order one: worst 1.0, 0.8, 0.8, 3.8 %,
/// means +0.3, +0.2, -0.2, -1.6 % (the paper's form: 6.5-25 % too bright). Bounds: all
/// orders, worst 50 %, means between -32 % and -18 %; order one, worst 6 %, means between
/// -3 % and +1 %.
#[test]
fn earth_daytime_error_against_the_reference_is_bounded() {
    let earth = Atmosphere::preset("earth").unwrap();
    let riley = prepare(ModelId::Riley, &earth, &settings(None, 0.01)).unwrap();
    let reference = prepare(ModelId::Reference, &earth, &settings(None, 0.01)).unwrap();
    let single = prepare(ModelId::Reference, &earth, &settings(Some(1), 0.01)).unwrap();
    for (orders, bound_worst, bound_mean) in [
        ("all orders", 0.50, (-0.32, -0.18)),
        ("order one", 0.06, (-0.03, 0.01)),
    ] {
        let against = if orders == "all orders" {
            reference.as_ref()
        } else {
            single.as_ref()
        };
        let errors = daytime_errors(&earth, riley.as_ref(), against);
        for (view_zenith, worst, mean) in &errors {
            eprintln!(
                "{orders}, view zenith {view_zenith}: worst {:.1} %, mean {:+.1} %",
                100.0 * worst,
                100.0 * mean
            );
        }
        for (view_zenith, worst, mean) in errors {
            assert!(
                worst < bound_worst && mean > bound_mean.0 && mean < bound_mean.1,
                "{orders}, view zenith {view_zenith}: worst {worst}, mean {mean}"
            );
        }
    }
}

/// The case of the issue that asked for the sphere: a level ray from the ground towards a
/// sun 2 degrees above the horizon. The paper's form leaves the aerosol's forward peak
/// undimmed by the air (and the air's light by the aerosol) on a flat ray that stays in
/// the densest air for ever: 7, 32 and 640 times too bright at 680, 550 and 440 nm. The
/// default is 5, 14 and 9 % too dark (ozone's fitted exponential puts too much of it in
/// the low air this ray crosses); bound 25 %.
#[test]
fn a_level_ray_towards_a_low_sun_is_dimmed_by_every_species() {
    let earth = Atmosphere::preset("earth").unwrap();
    let single = prepare(ModelId::Reference, &earth, &settings(Some(1), 0.01)).unwrap();
    let r = ViewRay::from_angles(earth.bottom_radius_m, 2.0, 90.0, 88.0, 0.0, None).unwrap();
    let want = single.radiance(&r).unwrap().radiance;
    for (form, bounds) in [
        (RileySettings::default(), (0.75, 1.25)),
        (RileySettings::PAPER, (2.0, f64::INFINITY)),
    ] {
        let m = prepare(ModelId::Riley, &earth, &riley_settings(form)).unwrap();
        let got = m.radiance(&r).unwrap().radiance;
        for w in 0..3 {
            let ratio = got[w] / want[w];
            eprintln!(
                "{form:?} w {w}: riley {:.4e} single {:.4e} ratio {ratio:.3}",
                got[w], want[w]
            );
            if w == 2 || form == RileySettings::default() {
                assert!(
                    ratio > bounds.0 && ratio < bounds.1,
                    "{form:?} w {w}: ratio {ratio}"
                );
            }
        }
    }
}
