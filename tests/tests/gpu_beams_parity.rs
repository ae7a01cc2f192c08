//! The GPU beams march (`shaders/shafts/beams/march.wgsl` through render-wgpu's
//! `shafts/beams/march_pass.rs`) against its CPU twin (atmosphere-core's
//! `beams/methods/march.rs`) on the same pixel rays of the shipped scenes, with the same
//! shadow maps: a sphere under a spotlight (Dobashi et al. 2002 Fig. 4), five spots with
//! gobos and a glTF pillar, sunlight through a stained-glass light map (a parallel light).
//! And the sphere's shadow in the air: removing the sphere brightens the pixels that
//! look through its shadow by the same factor on both sides.

mod support;

use std::path::Path;

use atmosphere_core::beams::methods::march::March;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::occluder::Primitive;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::GpuContext;
use render_wgpu::shafts::beams::gpu_scene::GpuScene;
use render_wgpu::shafts::beams::march_pass::MarchPass;
use support::beams::{check_relative, cpu_pixels, gpu_pixels, shipped_scene};
use support::gpu_or_skip;

/// Largest |L_gpu - L_cpu| / max(L_cpu, floor) of a pixel and wavelength, the floor
/// 1e-3 of the image's brightest value at that wavelength: f32 against f64 in the same
/// sums of 128 steps, the same shadow maps and light maps (the test prints what it
/// measured; docs/beams.md, "On the GPU").
const MAX_RELATIVE_ERROR: f64 = 2e-3;

fn march(scene: &BeamScene) -> March {
    let settings = BeamSettings {
        options: ModelOptions::parse(&["steps=128", "shadow_map_px=256"]).unwrap(),
        ..BeamSettings::default()
    };
    March::new(scene, &settings).unwrap()
}

/// Radiance at the three wavelengths per pixel, row by row: (CPU, GPU).
fn both(gpu: &GpuContext, pass: &MarchPass, scene: &BeamScene) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let march = march(scene);
    let (image, _) = pass.render(gpu, &GpuScene::new(&march)).unwrap();
    (
        cpu_pixels(&march, scene),
        gpu_pixels(image.read_radiance(gpu).unwrap()),
    )
}

#[test]
fn gpu_march_matches_the_cpu_march_on_the_shipped_scenes() {
    let Some(gpu) = gpu_or_skip("beams march parity") else {
        return;
    };
    let pass = MarchPass::new(&gpu).unwrap();
    for (name, width, height) in [
        ("sphere_spotlight.toml", 40, 60),
        ("stage_five_spots.toml", 64, 48),
        ("stained_glass_room.toml", 64, 48),
        ("point_lamp.toml", 64, 36),
    ] {
        let (cpu, gpu_pixels) = both(&gpu, &pass, &shipped_scene(name, width, height));
        check_relative(name, &cpu, &gpu_pixels, MAX_RELATIVE_ERROR);
    }
}

/// A point light with a light map (its azimuth wraps) and six shadow views, a spot,
/// a box, a sphere and a quad, and a tabulated phase function: what no shipped scene
/// holds.
const POINT_LIGHT_SCENE: &str = r#"
[medium]
scattering_per_m = { kind = "constant", value = 0.05 }
absorption_per_m = { kind = "constant", value = 0.01 }
phase = { kind = "tabulated", angles_deg = [0.0, 30.0, 90.0, 150.0, 180.0], values = [4.0, 2.0, 1.0, 0.8, 1.2] }

[camera]
position_m = [1.0, 3.0, 14.0]
look_at_m = [0.0, 3.0, 0.0]
vertical_fov_deg = 60.0
width_px = 48
height_px = 36

[[lights]]
kind = "point"
position_m = [0.5, 4.0, 0.0]
intensity_w_sr_nm = { kind = "constant", value = 300.0 }
axis = [0.3, -1.0, 0.0]
light_map = "gobo_dots.png"

[[lights]]
kind = "spot"
position_m = [-4.0, 8.0, 1.0]
direction = [0.4, -1.0, 0.0]
cone_deg = 20.0
falloff_exponent = 2.0
intensity_w_sr_nm = { kind = "constant", value = 800.0 }

[[occluders]]
kind = "box"
min_m = [-1.5, 1.0, -1.0]
max_m = [-0.5, 2.0, 1.0]

[[occluders]]
kind = "sphere"
center_m = [1.8, 3.5, 0.5]
radius_m = 0.6

[[occluders]]
kind = "quad"
corner_m = [-6.0, 0.0, -5.0]
edge_u_m = [12.0, 0.0, 0.0]
edge_v_m = [0.0, 10.0, 0.0]
"#;

#[test]
fn gpu_march_matches_the_cpu_march_with_a_point_light_and_a_tabulated_phase() {
    let Some(gpu) = gpu_or_skip("beams march parity, point light") else {
        return;
    };
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/beams");
    let scene = BeamScene::from_toml(POINT_LIGHT_SCENE, "point.toml", &folder).unwrap();
    let pass = MarchPass::new(&gpu).unwrap();
    let (cpu, gpu_pixels) = both(&gpu, &pass, &scene);
    check_relative("point light", &cpu, &gpu_pixels, MAX_RELATIVE_ERROR);
}

#[test]
fn the_sphere_darkens_the_air_in_its_shadow_as_on_the_cpu() {
    let Some(gpu) = gpu_or_skip("beams march shadow") else {
        return;
    };
    let pass = MarchPass::new(&gpu).unwrap();
    let with = shipped_scene("sphere_spotlight.toml", 40, 60);
    let mut without = with.clone();
    without
        .occluders
        .primitives
        .retain(|p| !matches!(p, Primitive::Sphere { .. }));
    let (cpu_with, gpu_with) = both(&gpu, &pass, &with);
    let (cpu_without, gpu_without) = both(&gpu, &pass, &without);
    // Pixels whose rays miss the sphere yet lose at least a fifth of their light to it:
    // they look through its shadow.
    let camera = &with.camera;
    let mut shadowed = 0;
    for i in 0..cpu_with.len() {
        let (x, y) = ((i as u32 % camera.width_px), (i as u32 / camera.width_px));
        let ray = camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5);
        let sphere = with.occluders.primitives[0];
        if sphere
            .hit(ray.origin_m, ray.direction, 0.0, f64::INFINITY)
            .is_some()
        {
            continue;
        }
        // Rays that see no light without the sphere tell nothing.
        if cpu_without[i][1] <= 0.0 {
            continue;
        }
        let cpu_ratio = cpu_with[i][1] / cpu_without[i][1];
        if cpu_ratio > 0.8 {
            continue;
        }
        shadowed += 1;
        let gpu_ratio = gpu_with[i][1] / gpu_without[i][1];
        assert!(
            (gpu_ratio - cpu_ratio).abs() < 0.02,
            "pixel ({x}, {y}): GPU keeps {gpu_ratio} of the light, CPU {cpu_ratio}"
        );
    }
    assert!(
        shadowed >= 20,
        "only {shadowed} pixels look through the shadow"
    );
}
