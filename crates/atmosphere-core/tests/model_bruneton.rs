//! The Bruneton 2008 model: its parameterization, its error against the reference (single
//! scattering and all orders), the order loop's stopping rule, and stability on extreme
//! rays. Tolerances are the measured errors with a margin (docs/models/bruneton.md).

mod common;

use common::{all_orders_reference, earth, luminance_errors, single};
use std::sync::OnceLock;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::bruneton::parameterization::{
    AngleMapping, Radii, ScatteringSize, table_position, texel_parameters,
};
use atmosphere_core::models::bruneton::{Bruneton, BrunetonSettings};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};
use atmosphere_core::optics::geometry::{horizon_mu, ray_hits_ground};

fn radii(a: &Atmosphere) -> Radii {
    Radii {
        bottom_m: a.bottom_radius_m,
        top_m: a.top_radius_m,
    }
}

/// Small tables for tests of the order loop and stability.
fn small() -> BrunetonSettings {
    BrunetonSettings {
        scattering_size: ScatteringSize {
            r: 8,
            mu: 32,
            mu_s: 8,
            nu: 4,
            angles: AngleMapping::PAPER,
        },
        irradiance_size: (16, 4),
        view_samples: 20,
        ..BrunetonSettings::default()
    }
}

#[test]
fn parameterization_round_trips() {
    let a = earth();
    let m = radii(&a);
    for &h in &[0.0, 1.0, 1_000.0, 10_000.0, 59_999.0, 60_000.0] {
        let r = a.bottom_radius_m + h;
        assert!((m.r_from_u(m.u_r(r)) - r).abs() < 1e-6 * r, "r {r}");
        let horizon = horizon_mu(r, a.bottom_radius_m);
        for &mu in &[-1.0, -0.5, horizon - 1e-3, horizon + 1e-3, 0.0, 0.3, 1.0] {
            let ground = ray_hits_ground(r, mu, a.bottom_radius_m);
            let x = m.x_mu(r, mu, ground);
            assert!((0.0..=1.0).contains(&x), "r {r} mu {mu}: x {x}");
            // At the ground and, for rays leaving, at the top the mapping is degenerate.
            if h > 0.0 && !(r >= a.top_radius_m && mu >= 0.0) {
                let back = m.mu_from_x(r, x, ground);
                assert!((back - mu).abs() < 1e-6, "r {r} mu {mu}: {back}");
            }
        }
    }
    let twilight = AngleMapping {
        min_mu_s: -0.35,
        nu_by_angle: true,
        mu_s_knee: false,
        geometric_mu_s: false,
        nu_edge: false,
        nu_by_azimuth: false,
        mu_zenith: false,
    };
    let knee = AngleMapping {
        min_mu_s: -0.31,
        mu_s_knee: true,
        ..AngleMapping::PAPER
    };
    for angles in [AngleMapping::PAPER, twilight, knee] {
        let lowest = angles.min_mu_s;
        for &mu_s in &[lowest, -0.2, -0.1, 0.0, 0.5, 1.0] {
            assert!(
                (angles.mu_s_from_u(angles.u_mu_s(mu_s)) - mu_s).abs() < 1e-12,
                "{mu_s}"
            );
            let x = angles.irradiance_x_mu_s(mu_s);
            assert!((angles.irradiance_mu_s(x) - mu_s).abs() < 1e-12, "{mu_s}");
        }
        assert!(angles.u_mu_s(lowest).abs() < 1e-12 && (angles.u_mu_s(1.0) - 1.0).abs() < 1e-12);
        assert!(angles.irradiance_x_mu_s(lowest).abs() < 1e-12);
        for &nu in &[-1.0, 0.0, 0.7, 1.0] {
            assert!((angles.nu_from_u(angles.u_nu(nu)) - nu).abs() < 1e-12);
        }
    }
    // The paper's u_mu_s = (1 - exp(-3 mu_s - 0.6)) / (1 - exp(-3.6)).
    let paper = |mu_s: f64| (1.0 - (-3.0 * mu_s - 0.6f64).exp()) / (1.0 - (-3.6f64).exp());
    assert!((AngleMapping::PAPER.u_mu_s(0.3) - paper(0.3)).abs() < 1e-15);
    // With the knee, above -0.2 u_mu_s is the paper's curve squeezed into
    // [g0 / (g0 - 1)... 1]: (paper - g0) / (1 - g0), g0 = -3 (0.11) / (1 - exp(-3.6)) the
    // linear part's value at -0.31; below, u_mu_s is linear with the curve's slope.
    let g0 = -3.0 * 0.11 / (1.0 - (-3.6f64).exp());
    for &mu_s in &[-0.2, -0.1, 0.0, 0.3, 1.0] {
        let squeezed = (paper(mu_s) - g0) / (1.0 - g0);
        assert!((knee.u_mu_s(mu_s) - squeezed).abs() < 1e-12, "{mu_s}");
    }
    let slope =
        |m: &AngleMapping, mu_s: f64| (m.u_mu_s(mu_s + 1e-7) - m.u_mu_s(mu_s - 1e-7)) / 2e-7;
    let at_knee = slope(&knee, -0.2);
    for &mu_s in &[-0.3, -0.25, -0.2 - 1e-5, -0.2 + 1e-5] {
        assert!((slope(&knee, mu_s) / at_knee - 1.0).abs() < 1e-3, "{mu_s}");
    }
    // The knee changes nothing where min_mu_s is not below -0.2.
    let high = AngleMapping {
        min_mu_s: -0.15,
        ..AngleMapping::PAPER
    };
    let high_knee = AngleMapping {
        mu_s_knee: true,
        ..high
    };
    for &mu_s in &[-0.15, -0.1, 0.2] {
        assert_eq!(high.u_mu_s(mu_s), high_knee.u_mu_s(mu_s));
    }
    // By angle, u_nu is linear in the scattering angle: 90 deg in the middle.
    assert!((twilight.u_nu(0.0) - 0.5).abs() < 1e-15);
    assert!((twilight.u_nu(0.5) - 2.0 / 3.0).abs() < 1e-12);
    // Texels of reachable (r, mu) fall back on themselves with weight 0 (by nu, nu is
    // left out: it is clamped to what mu and mu_s allow; by azimuth it is not), also with
    // the sky's texels spread towards the zenith.
    let paper = BrunetonSettings::default().scattering_size;
    let spread = ScatteringSize {
        angles: AngleMapping {
            mu_zenith: true,
            nu_by_azimuth: true,
            ..AngleMapping::PAPER
        },
        ..paper
    };
    for (size, axes) in [(paper, 3), (spread, 4)] {
        for &(ir, imu, imus, inu) in &[
            (0, 70, 3, 2),
            (5, 10, 31, 7),
            (31, 127, 0, 0),
            (17, 40, 12, 4),
            (9, 65, 20, 5),
            (3, 100, 8, 6),
        ] {
            let (r, mu, mu_s, nu, ground) = texel_parameters(&m, &size, ir, imu, imus, inu);
            let p = table_position(&m, &size, r, mu, mu_s, nu, ground);
            let got = [ir, imu, imus, inu];
            for (k, (i, w)) in p.iter().enumerate().take(axes) {
                let at = if *w > 0.5 { i + 1 } else { *i };
                let off = w.min(1.0 - w);
                assert!(at == got[k] && off < 1e-6, "axis {k}: {p:?} for {got:?}");
            }
        }
    }
    // The sky's spread: its inverse, its ends, and from the ground the texels above 45
    // deg up (t = 0.03 there): 2 of the paper's 64, 7 spread.
    let zenith = AngleMapping {
        mu_zenith: true,
        ..AngleMapping::PAPER
    };
    for k in 0..=50 {
        let t = k as f64 / 50.0;
        assert!((zenith.sky_t(zenith.sky_x_mu(t)) - t).abs() < 1e-12, "{t}");
    }
    assert_eq!((zenith.sky_x_mu(0.0), zenith.sky_x_mu(1.0)), (0.0, 1.0));
    let above_45 = |angles: &AngleMapping| {
        let x = angles.sky_x_mu(m.x_mu(m.bottom_m, 45f64.to_radians().sin(), false));
        (x * 63.0).floor() as usize + 1
    };
    assert_eq!(above_45(&AngleMapping::PAPER), 2);
    assert_eq!(above_45(&zenith), 7);
}

