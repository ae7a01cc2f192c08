//! The planner's rule on the GPU (render-wgpu's `shafts/beams/gpu_methods.rs` with
//! atmosphere-core's `beams/plan.rs`): a spotlight behind the camera is skipped, and the
//! frame without it equals the frame that draws it, for every beam method on the GPU.

mod support;

use std::path::Path;

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::plan::Skip;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::shafts::beams::gpu_methods::{GPU_BEAM_METHODS, PackedBeams, PreparedBeams};
use support::gpu_or_skip;

/// The largest difference allowed, as a share of the brightest pixel: the q table's
/// extent covers every light drawn, so qtable2002's table nodes move with the plan.
const TOLERANCE: f32 = 1e-3;

#[test]
fn pruning_a_spot_behind_the_camera_changes_no_pixel_on_the_gpu() {
    let Some(gpu) = gpu_or_skip("beams plan") else {
        return;
    };
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/beams");
    let text = std::fs::read_to_string(folder.join("sphere_spotlight.toml")).unwrap();
    let behind = "[[lights]]\nkind = \"spot\"\nposition_m = [0.0, 4.0, 40.0]\n\
                  direction = [0.0, 0.0, 1.0]\ncone_deg = 20.0\n\
                  intensity_w_sr_nm = { kind = \"constant\", value = 2000.0 }\n";
    let mut scene =
        BeamScene::from_toml(&format!("{text}\n{behind}"), "sphere.toml", &folder).unwrap();
    scene.camera.width_px = 32;
    scene.camera.height_px = 48;
    for id in GPU_BEAM_METHODS {
        let options = match id {
            BeamMethodId::Qtable2002 => vec!["table_u=64", "table_v=64", "shadow_map_px=128"],
            BeamMethodId::Planes2000 => vec!["planes=60", "shadow_map_px=128"],
            _ => vec!["steps=64", "shadow_map_px=128"],
        };
        let settings = BeamSettings {
            options: ModelOptions::parse(&options).unwrap(),
            ..BeamSettings::default()
        };
        let planned = PreparedBeams::new(id, &scene, &settings).unwrap();
        assert_eq!(planned.plan.lights, vec![None, Some(Skip::OutsideView)]);
        let everything = PackedBeams::new(id, &scene, &settings).unwrap();
        let render = |packed: PackedBeams| {
            let (image, _) = packed.renderer(&gpu).unwrap().render(&gpu).unwrap();
            image.read_radiance(&gpu).unwrap()
        };
        let pruned = render(planned.packed);
        let full = render(everything);
        let brightest = full.iter().map(|p| p[1]).fold(0.0f32, f32::max);
        assert!(brightest > 0.0, "{id}: a black image");
        for (i, (a, b)) in pruned.iter().zip(&full).enumerate() {
            for k in 0..3 {
                assert!(
                    (a[k] - b[k]).abs() <= TOLERANCE * brightest,
                    "{id}: pixel {i}: pruned {a:?}, full {b:?}"
                );
            }
        }
    }
}
