//! qtable2002's samples weighted by g and counted on each ray (`weighted_samples`,
//! `subplanes_per_ray`; not Dobashi et al. 2002's) against the reference where the
//! paper's product of means fails: rays that pass the sphere scene's spotlight within an
//! interval's length, and the scene's mean error (the paper's measure, 1.5 % for its
//! Fig. 4).

mod common;

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamMethod;
use atmosphere_core::beams::ray::SceneRay;
use atmosphere_core::beams::scene::BeamScene;
use common::beams::*;
use glam::DVec3;

const BOTH: [&str; 2] = ["weighted_samples=true", "subplanes_per_ray=true"];

#[test]
fn rays_that_pass_the_spotlight_closely_are_right_with_both_settings() {
    // From the camera to points below the light (20 m up, its cone 25 degrees about the
    // vertical): the ray crosses the cone where it is narrower than the 1.2 m interval
    // and 1 / s^2 changes by orders of magnitude across it.
    let s = sphere_scene();
    let truth = method(BeamMethodId::Reference, &s, &[]);
    let paper = qtable(&s, &[]);
    let both = qtable(&s, &BOTH);
    for below_m in [0.4, 0.7, 1.5] {
        let ray = SceneRay::new(
            s.camera.position_m,
            DVec3::new(0.0, 20.0 - below_m, 0.0) - s.camera.position_m,
            None,
        )
        .unwrap();
        let expected = truth.radiance(&ray).unwrap()[1];
        let by_paper = relative(paper.radiance(&ray).unwrap()[1], expected);
        let by_both = relative(both.radiance(&ray).unwrap()[1], expected);
        println!("{below_m} m below: paper {by_paper:.4}, both settings {by_both:.4}");
        assert!(by_both < 0.04, "{below_m} m below: {by_both}");
        assert!(
            by_both < 0.4 * by_paper,
            "{below_m} m below: {by_both} vs {by_paper}"
        );
    }
}

/// The mean error on a grid of 24 x 36 of the sphere scene's pixels, each ray a third
/// of a cell from its cell's corner, so that a column runs beside the light.
fn mean_error(s: &BeamScene, q: &dyn BeamMethod, truth: &dyn BeamMethod) -> f64 {
    grid_mean_error(s, q, truth, (24, 36), 0.33)
}

#[test]
fn the_sphere_scene_meets_the_papers_mean_error_with_both_settings() {
    let s = sphere_scene();
    let truth = method(BeamMethodId::Reference, &s, &[]);
    let paper = mean_error(&s, &qtable(&s, &[]), truth.as_ref());
    let weighted = mean_error(&s, &qtable(&s, &BOTH[..1]), truth.as_ref());
    let both = mean_error(&s, &qtable(&s, &BOTH), truth.as_ref());
    let finer = mean_error(
        &s,
        &qtable(&s, &[BOTH[0], BOTH[1], "epsilon=0.005"]),
        truth.as_ref(),
    );
    println!(
        "mean error: paper {paper:.4}, weighted {weighted:.4}, both {both:.4}, both at epsilon 0.005 {finer:.4}"
    );
    assert!(finer < 0.015, "{finer}");
    assert!(both < paper && finer < both, "{paper} {both} {finer}");
}

#[test]
fn a_ray_counts_the_centre_rays_sub_planes_on_the_centre_ray() {
    // The threshold is the paper's (epsilon of the centre ray's whole f_l): the centre
    // ray's own f_l gives its m_k back; epsilon 0 gives the most everywhere.
    let s = sphere_scene();
    for epsilon in ["epsilon=0.01", "epsilon=0.002"] {
        let q = qtable(&s, &[epsilon, BOTH[1]]);
        let rule = q.subplanes_per_ray().unwrap();
        let planes = &q.planes()[0];
        let subplanes: usize = planes.samples.iter().map(|m| m - 1).sum();
        assert!(subplanes > 0, "{epsilon}");
        for (k, (&f, &m)) in planes.centre_f_l.iter().zip(&planes.samples).enumerate() {
            assert_eq!(planes.samples_for(&rule, f), m, "{epsilon}, interval {k}");
        }
    }
    let q = qtable(&s, &["epsilon=0", "max_subplanes=7", BOTH[1]]);
    let rule = q.subplanes_per_ray().unwrap();
    assert_eq!(q.planes()[0].samples_for(&rule, 0.0), 8);
    assert!(qtable(&s, &[]).subplanes_per_ray().is_none());
}
