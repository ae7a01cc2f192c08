//! The GPU virtual planes (`shaders/shafts/beams/planes.wgsl` and `ray_end.wgsl`
//! through render-wgpu's `shafts/beams/planes_pass.rs`) against their CPU twin
//! (atmosphere-core's `beams/methods/planes2000.rs`) on the same pixel rays of the
//! shipped scenes, with the same shadow maps and light maps. And the sphere's shadow in
//! the air: removing the sphere brightens the pixels that look through its shadow by the
//! same factor on both sides, so a pass that lost its shadows fails.

mod support;

use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::methods::planes2000::Planes2000;
use atmosphere_core::beams::occluder::Primitive;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::GpuContext;
use render_wgpu::shafts::beams::planes_pass::{GpuPlanes, PlanesPass};
use support::beams::{check_relative, cpu_pixels, gpu_pixels, shipped_scene};
use support::gpu_or_skip;

/// Largest |L_gpu - L_cpu| / max(L_cpu, floor) of a pixel and wavelength, the floor
/// 1e-3 of the image's brightest value at that wavelength: f32 against f64 in the same
/// sums over the planes, xi interpolated by the rasteriser against the CPU's
/// interpolation over the same triangles (docs/beams/planes2000.md).
const MAX_RELATIVE_ERROR: f64 = 2e-3;

fn planes(scene: &BeamScene) -> Planes2000 {
    let settings = BeamSettings {
        options: ModelOptions::parse(&["planes=100", "lattice=16", "shadow_map_px=256"]).unwrap(),
        ..BeamSettings::default()
    };
    Planes2000::new(scene, &settings).unwrap()
}

/// Radiance at the three wavelengths per pixel, row by row: (CPU, GPU).
fn both(gpu: &GpuContext, pass: &PlanesPass, scene: &BeamScene) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let method = planes(scene);
    let (image, _) = pass.render(gpu, &GpuPlanes::new(&method)).unwrap();
    (
        cpu_pixels(&method, scene),
        gpu_pixels(image.read_radiance(gpu).unwrap()),
    )
}

#[test]
fn gpu_planes_match_the_cpu_planes_on_the_shipped_scenes() {
    let Some(gpu) = gpu_or_skip("beams planes parity") else {
        return;
    };
    let pass = PlanesPass::new(&gpu).unwrap();
    for (name, width, height) in [
        ("sphere_spotlight.toml", 40, 60),
        ("stage_five_spots.toml", 64, 48),
        ("stained_glass_room.toml", 64, 48),
        ("teapot_spotlight.toml", 64, 48),
        ("point_lamp.toml", 64, 36),
    ] {
        let (cpu, gpu_pixels) = both(&gpu, &pass, &shipped_scene(name, width, height));
        check_relative(name, &cpu, &gpu_pixels, MAX_RELATIVE_ERROR);
    }
}

#[test]
fn the_sphere_darkens_the_air_in_its_shadow_on_the_gpu_planes_as_on_the_cpu() {
    let Some(gpu) = gpu_or_skip("beams planes shadow") else {
        return;
    };
    let pass = PlanesPass::new(&gpu).unwrap();
    let with = shipped_scene("sphere_spotlight.toml", 40, 60);
    let mut without = with.clone();
    without
        .occluders
        .primitives
        .retain(|p| !matches!(p, Primitive::Sphere { .. }));
    let (cpu_with, gpu_with) = both(&gpu, &pass, &with);
    let (cpu_without, gpu_without) = both(&gpu, &pass, &without);
    let camera = &with.camera;
    let sphere = with.occluders.primitives[0];
    let mut shadowed = 0;
    for i in 0..cpu_with.len() {
        let (x, y) = ((i as u32 % camera.width_px), (i as u32 / camera.width_px));
        let ray = camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5);
        let misses = sphere
            .hit(ray.origin_m, ray.direction, 0.0, f64::INFINITY)
            .is_none();
        // Rays that miss the sphere yet lose at least a fifth of their light to it look
        // through its shadow; rays that see no light without it tell nothing.
        if !misses || cpu_without[i][1] <= 0.0 || cpu_with[i][1] / cpu_without[i][1] > 0.8 {
            continue;
        }
        shadowed += 1;
        let cpu_ratio = cpu_with[i][1] / cpu_without[i][1];
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
