//! Light shafts on the planet (`render_wgpu::shafts::terrain`, `shaders/sky/hillaire/
//! shafts.wgsl`, `shaders/sky/nishita/pixel.wgsl`, `shaders/sky/oneil/pixel.wgsl`,
//! `shaders/sky/bruneton/pixel.wgsl`, `shaders/sky/dobashi/trace.wgsl`) against their CPU
//! twins (`atmosphere_core::models::hillaire::shafts`, `models::nishita`, `models::oneil`,
//! `models::bruneton::shafts`, `models::dobashi::trace`, with the renderer's own shadow
//! map), that the shadow darkens the rays through it by the CPU's ratio, and that the
//! planner's pruning changes nothing.
//!
//! Needs a GPU adapter (lavapipe will do); see `gpu_hillaire_parity.rs`.

mod support;

use std::path::Path;

use atmos::render::scene::Scene;
use atmosphere_core::models::bruneton::Bruneton;
use atmosphere_core::models::dobashi::{Dobashi, DobashiSettings};
use atmosphere_core::models::hillaire::{Hillaire, HillaireSettings};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::nishita::{Nishita, NishitaSettings};
use atmosphere_core::models::oneil::{Oneil, OneilSettings};
use atmosphere_core::models::sky_model::SkyModel;
use render_wgpu::frame::surface_buffer::SurfaceTexel;
use render_wgpu::{Frame, Renderer};
use support::{FLOOR, cpu_pixel, renderer_or_skip};

/// Largest |L_gpu - L_cpu| / max(L_cpu, FLOOR) per pixel and channel with the shafts on:
/// the models' own parity (2e-3: the f16 store, the tables' f32 error) plus the shadow
/// test in f32, whose altitude and grid position carry about 0.5 m of rounding against
/// a penumbra band of at least 1 m, and the GPU's terrain surface distance; measured on
/// lavapipe: see the printed worst error.
const MAX_RELATIVE_ERROR: f64 = 5e-3;

/// The default scene (3 km above the Pennine Alps, the sun 5 deg up) at `width` x
/// `height`, with the sun `sun_zenith_deg` from the zenith.
fn alps(width: u32, height: u32, sun_zenith_deg: f64) -> Frame {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/default.toml");
    let scene = Scene {
        width: Some(width),
        height: Some(height),
        sun_zenith_deg: Some(sun_zenith_deg),
        ..Scene::load(&path).unwrap()
    };
    scene.frame().unwrap()
}

fn with_shafts(frame: &Frame, on: bool) -> Frame {
    let mut f = frame.clone();
    let mut terrain = f.terrain.expect("the scene has terrain");
    terrain.shafts = on;
    f.terrain = Some(terrain);
    f
}

/// The CPU model of `frame` (hillaire, nishita, oneil, bruneton or dobashi) with the renderer's last shadow map
/// (or none).
fn cpu_model(frame: &Frame, renderer: &Renderer, shafts: bool) -> Box<dyn SkyModel> {
    let shadow = if shafts {
        renderer.shadow_map().cloned()
    } else {
        None
    };
    let (a, s) = (&frame.atmosphere, &frame.settings);
    match frame.model {
        ModelId::Hillaire => {
            let mut model = Hillaire::prepare(a, s, HillaireSettings::default()).unwrap();
            model.set_terrain_shadow(shadow);
            Box::new(model)
        }
        ModelId::Nishita => {
            let mut model = Nishita::prepare(a, s, NishitaSettings::default()).unwrap();
            model.set_terrain_shadow(shadow);
            Box::new(model)
        }
        ModelId::Oneil => {
            let mut model = Oneil::prepare(a, s, OneilSettings::default()).unwrap();
            model.set_terrain_shadow(shadow);
            Box::new(model)
        }
        ModelId::Bruneton => {
            let mut model = Bruneton::prepare(a, s).unwrap();
            model.set_terrain_shadow(shadow);
            Box::new(model)
        }
        ModelId::Dobashi => {
            let mut model = Dobashi::prepare(a, s, DobashiSettings::default()).unwrap();
            model.set_terrain_shadow(shadow);
            Box::new(model)
        }
        other => panic!("{other} has no light shafts"),
    }
}

/// Renders `frame`; its HDR pixels and surface.
fn render(renderer: &mut Renderer, frame: &Frame) -> (Vec<[f32; 4]>, Vec<SurfaceTexel>) {
    let plan = renderer.render(frame).unwrap();
    println!("{plan}");
    (
        renderer.read_hdr().unwrap(),
        renderer.read_surface().unwrap(),
    )
}

#[test]
fn hillaire_shafts_over_the_alps_at_sunset_match_the_cpu_and_darken_by_its_ratio() {
    check_shafts(ModelId::Hillaire);
}