/// Daytime rays: camera on the ground, at 1 km and at 10 km; sky, horizon-near, down
/// views and an object at 20 km.
fn daytime_rays(a: &Atmosphere) -> Vec<ViewRay> {
    let mut rays = Vec::new();
    for &(alt, vz, sz, az, d) in &[
        (0.0, 0.0, 30.0, 0.0, None),
        (0.0, 45.0, 30.0, 0.0, None),
        (0.0, 60.0, 45.0, 90.0, None),
        (0.0, 80.0, 60.0, 180.0, None),
        (0.0, 85.0, 30.0, 30.0, Some(20_000.0)),
        (1_000.0, 30.0, 20.0, 120.0, None),
        (1_000.0, 95.0, 40.0, 0.0, None),
        (10_000.0, 70.0, 50.0, 45.0, None),
        (10_000.0, 120.0, 30.0, 90.0, None),
    ] {
        rays.push(ViewRay::from_angles(a.bottom_radius_m, alt, vz, sz, az, d).unwrap());
    }
    rays
}

/// RMS and largest relative luminance error on the rays.
fn relative_rms(model: &dyn SkyModel, reference: &dyn SkyModel, rays: &[ViewRay]) -> (f64, f64) {
    let (_, stats) = luminance_errors(model, reference, rays.iter().map(|r| (format!("{r:?}"), r)));
    (stats.rms, stats.max)
}

