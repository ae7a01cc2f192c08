//! Dobashi et al. 2002's q(u, v) table and sub-planes against independent numbers: the
//! table against a separate quadrature of its Eq. 9, the method against the closed form
//! of a point light's single scattering and against the reference on the sphere under a
//! spotlight (its Fig. 4), the plane interval of section 4.2.1 and the sub-plane counts
//! of section 4.2.2.

mod common;

use atmosphere_core::beams::medium::MediumSpectra;
use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::{BeamMethod, BeamSettings};
use atmosphere_core::beams::methods::qtable2002::Qtable2002;
use atmosphere_core::beams::methods::qtable2002::q_table::{QExtent, QTable};
use atmosphere_core::beams::ray::SceneRay;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::optics::phase::PhaseFunction;
use common::beams::*;
use glam::DVec3;

#[test]
fn table_nodes_hold_eq_9_integrated_independently() {
    let medium = MediumSpectra {
        scattering_per_m: vec![0.03, 0.2],
        extinction_per_m: vec![0.035, 0.3],
    };
    let phase = PhaseFunction::NishitaHazy;
    // Two nodes a side: the nodes are the extent's corners.
    for (u, v) in [(-7.0, 0.3), (-0.4, 0.05), (2.5, 4.0), (0.0, 12.0)] {
        let extent = QExtent {
            u_min_m: u,
            u_max_m: u + 50.0,
            v_min_m: v,
            v_max_m: v * 3.0,
        };
        let table = QTable::new(&medium, &phase, extent, [2, 2], 1.2);
        for w in 0..2 {
            // The interval [0, 1.2] of a ray passing the light at distance v, starting
            // at u along it: the attenuation from the interval's start, as in Eq. 9.
            let expected = point_light_airlight(
                DVec3::new(u, -v, 0.0),
                DVec3::X,
                DVec3::ZERO,
                1.0,
                medium.scattering_per_m[w],
                medium.extinction_per_m[w],
                &phase,
                (0.0, 1.2),
            );
            let q = table.q(u, v, w);
            assert!(
                relative(q, expected) < 1e-9,
                "({u}, {v}) {w}: {q} vs {expected}"
            );
        }
    }
}

#[test]
fn converged_table_matches_the_point_light_closed_form_within_half_a_percent() {
    let (sigma_s, sigma_a, intensity) = (0.05, 0.02, 800.0);
    let light = [1.0, 6.0, -3.0];
    for phase in [ISOTROPIC, "{ kind = \"nishita_hazy\" }"] {
        let s = scene(
            &medium(sigma_s, sigma_a, phase),
            &point_light(light, intensity),
        );
        let q = qtable(
            &s,
            &[
                "delta_min_m=0.1",
                "delta_max_m=0.1",
                "table_u=512",
                "table_v=512",
            ],
        );
        let end = 20.7 / (sigma_s + sigma_a);
        for (x, y) in [(16.0, 12.0), (8.0, 4.0), (24.0, 20.0), (30.0, 1.0)] {
            let ray = s.camera.ray(x, y);
            let expected = point_light_airlight(
                ray.origin_m,
                ray.direction,
                DVec3::from(light),
                intensity,
                sigma_s,
                sigma_s + sigma_a,
                &s.medium.phase,
                (0.0, end),
            );
            for l in q.radiance(&ray).unwrap() {
                let e = relative(l, expected);
                assert!(e < 0.005, "{phase} pixel ({x}, {y}): {l} vs {expected}");
            }
        }
    }
}

/// The mean absolute error of `L_550` against the reference over a grid of 8 x 12 of
/// the sphere scene's pixels, relative to the reference's mean (the paper's "average
/// error in intensities").
fn sphere_scene_error(s: &BeamScene, options: &[&str]) -> f64 {
    let truth = method(BeamMethodId::Reference, s, &[]);
    grid_mean_error(s, &qtable(s, options), truth.as_ref(), (8, 12), 0.5)
}

