//! Dobashi et al. 2002's q(u, v) table and sub-planes against independent numbers: the
//! table against a separate quadrature of its Eq. 9, the method against the closed form
//! of a point light's single scattering and against the reference on the sphere under a
//! spotlight (its Fig. 4), the plane interval of section 4.2.1 and the sub-plane counts
//! of section 4.2.2.

mod common;

use std::path::PathBuf;

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

fn sphere_scene() -> BeamScene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes/beams/sphere_spotlight.toml");
    BeamScene::load(&path).unwrap()
}

fn qtable(scene: &BeamScene, options: &[&str]) -> Qtable2002 {
    let settings = BeamSettings {
        options: ModelOptions::parse(options).unwrap(),
        ..BeamSettings::default()
    };
    Qtable2002::new(scene, &settings).unwrap()
}

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

#[test]
fn explore_sphere_scene() {
    let s = sphere_scene();
    let truth = method(BeamMethodId::Reference, &s, &[]);
    for opts in [
        &["epsilon=0"][..],
        &["epsilon=0", "shadow_map_px=2048"][..],
        &["epsilon=1e-6"][..],
        &["delta_max_m=0.1", "epsilon=1"][..],
    ] {
        let q = qtable(&s, opts);
        eprintln!(
            "{opts:?} dt {} planes {} sub {}",
            q.interval_m(),
            q.planes()[0].samples.len(),
            q.planes()[0].subplane_count()
        );
        let (mut diff, mut total, mut n) = (0.0, 0.0, 0);
        for j in 0..12 {
            for i in 0..8 {
                let ray = s.camera.ray(
                    (i as f64 + 0.5) * 300.0 / 8.0,
                    (j as f64 + 0.5) * 450.0 / 12.0,
                );
                let a = q.radiance(&ray).unwrap()[1];
                let b = truth.radiance(&ray).unwrap()[1];
                diff += (a - b).abs();
                total += b;
                n += 1;
            }
        }
        eprintln!("mean abs rel {} over {n}", diff / total);
    }
}