fn single_model() -> &'static Bruneton {
    static MODEL: OnceLock<Bruneton> = OnceLock::new();
    MODEL.get_or_init(|| {
        Bruneton::prepare(
            &earth(),
            &ModelSettings {
                max_orders: Some(1),
                ..ModelSettings::default()
            },
        )
        .unwrap()
    })
}

fn full_model() -> &'static Bruneton {
    static MODEL: OnceLock<Bruneton> = OnceLock::new();
    MODEL.get_or_init(|| Bruneton::prepare(&earth(), &ModelSettings::default()).unwrap())
}

#[test]
fn single_scattering_matches_the_reference() {
    let a = earth();
    let reference = prepare(ModelId::Reference, &a, &single()).unwrap();
    let (rms, worst) = relative_rms(single_model(), reference.as_ref(), &daytime_rays(&a));
    eprintln!("single scattering: relative RMS {rms:.4}, worst {worst:.4}");
    // Measured: RMS 0.0043, worst 0.0080 (ground, 45 degrees).
    assert!(rms < 0.008 && worst < 0.015, "rms {rms}, worst {worst}");
}

#[test]
fn all_orders_match_the_reference() {
    let a = earth();
    let reference = all_orders_reference(&a, 0.003);
    let (rms, worst) = relative_rms(full_model(), reference.as_ref(), &daytime_rays(&a));
    eprintln!("all orders: relative RMS {rms:.4}, worst {worst:.4}");
    // Measured: RMS 0.0067, worst 0.0129 (object at 20 km); the reference's Monte Carlo
    // error is 0.3 % (at 1 % its noise alone reached 2 % on one ray).
    assert!(rms < 0.012 && worst < 0.02, "rms {rms}, worst {worst}");
}

#[test]
fn orders_stop_when_an_order_adds_less_than_the_threshold() {
    let a = earth();
    let settings = BrunetonSettings {
        order_threshold: 0.05,
        ..small()
    };
    let model = Bruneton::prepare_with(&a, &ModelSettings::default(), &settings).unwrap();
    let orders = model.orders();
    let (last, before) = orders.split_last().unwrap();
    assert!(orders.len() >= 3, "{orders:?}");
    assert!(last.share < 0.05, "{orders:?}");
    assert!(before.iter().all(|o| o.share >= 0.05), "{orders:?}");
    // Shares fall order after order.
    assert!(
        orders.windows(2).all(|w| w[1].share < w[0].share),
        "{orders:?}"
    );
    // A lower threshold computes more orders; max_orders caps them.
    let finer = Bruneton::prepare_with(
        &a,
        &ModelSettings::default(),
        &BrunetonSettings {
            order_threshold: 0.005,
            ..small()
        },
    )
    .unwrap();
    assert!(finer.orders().len() > orders.len(), "{:?}", finer.orders());
    let capped = Bruneton::prepare_with(
        &a,
        &ModelSettings {
            max_orders: Some(2),
            ..ModelSettings::default()
        },
        &BrunetonSettings {
            order_threshold: 0.0,
            ..small()
        },
    )
    .unwrap();
    assert_eq!(capped.orders().len(), 2);
}

