//! Every shipped beams scene loads, and both methods give finite, non-negative radiance
//! over a grid of its camera's pixels, positive where the camera looks into a beam.

use std::path::PathBuf;

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::methods::registry::prepare;
use atmosphere_core::beams::scene::BeamScene;

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
    assert_eq!(scenes.len(), 3, "{scenes:?}");
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
