//! Every shipped beams scene loads, and both methods give finite, non-negative radiance
//! over a grid of its camera's pixels, positive where the camera looks into a beam.

use std::path::PathBuf;

use atmosphere_core::beams::bvh::Bvh;
use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::methods::registry::prepare;
use atmosphere_core::beams::ray::SceneRay;
use atmosphere_core::beams::scene::BeamScene;
use glam::DVec3;

fn shipped_scenes() -> Vec<PathBuf> {
    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes/beams");
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    scenes
}

#[test]
fn every_shipped_scene_gives_finite_positive_light() {
    let scenes = shipped_scenes();
    assert_eq!(scenes.len(), 5, "{scenes:?}");
    for path in scenes {
        let scene = BeamScene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let (w, h) = (
            f64::from(scene.camera.width_px),
            f64::from(scene.camera.height_px),
        );
        let settings = BeamSettings::default();
        for id in BeamMethodId::ALL {
            let method = prepare(id, &scene, &settings).unwrap();
            let centre = method
                .radiance(&scene.camera.ray(0.5 * w, 0.5 * h))
                .unwrap();
            assert!(
                centre.iter().all(|l| l.is_finite() && *l > 0.0),
                "{} {id}: {centre:?}",
                path.display()
            );
            for (fx, fy) in [(0.1, 0.1), (0.9, 0.2), (0.3, 0.8), (0.7, 0.6)] {
                let l = method.radiance(&scene.camera.ray(fx * w, fy * h)).unwrap();
                assert!(
                    l.iter().all(|l| l.is_finite() && *l >= 0.0),
                    "{}: {l:?}",
                    path.display()
                );
            }
        }
    }
}

#[test]
fn the_reference_converges_through_light_maps_and_box_shadows() {
    // Stained glass (a 128 x 128 map) through window openings in a wall of boxes: the
    // default tolerance agrees with a thousand times finer one on a grid of pixels.
    let path = shipped_scenes()
        .into_iter()
        .find(|p| p.ends_with("stained_glass_room.toml"))
        .unwrap();
    let scene = BeamScene::load(&path).unwrap();
    let mut fine = BeamSettings::default();
    fine.options.set("tolerance", 1e-8);
    fine.options.set("max_panels", 2_000_000);
    let coarse = prepare(BeamMethodId::Reference, &scene, &BeamSettings::default()).unwrap();
    let fine = prepare(BeamMethodId::Reference, &scene, &fine).unwrap();
    let (w, h) = (
        f64::from(scene.camera.width_px),
        f64::from(scene.camera.height_px),
    );
    let mut lit = 0;
    for j in 0..6 {
        for i in 0..8 {
            let ray = scene
                .camera
                .ray((i as f64 + 0.5) * w / 8.0, (j as f64 + 0.5) * h / 6.0);
            let (a, b) = (coarse.radiance(&ray).unwrap(), fine.radiance(&ray).unwrap());
            for k in 0..3 {
                assert!(
                    (a[k] - b[k]).abs() <= 1e-4 * b[k],
                    "pixel ({i}, {j}): {} {}",
                    a[k],
                    b[k]
                );
            }
            lit += usize::from(b[1] > 0.0);
        }
    }
    assert!(lit >= 8, "{lit} of 48 rays see a shaft");
}

#[test]
fn the_teapot_stands_where_its_scene_puts_it_and_shadows_the_beam_below_it() {
    let path = shipped_scenes()
        .into_iter()
        .find(|p| p.ends_with("teapot_spotlight.toml"))
        .unwrap();
    let scene = BeamScene::load(&path).unwrap();
    // 32 patches of 8 x 8 quads, less the triangles where the lid's and the bottom's
    // patches close to a point.
    assert_eq!(scene.occluders.triangles.len(), 4032);
    let (lo, hi) = scene.occluders.triangles.bounds().unwrap();
    // Newell's extent (x -3 to 3.4 at the handle and spout tips' tessellation, z up to
    // 3.15, radius 2) scaled by 0.4, z up turned to y up, 1 m up on the pedestal.
    for (got, expected) in [
        (lo.x, -1.2),
        (hi.y, 2.26),
        (lo.z, -0.8),
        (hi.z, 0.8),
        (lo.y, 1.0),
    ] {
        assert!((got - expected).abs() < 1e-3, "{got} vs {expected}");
    }
    // From the camera below the teapot's body, beside the pedestal: the teapot's shadow
    // removes the light of the stretch under it.
    let toward = DVec3::new(0.55, 0.5, 0.0);
    let ray = SceneRay::new(
        scene.camera.position_m,
        toward - scene.camera.position_m,
        None,
    )
    .unwrap();
    let mut open = scene.clone();
    open.occluders.triangles = Bvh::default();
    let settings = BeamSettings::default();
    let radiance =
        |s: &BeamScene, id| prepare(id, s, &settings).unwrap().radiance(&ray).unwrap()[1];
    let (shadowed, unshadowed) = (
        radiance(&scene, BeamMethodId::Reference),
        radiance(&open, BeamMethodId::Reference),
    );
    assert!(
        shadowed > 0.0 && shadowed < 0.8 * unshadowed,
        "{shadowed} with the teapot, {unshadowed} without"
    );
    let qtable = radiance(&scene, BeamMethodId::Qtable2002);
    assert!(
        (qtable - shadowed).abs() < 0.05 * shadowed,
        "qtable2002 {qtable}, reference {shadowed}"
    );
}