#[test]
fn extreme_rays_are_finite_and_bounded() {
    let a = earth();
    let model = Bruneton::prepare_with(&a, &ModelSettings::default(), &small()).unwrap();
    let mut rays = Vec::new();
    for &alt in &[0.0, 1e-6, 1.0, 60_000.0, 1e5, 1e8] {
        let horizon = horizon_mu(a.bottom_radius_m + alt, a.bottom_radius_m)
            .acos()
            .to_degrees();
        for &vz in &[
            0.0,
            89.999,
            90.0,
            90.001,
            horizon - 1e-6,
            horizon + 1e-6,
            180.0,
        ] {
            for &sz in &[0.0, 89.9, 90.0, 95.0, 110.0, 180.0] {
                for d in [None, Some(1e-3), Some(1.0), Some(5e4), Some(1e9)] {
                    rays.push(
                        ViewRay::from_angles(a.bottom_radius_m, alt, vz, sz, 30.0, d).unwrap(),
                    );
                }
            }
        }
    }
    for ray in &rays {
        let out = model.radiance(ray).unwrap();
        for (l, t) in out.radiance.iter().zip(&out.transmittance) {
            assert!(l.is_finite() && *l >= 0.0 && *l < 10.0, "{ray:?}: {out:?}");
            assert!((0.0..=1.0).contains(t), "{ray:?}: {out:?}");
        }
    }
    // Looking away from the planet from space: nothing, fully transparent.
    let away = ViewRay::from_angles(a.bottom_radius_m, 1e8, 0.0, 30.0, 0.0, None).unwrap();
    let out = model.radiance(&away).unwrap();
    assert!(out.radiance.iter().all(|l| *l == 0.0));
    assert!(out.transmittance.iter().all(|t| *t == 1.0));
}

fn radiances(model: &dyn SkyModel, rays: &[ViewRay]) -> Vec<Vec<f64>> {
    rays.iter()
        .map(|ray| model.radiance(ray).unwrap().radiance)
        .collect()
}

fn assert_same(a: &[Vec<f64>], b: &[Vec<f64>]) {
    for (x, y) in a.iter().flatten().zip(b.iter().flatten()) {
        assert!((x - y).abs() <= 1e-12 * y.abs(), "{x} vs {y}");
    }
}

#[test]
fn update_rebuilds_only_what_changed_and_equals_a_fresh_build() {
    let a = earth();
    let rays = daytime_rays(&a);
    let settings = ModelSettings::default();
    let mut model = Bruneton::prepare_with(&a, &settings, &small()).unwrap();
    assert!(model.update(&a).unwrap().is_empty());

    let mut brighter_ground = a.clone();
    brighter_ground.ground_albedo = 0.3;
    assert_eq!(
        model.update(&brighter_ground).unwrap(),
        ["multiple scattering", "irradiance"]
    );
    let fresh = Bruneton::prepare_with(&brighter_ground, &settings, &small()).unwrap();
    assert_same(&radiances(&model, &rays), &radiances(&fresh, &rays));

    let mut dimmer_sun = brighter_ground.clone();
    dimmer_sun.sun.irradiance_w_m2_nm = a.sun.irradiance_w_m2_nm.scaled(0.5);
    assert!(model.update(&dimmer_sun).unwrap().is_empty());
    let fresh = Bruneton::prepare_with(&dimmer_sun, &settings, &small()).unwrap();
    assert_same(&radiances(&model, &rays), &radiances(&fresh, &rays));

    // Aerosol coefficients change extinction but not the columns of matter.
    let mut hazier = dimmer_sun.clone();
    hazier.mie.scattering_per_m = a.mie.scattering_per_m.scaled(2.0);
    hazier.mie.extinction_per_m = a.mie.extinction_per_m.scaled(2.0);
    assert_eq!(
        model.update(&hazier).unwrap(),
        ["single scattering", "multiple scattering", "irradiance"]
    );
    let fresh = Bruneton::prepare_with(&hazier, &settings, &small()).unwrap();
    assert_same(&radiances(&model, &rays), &radiances(&fresh, &rays));
}

#[test]
fn pruning_mie_at_zero_aerosol_changes_no_answer() {
    let mut a = earth();
    a.mie.scattering_per_m = a.mie.scattering_per_m.scaled(0.0);
    a.mie.extinction_per_m = a.mie.extinction_per_m.scaled(0.0);
    let with = |prune| {
        Bruneton::prepare_with(
            &a,
            &ModelSettings {
                prune,
                ..ModelSettings::default()
            },
            &small(),
        )
        .unwrap()
    };
    let (pruned, full) = (with(true), with(false));
    assert!(pruned.mie_pruned() && !full.mie_pruned());
    assert!(pruned.tables()[0].single_mie.is_none());
    assert!(pruned.table_bytes() < full.table_bytes());
    let mut rays = daytime_rays(&a);
    rays.push(ViewRay::from_angles(a.bottom_radius_m, 1e6, 100.0, 60.0, 10.0, None).unwrap());
    assert_same(&radiances(&pruned, &rays), &radiances(&full, &rays));
    // Aerosol back: Mie work again.
    let mut model = pruned;
    let rebuilt = model.update(&earth()).unwrap();
    assert!(rebuilt.contains(&"single scattering"), "{rebuilt:?}");
    assert!(!model.mie_pruned() && model.tables()[0].single_mie.is_some());
}