#[test]
fn nishita_shafts_over_the_alps_at_sunset_match_the_cpu_and_darken_by_its_ratio() {
    check_shafts(ModelId::Nishita);
}

#[test]
fn oneil_shafts_over_the_alps_at_sunset_match_the_cpu_and_darken_by_its_ratio() {
    check_shafts(ModelId::Oneil);
}

#[test]
fn bruneton_shafts_over_the_alps_at_sunset_match_the_cpu_and_darken_by_its_ratio() {
    check_shafts(ModelId::Bruneton);
}

#[test]
fn dobashi_shafts_over_the_alps_at_sunset_match_the_cpu_and_darken_by_its_ratio() {
    check_shafts(ModelId::Dobashi);
}

/// `model`'s frame of the Alps with the sun 4 degrees up, with shafts, against the CPU
/// within [`MAX_RELATIVE_ERROR`]; with and without, the GPU's ratio against the CPU's
/// wherever the CPU's shadow takes out more than 2 %.
fn check_shafts(model: ModelId) {
    let Some(mut renderer) = renderer_or_skip("shafts over the alps") else {
        return;
    };
    let mut frame = alps(64, 36, 86.0);
    frame.model = model;
    let (dark, surface) = render(&mut renderer, &with_shafts(&frame, true));
    let dark_ldr = renderer.read_ldr().unwrap();
    let map = renderer.shadow_map().expect("the frame had shafts").clone();
    assert!(
        map.shadowing_cells > 0,
        "a low sun over the Alps casts shadows"
    );
    let shadowed = cpu_model(&frame, &renderer, true);
    let (lit, lit_surface) = render(&mut renderer, &with_shafts(&frame, false));
    let lit_ldr = renderer.read_ldr().unwrap();
    let changed = dark_ldr
        .iter()
        .zip(&lit_ldr)
        .filter(|(a, b)| a != b)
        .count();
    println!("{changed} displayed pixels changed");
    assert_eq!(surface, lit_surface);
    let unshadowed = cpu_model(&frame, &renderer, false);
    let (mut worst, mut darkened) = (0.0f64, 0);
    for row in 0..frame.height {
        for column in 0..frame.width {
            let i = (row * frame.width + column) as usize;
            let texel = Some(&surface[i]);
            let cpu = cpu_pixel(shadowed.as_ref(), &frame, column, row, texel);
            let cpu_lit = cpu_pixel(unshadowed.as_ref(), &frame, column, row, texel);
            for c in 0..3 {
                let (gpu, gpu_lit) = (f64::from(dark[i][c]), f64::from(lit[i][c]));
                let error = (gpu - cpu[c]).abs() / cpu[c].max(FLOOR);
                worst = worst.max(error);
                assert!(
                    error <= MAX_RELATIVE_ERROR,
                    "pixel ({column}, {row}) channel {c}: gpu {gpu:e}, cpu {:e}",
                    cpu[c]
                );
                // Where the CPU's shadow takes out more than 2 %, the GPU's does too, by
                // the CPU's ratio.
                let ratio = cpu[c] / cpu_lit[c];
                if ratio < 0.98 && cpu_lit[c] > FLOOR {
                    darkened += 1;
                    let gpu_ratio = gpu / gpu_lit;
                    assert!(
                        (gpu_ratio - ratio).abs() < 2.0 * MAX_RELATIVE_ERROR,
                        "pixel ({column}, {row}) channel {c}: gpu ratio {gpu_ratio}, cpu {ratio}"
                    );
                }
            }
        }
    }
    println!(
        "{model}: worst relative error {worst:.2e}; {darkened} pixel channels darkened by > 2 %"
    );
    assert!(darkened > 30, "only {darkened} pixel channels in shadow");
}

/// A frame whose shafts the planner leaves out (a high sun: nothing over the Alps
/// casts a shadow into the air) renders as with them forced on; the rule's other cases
/// are unit tests of `shafts/terrain/planner.rs`.
#[test]
fn pruning_the_shafts_changes_nothing() {
    let Some(mut renderer) = renderer_or_skip("shafts pruning") else {
        return;
    };
    let frame = alps(48, 27, 20.0);
    let plan = renderer.render(&frame).unwrap();
    let why = "nothing casts a shadow into the air";
    assert!(plan.skipped.contains(&("shafts", why)), "{plan}");
    let pruned = renderer.read_hdr().unwrap();
    renderer.set_prune_shafts(false);
    let plan = renderer.render(&frame).unwrap();
    assert!(!plan.skipped.iter().any(|(s, _)| *s == "shafts"), "{plan}");
    assert_eq!(pruned, renderer.read_hdr().unwrap());
}
