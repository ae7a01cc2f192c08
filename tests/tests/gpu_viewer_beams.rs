//! The viewer's beams frame (`crates/app/src/viewer/beams_view.rs`, with the scene as
//! the panel's state makes it, `beams_state.rs`) against `atmos render --scene` of the
//! same scene, size, method and settings (`crates/app/src/render/beams.rs`): the same
//! PNG pixels bit for bit, metered exposure included, for every beam method on the GPU.

mod support;

use std::path::Path;

use atmos::render::scene::Scene;
use atmos::viewer::beams_state::BeamsState;
use atmos::viewer::beams_view::BeamsView;
use render_wgpu::shafts::beams::gpu_methods::GPU_BEAM_METHODS;
use support::gpu_or_skip;

#[test]
fn the_viewers_beams_frame_is_atmos_renders_image() {
    let Some(gpu) = gpu_or_skip("viewer beams") else {
        return;
    };
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/beams/stage_five_spots.toml");
    let dir = tempfile::tempdir().unwrap();
    let (width, height) = (64, 36);
    for id in GPU_BEAM_METHODS {
        let set = match id.to_string().as_str() {
            "planes2000" => vec!["planes=40", "shadow_map_px=128"],
            "qtable2002" => vec!["table_u=64", "table_v=64", "shadow_map_px=128"],
            _ => vec!["steps=48", "shadow_map_px=128"],
        };
        let out = dir.path().join(format!("{id}.png"));
        let flags = Scene {
            width: Some(width),
            height: Some(height),
            set: set.iter().map(|s| s.to_string()).collect(),
            ..Scene::default()
        };
        atmos::render::beams::run(&path, &flags, Some(&id.to_string()), &out).unwrap();
        let rendered = image::open(&out).unwrap().to_rgb8();

        let mut state = BeamsState::default();
        assert!(state.open(&path), "{}", state.message);
        let edit = state.edit.as_mut().unwrap();
        edit.method = id;
        edit.settings = set.join(" ");
        let (scene, settings) = state.frame_scene(width, height).unwrap();
        let mut view = BeamsView::default();
        let shown = view
            .render(&gpu, &scene, id, &settings, None)
            .unwrap()
            .expect("a first frame");
        assert_eq!(shown.size, (width, height));
        let viewer: Vec<u8> = shown
            .pixels
            .iter()
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        assert_eq!(
            viewer,
            rendered.as_raw().as_slice(),
            "{id}: the viewer's pixels differ"
        );
        assert!(viewer.iter().any(|&v| v > 32), "{id}: the frame is black");
        assert!(
            view.stats.plan.contains("lights[4] drawn"),
            "{}",
            view.stats.plan
        );
        // Nothing changed: nothing is rendered again; a new exposure only re-tone-maps.
        assert!(
            view.render(&gpu, &scene, id, &settings, None)
                .unwrap()
                .is_none()
        );
        let darker = view
            .render(&gpu, &scene, id, &settings, Some(view.stats.ev100 + 2.0))
            .unwrap()
            .expect("a new exposure");
        let sum = |p: &[[u8; 4]]| p.iter().map(|p| u64::from(p[1])).sum::<u64>();
        assert!(sum(&darker.pixels) < sum(&shown.pixels), "{id}");
    }
}

#[test]
fn the_viewer_shows_the_planners_skips_and_names_a_refused_setting_once() {
    let Some(gpu) = gpu_or_skip("viewer beams") else {
        return;
    };
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/beams/sphere_spotlight.toml");
    let mut state = BeamsState::default();
    assert!(state.open(&path), "{}", state.message);
    let edit = state.edit.as_mut().unwrap();
    edit.density = 0.0;
    edit.settings = "steps=16 shadow_map_px=64".into();
    let (scene, settings) = state.frame_scene(32, 18).unwrap();
    let mut view = BeamsView::default();
    let id = state.edit.as_ref().unwrap().method;
    let shown = view
        .render(&gpu, &scene, id, &settings, Some(0.0))
        .unwrap()
        .unwrap();
    assert_eq!(
        view.stats.plan,
        "lights[0] skipped (the medium scatters nothing)"
    );
    assert!(shown.pixels.iter().all(|p| p[..3] == [0, 0, 0]));
    // A setting the method refuses: named, and the same error again without preparing.
    state.edit.as_mut().unwrap().settings = "steps=0".into();
    let (scene, settings) = state.frame_scene(32, 18).unwrap();
    let first = view
        .render(&gpu, &scene, id, &settings, None)
        .unwrap_err()
        .to_string();
    assert!(first.contains("steps"), "{first}");
    let again = view
        .render(&gpu, &scene, id, &settings, None)
        .unwrap_err()
        .to_string();
    assert_eq!(first, again);
}
