//! The GPU q(u, v) table pass (`shaders/shafts/beams/qtable_walk.wgsl`, `qtable.wgsl`
//! and `q_table.wgsl` through render-wgpu's `shafts/beams/qtable_pass.rs`) against its
//! CPU twin (atmosphere-core's `beams/methods/qtable2002/`) on the same pixel rays of the
//! shipped scenes, with the same table, planes, sub-planes and shadow maps, the planes
//! walked per pixel (the default) and drawn one by one (`gpu_raster_planes=true`); the
//! sub-planes the GPU draws are the CPU's, appear only where f_l exceeds epsilon, and
//! change the GPU's picture; the walk at reduced resolution upsampled
//! (`resolution_divisor`, `qtable_upsample.wgsl`) against its CPU twin.

mod support;

use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::methods::qtable2002::Qtable2002;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::GpuContext;
use render_wgpu::shafts::beams::qtable_pass::{GpuQtable, QtablePass};
use support::beams::{check_relative, cpu_pixels, gpu_pixels, shipped_scene};
use support::gpu_or_skip;

/// Largest |L_gpu - L_cpu| / max(L_cpu, floor) of a pixel and wavelength, the floor
/// 1e-3 of the image's brightest value at that wavelength: the same table read in f32
/// against f64, the same samples and shadow maps (docs/beams/qtable2002.md).
const MAX_RELATIVE_ERROR: f64 = 2e-3;

fn qtable(scene: &BeamScene, epsilon: &str, raster: bool) -> Qtable2002 {
    qtable_with(scene, &[epsilon, &format!("gpu_raster_planes={raster}")])
}

fn qtable_with(scene: &BeamScene, options: &[&str]) -> Qtable2002 {
    let mut all = vec!["table_u=64", "table_v=64", "shadow_map_px=256"];
    all.extend_from_slice(options);
    let settings = BeamSettings {
        options: ModelOptions::parse(&all).unwrap(),
        ..BeamSettings::default()
    };
    Qtable2002::new(scene, &settings).unwrap()
}

/// Radiance at the three wavelengths per pixel, row by row: (CPU, GPU), and the
/// prepared method.
fn both(
    gpu: &GpuContext,
    pass: &QtablePass,
    method: &Qtable2002,
    scene: &BeamScene,
) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let (image, _) = pass.render(gpu, &GpuQtable::new(method)).unwrap();
    (
        cpu_pixels(method, scene),
        gpu_pixels(image.read_radiance(gpu).unwrap()),
    )
}

#[test]
fn gpu_qtable_matches_the_cpu_qtable_on_the_shipped_scenes() {
    let Some(gpu) = gpu_or_skip("beams qtable parity") else {
        return;
    };
    let pass = QtablePass::new(&gpu).unwrap();
    for (name, width, height) in [
        ("sphere_spotlight.toml", 40, 60),
        ("stage_five_spots.toml", 64, 48),
        ("stained_glass_room.toml", 64, 48),
        ("teapot_spotlight.toml", 64, 48),
        ("point_lamp.toml", 64, 36),
    ] {
        let s = shipped_scene(name, width, height);
        for raster in [false, true] {
            let method = qtable(&s, "epsilon=0.01", raster);
            assert_eq!(method.gpu_raster_planes(), raster);
            let (cpu, gpu_pixels) = both(&gpu, &pass, &method, &s);
            let what = format!("{name}, gpu_raster_planes={raster}");
            check_relative(&what, &cpu, &gpu_pixels, MAX_RELATIVE_ERROR);
        }
    }
}

#[test]
fn the_gpu_draws_the_cpus_subplanes_only_where_f_l_exceeds_epsilon() {
    let Some(gpu) = gpu_or_skip("beams qtable sub-planes") else {
        return;
    };
    let pass = QtablePass::new(&gpu).unwrap();
    let s = shipped_scene("sphere_spotlight.toml", 40, 60);
    let with = qtable(&s, "epsilon=0.01", false);
    let packed = GpuQtable::new(&with);
    let cpu_count: usize = with.planes().iter().map(|p| p.subplane_count()).sum();
    assert_eq!(packed.subplane_count(), cpu_count);
    let raster = GpuQtable::new(&qtable(&s, "epsilon=0.01", true));
    assert_eq!(raster.subplane_count(), cpu_count);
    assert!(cpu_count > 0, "no sub-planes at epsilon 0.01");
    // Every interval with sub-planes has f_l / m_k of at least epsilon of the centre
    // ray's whole f_l; every interval without has a share below 2 epsilon.
    for planes in with.planes() {
        for (&m, &share) in planes.samples.iter().zip(&planes.centre_share) {
            if m > 1 {
                assert!(share / m as f64 >= 0.01, "m = {m} at share {share}");
            } else {
                assert!(share < 0.02, "no sub-plane at share {share}");
            }
        }
    }
    // Without sub-planes (epsilon 1: no interval holds all the light) the GPU draws
    // none, and the picture changes as on the CPU.
    let without = qtable(&s, "epsilon=1", false);
    assert_eq!(GpuQtable::new(&without).subplane_count(), 0);
    let (cpu_with, gpu_with) = both(&gpu, &pass, &with, &s);
    let (cpu_without, gpu_without) = both(&gpu, &pass, &without, &s);
    check_relative("with sub-planes", &cpu_with, &gpu_with, MAX_RELATIVE_ERROR);
    check_relative(
        "without sub-planes",
        &cpu_without,
        &gpu_without,
        MAX_RELATIVE_ERROR,
    );
    let changed = |with: &[[f64; 3]], without: &[[f64; 3]]| {
        with.iter()
            .zip(without)
            .filter(|(a, b)| (a[1] - b[1]).abs() > 1e-2 * a[1])
            .count()
    };
    let on_cpu = changed(&cpu_with, &cpu_without);
    let on_gpu = changed(&gpu_with, &gpu_without);
    assert!(
        on_cpu >= 20,
        "sub-planes change only {on_cpu} pixels on the CPU"
    );
    assert!(
        on_gpu >= 20,
        "sub-planes change only {on_gpu} pixels on the GPU"
    );
}