/// Each order's part against the reference's, per ray (docs/models/bruneton.md, "The cause
/// of the multiple-scattering bias"). Slow: run with
/// `cargo test -p atmosphere-core --test model_bruneton -- --ignored --nocapture`.
#[test]
#[ignore]
fn orders_against_the_reference() {
    let a = earth();
    let rays = daytime_rays(&a);
    let color = SpectrumToColor::new(&ModelSettings::default().wavelengths_nm).unwrap();
    let luminances = |model: &dyn SkyModel| -> Vec<f64> {
        radiances(model, &rays)
            .iter()
            .map(|l| color.luminance_cd_m2(l))
            .collect()
    };
    let settings = |max_orders| ModelSettings {
        max_orders,
        target_relative_error: 0.003,
        ..ModelSettings::default()
    };
    let reference = |orders| {
        luminances(
            prepare(ModelId::Reference, &a, &settings(orders))
                .unwrap()
                .as_ref(),
        )
    };
    let model = |orders| luminances(&Bruneton::prepare(&a, &settings(orders)).unwrap());
    let (r1, r2, ra) = (reference(Some(1)), reference(Some(2)), reference(None));
    let (b1, b2, ba) = (model(Some(1)), model(Some(2)), model(None));
    let mut squares = [0.0; 2];
    eprintln!("| ray | single | order 2 part | orders 3+ part | all orders |");
    for i in 0..rays.len() {
        let single = b1[i] / r1[i] - 1.0;
        let second = ((b2[i] - b1[i]) - (r2[i] - r1[i])) / r2[i];
        let higher = ((ba[i] - b2[i]) - (ra[i] - r2[i])) / ra[i];
        let all = ba[i] / ra[i] - 1.0;
        squares[0] += single * single;
        squares[1] += all * all;
        eprintln!("| {i} | {single:+.4} | {second:+.4} | {higher:+.4} | {all:+.4} |");
    }
    let n = rays.len() as f64;
    eprintln!(
        "RMS: single {:.4}, all orders {:.4}",
        (squares[0] / n).sqrt(),
        (squares[1] / n).sqrt()
    );
}

/// Small tables with options.
fn small_with(options: &[&str]) -> Bruneton {
    let mut settings = ModelSettings {
        max_orders: Some(2),
        ..ModelSettings::default()
    };
    for item in ["r=8", "mu=32", "mu_s=16", "nu=4", "view_samples=20"]
        .iter()
        .chain(options)
    {
        let (k, v) = item.split_once('=').unwrap();
        settings.options.set(k, v);
    }
    Bruneton::prepare(&earth(), &settings).unwrap()
}

/// Green radiance from the ground 10 deg up towards a sun at `sun_zenith_deg`.
fn towards_the_sun(model: &Bruneton, sun_zenith_deg: f64) -> f64 {
    let a = earth();
    let ray =
        ViewRay::from_angles(a.bottom_radius_m, 2.0, 80.0, sun_zenith_deg, 0.0, None).unwrap();
    model.radiance(&ray).unwrap().radiance[1]
}

#[test]
fn suns_below_the_papers_range_are_resolved_with_a_lower_min_mu_s() {
    // The paper's table ends at mu_s = -0.2 (101.5 deg): suns below it are clamped, so
    // the sky of 103 and 106 deg differs only by the view-sun angle; with
    // min_mu_s = -0.35 it darkens as the sun sinks.
    let paper = small_with(&[]);
    let (p103, p106) = (
        towards_the_sun(&paper, 103.0),
        towards_the_sun(&paper, 106.0),
    );
    let lower = small_with(&["min_mu_s=-0.35"]);
    let (l103, l106) = (
        towards_the_sun(&lower, 103.0),
        towards_the_sun(&lower, 106.0),
    );
    eprintln!("103 / 106 deg: paper {p103:e} / {p106:e}, min_mu_s=-0.35 {l103:e} / {l106:e}");
    assert!(p103 / p106 < 1.1, "{p103} {p106}");
    assert!(l103 / l106 > 3.0 && l106 > 0.0, "{l103} {l106}");
    // The linear extension below -0.2 down to -0.31 (the sun 18 deg down) resolves them
    // too, and agrees with the shifted curve within the error of either's mu_s axis.
    let knee = small_with(&["min_mu_s=-0.31", "mu_s_knee=true"]);
    let (k103, k106) = (towards_the_sun(&knee, 103.0), towards_the_sun(&knee, 106.0));
    eprintln!("103 / 106 deg: min_mu_s=-0.31 mu_s_knee=true {k103:e} / {k106:e}");
    assert!(k103 / k106 > 3.0 && k106 > 0.0, "{k103} {k106}");
    assert!((k103 / l103 - 1.0).abs() < 0.3, "{k103} {l103}");
}