#[test]
fn the_sphere_under_a_spotlight_matches_the_reference_as_sub_planes_are_added() {
    // Fig. 4 of the paper: 1.5 % mean error against ray tracing (docs/beams/qtable2002.md
    // has the numbers here).
    let s = sphere_scene();
    let none = sphere_scene_error(&s, &["epsilon=1"]);
    let paper = sphere_scene_error(&s, &[]);
    let all = sphere_scene_error(&s, &["epsilon=0"]);
    assert!(paper < 0.03, "epsilon=0.01: {paper}");
    assert!(
        paper < 0.5 * none,
        "epsilon=0.01: {paper}, no sub-planes {none}"
    );
    assert!(all < 0.005, "epsilon=0: {all}");
}

#[test]
fn a_ray_through_the_spheres_shadow_gets_only_its_lit_parts() {
    // From the camera toward (0, 5, 0): through the umbra below the sphere (the light
    // at 20 m, the sphere of 2 m at 10 m) between lit stretches of the cone.
    let s = sphere_scene();
    let ray = SceneRay::new(
        s.camera.position_m,
        DVec3::new(0.0, 5.0, 0.0) - s.camera.position_m,
        None,
    )
    .unwrap();
    let truth = method(BeamMethodId::Reference, &s, &[])
        .radiance(&ray)
        .unwrap()[1];
    let mut open = s.clone();
    open.occluders.primitives.remove(0);
    let unshadowed = method(BeamMethodId::Reference, &open, &[])
        .radiance(&ray)
        .unwrap()[1];
    assert!(
        truth < 0.8 * unshadowed,
        "{truth} vs {unshadowed} unshadowed"
    );
    let got = qtable(&s, &["epsilon=0"]).radiance(&ray).unwrap()[1];
    assert!(relative(got, truth) < 0.01, "{got} vs {truth}");
    let got_open = qtable(&open, &["epsilon=0"]).radiance(&ray).unwrap()[1];
    assert!(
        relative(got_open, unshadowed) < 0.01,
        "{got_open} vs {unshadowed}"
    );
}

#[test]
fn sub_planes_appear_only_where_f_l_exceeds_epsilon() {
    let s = sphere_scene();
    let paper = qtable(&s, &[]);
    let planes = &paper.planes()[0];
    // f_l on the centre ray against the closed-form integral of Eq. 8 over each
    // interval (intensity 1, the spot's profile and cone left to f_h as in Eq. 6).
    let light = s.lights[0].position_m().unwrap();
    let dt = paper.interval_m();
    assert!((dt - 1.2).abs() < 1e-9, "interval {dt}");
    let medium = s.medium.at(&BeamSettings::default().wavelengths_nm);
    for (k, f) in planes.centre_f_l.iter().enumerate() {
        let d = planes.first_depth_m + k as f64 * dt;
        let expected = (0..3)
            .map(|w| {
                point_light_airlight(
                    s.camera.position_m,
                    s.camera.forward,
                    light,
                    1.0,
                    medium.scattering_per_m[w],
                    medium.extinction_per_m[w],
                    &s.medium.phase,
                    (d, d + dt),
                )
            })
            .fold(0.0, f64::max);
        assert!(
            relative(*f, expected) < 0.01,
            "plane {k}: {f} vs {expected}"
        );
    }
    let total: f64 = planes.centre_f_l.iter().sum();
    // Each interval's m_k is floor(share / epsilon), at least 1: sub-planes only where
    // the share is at least twice epsilon, the most where f_l peaks.
    let check = |q: &Qtable2002, epsilon: f64| {
        let planes = &q.planes()[0];
        let mut inserted = 0;
        for (f, m) in planes.centre_f_l.iter().zip(&planes.samples) {
            let share = f / total;
            let expected = if share >= 2.0 * epsilon {
                (share / epsilon).floor() as usize
            } else {
                1
            };
            assert_eq!(*m, expected, "share {share}, epsilon {epsilon}");
            inserted += m - 1;
        }
        assert_eq!(inserted, planes.subplane_count());
        inserted
    };
    let count = check(&paper, 0.01);
    assert!(count > 16, "{count} sub-planes at epsilon = 0.01");
    assert_eq!(check(&qtable(&s, &["epsilon=0.5"]), 0.5), 0);
    let peak = planes.centre_f_l.iter().copied().fold(0.0, f64::max) / total;
    let epsilon = peak / 3.0;
    let few = qtable(&s, &[&format!("epsilon={epsilon}")]);
    assert!(check(&few, epsilon) > 0);
    let samples = &few.planes()[0].samples;
    let brightest = planes
        .centre_f_l
        .iter()
        .enumerate()
        .fold((0, 0.0), |b, (k, f)| if *f > b.1 { (k, *f) } else { b })
        .0;
    assert_eq!(samples[brightest], 3);
    assert!(samples.contains(&1));
    // Epsilon 0: the most sub-planes everywhere.
    let all = qtable(&s, &["epsilon=0", "max_subplanes=16"]);
    assert!(all.planes()[0].samples.iter().all(|&m| m == 17));
}