/// Pixels whose largest |a - b| / max(a, floor) over the wavelengths exceeds `tolerance`,
/// the floor 1e-3 of `a`'s brightest value, and the largest such error.
fn differing(a: &[[f64; 3]], b: &[[f64; 3]], tolerance: f64) -> (usize, f64) {
    let floor: [f64; 3] =
        std::array::from_fn(|k| 1e-3 * a.iter().map(|p| p[k]).fold(0.0, f64::max));
    let errors = a.iter().zip(b).map(|(a, b)| {
        (0..3)
            .map(|k| (b[k] - a[k]).abs() / a[k].max(floor[k]))
            .fold(0.0, f64::max)
    });
    errors.fold((0, 0.0f64), |(n, worst), e| {
        (n + usize::from(e > tolerance), worst.max(e))
    })
}

#[test]
fn the_gpu_upsamples_its_reduced_walk_as_the_cpu_does() {
    let Some(gpu) = gpu_or_skip("beams qtable upsample") else {
        return;
    };
    let pass = QtablePass::new(&gpu).unwrap();
    for (name, width, height) in [
        ("sphere_spotlight.toml", 64, 96),
        ("stained_glass_room.toml", 64, 48),
        ("point_lamp.toml", 64, 36),
        // glTF meshes: the pixels walked at full size read the frame's traced ray ends.
        ("teapot_spotlight.toml", 64, 48),
        ("stage_five_spots.toml", 64, 48),
    ] {
        let s = shipped_scene(name, width, height);
        let walk = qtable_with(&s, &["epsilon=0.01"]);
        let reduced = qtable_with(&s, &["epsilon=0.01", "resolution_divisor=4"]);
        let (cpu, gpu_image) = both(&gpu, &pass, &reduced, &s);
        let cpu_walk = cpu_pixels(&walk, &s);
        // A pixel whose taps spread by about the tolerance may be interpolated on one
        // side and walked on the other (f32 against f64): a few such pixels, each off
        // by less than the interpolation's own error.
        let (apart, worst) = differing(&cpu, &gpu_image, MAX_RELATIVE_ERROR);
        println!("{name}: {apart} pixels beyond the parity, largest {worst:.2e}");
        assert!(apart * 100 <= cpu.len(), "{name}: {apart} pixels apart");
        assert!(worst < 0.1, "{name}: {worst}");
        // The upsample changes the picture, alike on both.
        let (changed_cpu, _) = differing(&cpu_walk, &cpu, 1e-2);
        let (changed_gpu, _) = differing(&cpu_walk, &gpu_image, 1e-2);
        println!("{name}: {changed_cpu} pixels changed on the CPU, {changed_gpu} on the GPU");
        assert!(changed_cpu >= 20 && changed_gpu >= 20, "{name}");
    }
}

/// The samples weighted by g at each and counted on each ray from its own f_l
/// (`weighted_samples`, `subplanes_per_ray`; not the paper's): the walk, the drawn planes
/// (weighted: drawn planes cannot count per ray) and the reduced walk, each within the
/// parity, and both settings change the picture.
#[test]
fn samples_weighted_and_counted_per_ray_match_the_cpu() {
    let Some(gpu) = gpu_or_skip("beams qtable weighted samples") else {
        return;
    };
    let pass = QtablePass::new(&gpu).unwrap();
    for (name, width, height) in [
        ("sphere_spotlight.toml", 40, 60),
        ("stained_glass_room.toml", 64, 48),
        ("teapot_spotlight.toml", 64, 48),
        ("point_lamp.toml", 64, 36),
    ] {
        let s = shipped_scene(name, width, height);
        let plain = cpu_pixels(&qtable_with(&s, &["epsilon=0.01"]), &s);
        for options in [
            &["weighted_samples=true", "subplanes_per_ray=true"][..],
            &["weighted_samples=true", "gpu_raster_planes=true"],
            &["subplanes_per_ray=true"],
        ] {
            let method = qtable_with(&s, &[&["epsilon=0.01"], options].concat());
            let (cpu, gpu_image) = both(&gpu, &pass, &method, &s);
            let what = format!("{name}, {options:?}");
            check_relative(&what, &cpu, &gpu_image, MAX_RELATIVE_ERROR);
            let (changed, _) = differing(&plain, &cpu, 1e-3);
            println!("{what}: {changed} pixels changed by the settings");
            assert!(
                changed >= 20,
                "{what}: the settings changed {changed} pixels"
            );
        }
    }
    let s = shipped_scene("sphere_spotlight.toml", 64, 96);
    let reduced = qtable_with(
        &s,
        &[
            "epsilon=0.005",
            "weighted_samples=true",
            "subplanes_per_ray=true",
            "resolution_divisor=4",
        ],
    );
    let (cpu, gpu_image) = both(&gpu, &pass, &reduced, &s);
    let (apart, worst) = differing(&cpu, &gpu_image, MAX_RELATIVE_ERROR);
    println!("reduced: {apart} pixels beyond the parity, largest {worst:.2e}");
    assert!(
        apart * 100 <= cpu.len() && worst < 0.1,
        "{apart} apart, {worst}"
    );
}