#[test]
fn the_sun_disk_lights_the_ground_while_its_centre_is_just_below_the_horizon() {
    let a = earth();
    let alpha = a.sun.angular_radius_rad;
    let point = glam::DVec3::new(0.0, 0.0, a.bottom_radius_m);
    let at = |model: &Bruneton, below_rad: f64| {
        let z = (0.5 * std::f64::consts::PI + below_rad).cos();
        let sun = glam::DVec3::new((1.0 - z * z).sqrt(), 0.0, z);
        let tilted = atmosphere_core::models::sky_model::SurfacePoint {
            point_m: point,
            normal: glam::DVec3::new(1.0, 0.0, 1.0),
            sun_direction: sun,
        };
        model.surface_irradiance(&tilted).unwrap()[0]
    };
    let point_sun = small_with(&[]);
    let disk = small_with(&["sun_disk=true"]);
    // Centre half a radius below the horizon: a point sun is set, a disk's top shows;
    // two radii below both are set (the sky's light differs by the tables' small change).
    let (p, d) = (at(&point_sun, 0.5 * alpha), at(&disk, 0.5 * alpha));
    assert!(d > 1.5 * p, "{p} {d}");
    let (p, d) = (at(&point_sun, 2.0 * alpha), at(&disk, 2.0 * alpha));
    assert!((p - d).abs() < 1e-3 * p, "{p} {d}");
    // High up the disk and the point agree.
    let (p, d) = (at(&point_sun, -0.3), at(&disk, -0.3));
    assert!((p - d).abs() < 1e-3 * p, "{p} {d}");
}

#[test]
fn geometric_interpolation_along_mu_s_follows_the_twilight_sky() {
    use atmosphere_core::models::bruneton::tables::along_mu_s;
    // Exact for an exponential, equal to the texels at their ends, linear where a texel
    // is not positive.
    let (a, b) = (2.0, 2.0 * (-1.5f64).exp());
    assert!((along_mu_s(a, b, 0.4, true) - 2.0 * (-0.6f64).exp()).abs() < 1e-12);
    assert_eq!(along_mu_s(a, b, 0.0, true), a);
    assert!((along_mu_s(a, b, 1.0, true) - b).abs() < 1e-15);
    assert_eq!(along_mu_s(a, 0.0, 0.25, true), 1.5);
    // The sky towards the sun 10 deg up from the ground, the sun 3-10 deg below the
    // horizon: S of 16 sun-angle texels against 128 (the same method resolved along
    // mu_s), linearly and geometrically between texels.
    let fine = small_with(&["mu_s=128"]);
    let linear = small_with(&[]);
    let geometric = small_with(&["geometric_mu_s=true"]);
    let (mut e_linear, mut e_geometric) = (0.0, 0.0);
    let suns: Vec<f64> = (0..15).map(|i| 93.0 + 0.5 * i as f64).collect();
    for &sun in &suns {
        let truth = towards_the_sun(&fine, sun);
        e_linear += (towards_the_sun(&linear, sun) / truth - 1.0).powi(2);
        e_geometric += (towards_the_sun(&geometric, sun) / truth - 1.0).powi(2);
    }
    let rms = |e: f64| 100.0 * (e / suns.len() as f64).sqrt();
    eprintln!(
        "twilight, 16 mu_s texels against 128: linear {:.2} %, geometric {:.2} % RMS",
        rms(e_linear),
        rms(e_geometric)
    );
    assert!(rms(e_geometric) < 0.5 * rms(e_linear));
    // Towards a sun above the horizontal (every look-up and node of the ray and its
    // texels above it) nothing changes.
    for sun in [30.0, 60.0, 89.0] {
        assert_eq!(
            towards_the_sun(&linear, sun),
            towards_the_sun(&geometric, sun)
        );
    }
}
