//! The planner's rule for beams scenes (`beams/plan.rs`): a light whose beam cannot
//! reach the visible air, or any light in a medium that scatters nothing, gets no work;
//! pruning changes no pixel, and a light outside the frustum that shines into it is
//! kept. And the q table's planes cover only their light's part of the screen.

use std::path::Path;

use atmosphere_core::atmosphere::spectral::Spectral;
use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::{BeamMethod, BeamSettings};
use atmosphere_core::beams::methods::qtable2002::Qtable2002;
use atmosphere_core::beams::methods::registry::prepare;
use atmosphere_core::beams::plan::{BeamPlan, Skip};
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;

const WAVELENGTHS: [f64; 3] = [680.0, 550.0, 440.0];

/// The shipped sphere scene with `extra` lights appended, at 24 x 36 pixels.
fn sphere_scene_with(extra: &str) -> BeamScene {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes/beams");
    let text = std::fs::read_to_string(folder.join("sphere_spotlight.toml")).unwrap();
    let mut scene =
        BeamScene::from_toml(&format!("{text}\n{extra}"), "sphere.toml", &folder).unwrap();
    scene.camera.width_px = 24;
    scene.camera.height_px = 36;
    scene
}

/// A spot at `position` along `direction`.
fn spot(position: &str, direction: &str) -> String {
    format!(
        "[[lights]]\nkind = \"spot\"\nposition_m = {position}\ndirection = {direction}\n\
         cone_deg = 20.0\nintensity_w_sr_nm = {{ kind = \"constant\", value = 2000.0 }}\n"
    )
}

/// The march's radiance at every pixel of the scene's camera.
fn image(scene: &BeamScene) -> Vec<Vec<f64>> {
    let settings = BeamSettings {
        options: ModelOptions::parse(&["steps=32", "shadow_map_px=64"]).unwrap(),
        ..BeamSettings::default()
    };
    let march = prepare(BeamMethodId::March, scene, &settings).unwrap();
    let camera = &scene.camera;
    (0..camera.height_px)
        .flat_map(|y| (0..camera.width_px).map(move |x| (x, y)))
        .map(|(x, y)| {
            march
                .radiance(&camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5))
                .unwrap()
        })
        .collect()
}

#[test]
fn a_spot_behind_the_camera_is_skipped_and_pruning_it_changes_no_pixel() {
    let scene = sphere_scene_with(&spot("[0.0, 4.0, 40.0]", "[0.0, 0.0, 1.0]"));
    let plan = BeamPlan::new(&scene, &WAVELENGTHS);
    assert_eq!(plan.lights, vec![None, Some(Skip::OutsideView)]);
    assert_eq!(plan.drawn(), 1);
    assert_eq!(
        plan.to_string(),
        "lights[0] drawn, lights[1] skipped (its beam stays outside the view)"
    );
    let pruned = plan.pruned(&scene);
    assert_eq!(pruned.lights.len(), 1);
    assert_eq!(image(&scene), image(&pruned));
}

#[test]
fn a_spot_outside_the_frustum_that_shines_into_it_is_kept() {
    // 40 m to the right of the view, pointing back across it: the light is outside the
    // frustum, its beam is not.
    let scene = sphere_scene_with(&spot("[40.0, 8.0, 0.0]", "[-1.0, 0.0, 0.0]"));
    let plan = BeamPlan::new(&scene, &WAVELENGTHS);
    assert_eq!(plan.lights, vec![None, None]);
    let mut only_first = scene.clone();
    only_first.lights.truncate(1);
    let brighter = image(&scene)
        .iter()
        .zip(image(&only_first))
        .filter(|(a, b)| a[1] > 1.01 * b[1])
        .count();
    assert!(brighter > 10, "the side spot lights only {brighter} pixels");
}

#[test]
fn a_medium_that_scatters_nothing_skips_every_light() {
    let mut scene = sphere_scene_with("");
    scene.medium.scattering_per_m = Spectral::Constant { value: 0.0 };
    let plan = BeamPlan::new(&scene, &WAVELENGTHS);
    assert_eq!(plan.lights, vec![Some(Skip::NothingScatters)]);
    assert!(image(&scene).iter().flatten().all(|&l| l == 0.0));
    assert!(plan.pruned(&scene).lights.is_empty());
}

#[test]
fn the_q_tables_planes_cover_only_the_spots_pyramid_on_the_screen() {
    // A wide frame, as the bench's 1280 x 720.
    let mut scene = sphere_scene_with("");
    (scene.camera.width_px, scene.camera.height_px) = (48, 27);
    let settings = BeamSettings {
        options: ModelOptions::parse(&["table_u=32", "table_v=32", "shadow_map_px=64"]).unwrap(),
        ..BeamSettings::default()
    };
    let qtable = Qtable2002::new(&scene, &settings).unwrap();
    let [x0, y0, x1, y1] = qtable.screen_bounds()[0];
    // The pyramid from the spot 20 m up to the floor: narrower than the screen, its
    // apex below the top edge.
    assert!(-1.0 < x0 && x0 < 0.0 && 0.0 < x1 && x1 < 1.0, "{x0} {x1}");
    assert!(y0 < 0.0 && 0.0 < y1 && y1 < 1.0, "{y0} {y1}");
    // A ray beside it gets nothing, one through the middle its light.
    let camera = &scene.camera;
    let side = camera.ray(0.5, 13.5);
    assert!(qtable.radiance(&side).unwrap().iter().all(|&l| l == 0.0));
    let middle = camera.ray(24.0, 13.5);
    assert!(qtable.radiance(&middle).unwrap()[1] > 0.0);
}