#[test]
fn the_interval_is_the_widest_whose_table_stays_within_i_max() {
    let s = sphere_scene();
    let small = ["table_u=64", "table_v=64"];
    let at = |dt: f64| {
        let opts = [
            small[0],
            small[1],
            &format!("delta_min_m={dt}"),
            &format!("delta_max_m={dt}"),
        ];
        qtable(&s, &opts).table().max_value()
    };
    let (q_06, q_07) = (at(0.6), at(0.7));
    assert!(
        q_06 < q_07,
        "the table grows with the interval: {q_06}, {q_07}"
    );
    let chosen = |i_max: f64| {
        let opts = [small[0], small[1], &format!("i_max={i_max}")];
        qtable(&s, &opts).interval_m()
    };
    assert!((chosen(0.5 * (q_06 + q_07)) - 0.6).abs() < 1e-9);
    assert!((chosen(1e12) - 1.2).abs() < 1e-9);
    assert!((chosen(1e-12) - 0.1).abs() < 1e-9);
}

#[test]
fn epsilon_zero_and_extreme_media_stay_finite_and_bad_settings_are_named() {
    // Density 0 and 1e3 m^-1, a light inside an occluder and a light at the camera are
    // in tests/beams_stability.rs for every method; here epsilon 0 at those media.
    let light = point_light([0.0, 3.0, 0.0], 100.0);
    for (sigma_s, sigma_a) in [(0.0, 0.0), (1e3, 1e-3), (0.05, 0.01)] {
        let s = scene(&medium(sigma_s, sigma_a, ISOTROPIC), &light);
        let q = qtable(&s, &["epsilon=0", "max_subplanes=8"]);
        let l = q.radiance(&s.camera.ray(16.0, 12.0)).unwrap();
        assert!(l.iter().all(|x| x.is_finite() && *x >= 0.0), "{l:?}");
        if sigma_s < 1.0 {
            assert_eq!(l[0] == 0.0, sigma_s == 0.0, "{l:?}");
        }
    }
    let s = sphere_scene();
    let settings = |options: &[&str]| BeamSettings {
        options: ModelOptions::parse(options).unwrap(),
        ..BeamSettings::default()
    };
    for (options, message) in [
        (
            &["delta_min_m=2", "delta_max_m=1"][..],
            "delta_min_m=2 exceeds delta_max_m=1",
        ),
        (&["epsilon=-1"][..], "epsilon=-1 is outside 0..=1"),
        (&["d0_m=0"][..], "d0_m=0 is outside 0.001..=10000000"),
        (&["table_u=1"][..], "table_u=1 is outside 2..=4096"),
        (
            &["gpu_raster_planes=1"][..],
            "gpu_raster_planes=1: expected true or false",
        ),
        (
            &["subplanes_per_ray=true", "gpu_raster_planes=true"][..],
            "subplanes_per_ray=true with gpu_raster_planes=true",
        ),
        (
            &["weighted_samples=yes"][..],
            "weighted_samples=yes: expected true or false",
        ),
        (
            &["delta_min_m=1e-4", "delta_max_m=1e-4", "d0_m=1e7"][..],
            "planes 0.0001 m apart; at most 65536",
        ),
    ] {
        let e = match Qtable2002::new(&s, &settings(options)) {
            Ok(_) => panic!("{options:?} accepted"),
            Err(e) => e.to_string(),
        };
        assert!(e.contains(message), "{options:?}: {e}");
    }
}
