//! Extreme beams scenes give finite, bounded radiance from every method (and qtable2002
//! at epsilon 0, its samples as the paper weighs them and weighted and counted per ray):
//! a light inside an occluder, the camera inside a beam and at a light, a medium of
//! density 0 and one of 1e3 m^-1.

mod common;

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::{BeamMethod, BeamSettings};
use atmosphere_core::beams::methods::registry::prepare;
use atmosphere_core::beams::ray::SceneRay;
use atmosphere_core::beams::scene::BeamScene;
use common::beams::*;
use glam::DVec3;

/// Every method at its defaults, and qtable2002 at the most sub-planes (epsilon 0),
/// with its samples as the paper weighs them and weighted and counted per ray.
fn methods(scene: &BeamScene) -> Vec<(BeamMethodId, Box<dyn BeamMethod>)> {
    let settings = BeamSettings::default();
    let mut all: Vec<(BeamMethodId, Box<dyn BeamMethod>)> = BeamMethodId::ALL
        .into_iter()
        .map(|id| (id, prepare(id, scene, &settings).unwrap()))
        .collect();
    for options in [
        &["epsilon=0"][..],
        &[
            "epsilon=0",
            "weighted_samples=true",
            "subplanes_per_ray=true",
        ],
    ] {
        let q = BeamMethodId::Qtable2002;
        all.push((q, method(q, scene, options)));
    }
    all
}

/// The camera's centre ray, and a ray from the camera to the light at (0, 3, 0).
fn camera_rays(scene: &BeamScene) -> [SceneRay; 2] {
    let to_light = DVec3::new(0.0, 3.0, 0.0) - scene.camera.position_m;
    [
        scene.camera.ray(16.0, 12.0),
        SceneRay::new(scene.camera.position_m, to_light, None).unwrap(),
    ]
}

fn radiance_of(scene: &BeamScene) -> Vec<Vec<f64>> {
    let mut out = Vec::new();
    for (id, method) in methods(scene) {
        for ray in camera_rays(scene) {
            let l = method.radiance(&ray).unwrap();
            assert!(l.iter().all(|x| x.is_finite() && *x >= 0.0), "{id}: {l:?}");
            out.push(l);
        }
    }
    out
}

#[test]
fn a_light_inside_an_occluder_is_dark() {
    let rest = format!(
        "{}[[occluders]]\nkind = \"sphere\"\ncenter_m = [0, 3, 0]\nradius_m = 0.5\n",
        point_light([0.0, 3.0, 0.0], 100.0)
    );
    for l in radiance_of(&scene(&medium(0.05, 0.01, ISOTROPIC), &rest)) {
        assert_eq!(l, vec![0.0; 3]);
    }
}

#[test]
fn density_zero_scatters_nothing_and_density_1e3_stays_finite() {
    let light = point_light([0.0, 3.0, 0.0], 100.0);
    for l in radiance_of(&scene(&medium(0.0, 0.0, ISOTROPIC), &light)) {
        assert_eq!(l, vec![0.0; 3]);
    }
    radiance_of(&scene(&medium(1e3, 1e-3, ISOTROPIC), &light));
}

#[test]
fn a_camera_inside_a_beam_and_at_a_light_gets_finite_light() {
    // The camera of the common scenes sits at (0, 2, 20); a point light there, with the
    // default radius, and a parallel beam all around it.
    let rest = format!(
        "{}[[lights]]\nkind = \"parallel\"\nposition_m = [0, 10, 0]\ndirection = [0, -1, 0]\n\
         irradiance_w_m2_nm = {{ kind = \"constant\", value = 1 }}\n\
         [[lights]]\nkind = \"point\"\nposition_m = [0, 2, 20]\n\
         intensity_w_sr_nm = {{ kind = \"constant\", value = 10 }}\n",
        point_light([0.0, 3.0, 0.0], 100.0)
    );
    let s = scene(&medium(0.05, 0.01, ISOTROPIC), &rest);
    for l in radiance_of(&s) {
        assert!(l.iter().all(|x| *x > 0.0), "{l:?}");
    }
}
