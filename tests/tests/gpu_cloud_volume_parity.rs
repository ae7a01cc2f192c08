//! Half-angle slicing of a voxel cloud on the GPU (render-wgpu's
//! `clouds/volume/slicing_pass.rs`, `shaders/clouds/volume/`) against its CPU twin
//! (atmosphere-core's `clouds/volume/slicing.rs`), pixel by pixel on 64 x 64 images of
//! a ball of cloud and of the shipped cumulus, facing away from the sun (front to back)
//! and towards it (back to front), with Riley's light and the octaves.
//!
//! Tolerance: each pixel's radiance within 0.5 % of itself plus 0.1 % of the image's
//! brightest pixel, and its transmittance within 0.001, but for one value in a hundred,
//! which may be off by four times that: Riley's order index floor(albedo tau) + 1 jumps
//! where tau crosses an integer, and f32 may put a pixel on either side; the proxy
//! polygons' rasterised edges and the CPU's box test may differ by a pixel where the
//! density on the box's faces is not 0.
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use std::path::Path;

use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::LayerMethod;
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::volume::camera::{VolumeCamera, VolumeSun};
use atmosphere_core::clouds::volume::cloud::VoxelCloud;
use atmosphere_core::clouds::volume::grid::VoxelGrid;
use atmosphere_core::clouds::volume::image::VolumeImage;
use atmosphere_core::clouds::volume::scene::VolumeScene;
use atmosphere_core::clouds::volume::settings::VolumeSettings;
use atmosphere_core::clouds::volume::slicing::slicing_image;
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;
use render_wgpu::clouds::volume::slicing_pass::slicing_image_gpu;

const RELATIVE: f64 = 0.005;
const OF_BRIGHTEST: f64 = 0.001;
const TRANSMITTANCE: f64 = 0.001;
const OUTLIER_FACTOR: f64 = 4.0;

/// Henyey-Greenstein tables, another g at each wavelength so that a swapped channel shows.
fn orders() -> ScatteringOrders {
    let series: Vec<LegendreSeries> = [0.84, 0.85, 0.86]
        .iter()
        .map(|&g| LegendreSeries::henyey_greenstein(g, 300))
        .collect();
    ScatteringOrders::new(&series).unwrap()
}

fn phase() -> CloudPhase {
    CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap()
}

/// A ball of cloud, 0 on the grid's faces, 240 m across, extinction up to 0.05 m^-1.
fn ball() -> VoxelCloud {
    let n = 24;
    let density = (0..n * n * n)
        .map(|k| {
            let c = |i: usize| (i as f64 + 0.5) / (n as f64 / 2.0) - 1.0;
            let (x, y, z) = (c(k % n), c((k / n) % n), c(k / (n * n)));
            let r2 = x * x + y * y + z * z;
            if r2 >= 1.0 {
                0.0
            } else {
                ((-3.0 * r2).exp() * (1.0 - r2)) as f32
            }
        })
        .collect();
    let grid = VoxelGrid::new([n, n, n], density).unwrap();
    VoxelCloud::new(
        grid,
        DVec3::new(-120.0, -120.0, 500.0),
        10.0,
        0.05,
        1.0,
        phase(),
    )
    .unwrap()
}

/// Counts the values outside the tolerance (none may exceed OUTLIER_FACTOR times it);
/// returns (outliers, values, worst multiple of the tolerance).
fn compare(name: &str, gpu: &VolumeImage, cpu: &VolumeImage) -> (usize, usize, f64) {
    let brightest = cpu.radiance.iter().copied().fold(0.0, f64::max);
    assert!(brightest > 0.0, "{name}: a black image");
    let mut outliers = 0;
    let mut worst: f64 = 0.0;
    for (g, c) in gpu.radiance.iter().zip(&cpu.radiance) {
        assert!(g.is_finite(), "{name}: {g}");
        let ratio = (g - c).abs() / (RELATIVE * c.abs() + OF_BRIGHTEST * brightest);
        worst = worst.max(ratio);
        outliers += usize::from(ratio > 1.0);
    }
    for (g, c) in gpu.transmittance.iter().zip(&cpu.transmittance) {
        let ratio = (g - c).abs() / TRANSMITTANCE;
        worst = worst.max(ratio);
        outliers += usize::from(ratio > 1.0);
    }
    let values = cpu.radiance.len() + cpu.transmittance.len();
    println!("{name}: {outliers} of {values} outside the tolerance, worst {worst:.3} of it");
    assert!(worst <= OUTLIER_FACTOR, "{name}: worst {worst}");
    assert!(outliers * 100 <= values, "{name}: {outliers} of {values}");
    (outliers, values, worst)
}

#[test]
fn slicing_on_the_gpu_matches_the_cpu_pixel_by_pixel() {
    let Some(gpu) = support::gpu_or_skip("slicing_on_the_gpu_matches_the_cpu_pixel_by_pixel")
    else {
        return;
    };
    let orders = orders();
    let sun = VolumeSun::new(35.0, 30.0, vec![1.474, 1.8504, 1.91198]).unwrap();
    let ball = ball();
    let centre = DVec3::new(0.0, 0.0, 500.0);
    for (name, position, light) in [
        (
            "ball, facing away, riley",
            DVec3::new(600.0, 350.0, 900.0),
            LayerMethod::Riley,
        ),
        (
            "ball, facing away, octaves",
            DVec3::new(600.0, 350.0, 900.0),
            LayerMethod::Octaves,
        ),
        (
            "ball, facing the sun, riley",
            DVec3::new(-650.0, -380.0, 300.0),
            LayerMethod::Riley,
        ),
        (
            "ball, facing the sun, octaves",
            DVec3::new(-650.0, -380.0, 300.0),
            LayerMethod::Octaves,
        ),
    ] {
        let camera = VolumeCamera::looking_at(position, centre, 30.0, 64, 64).unwrap();
        let settings = VolumeSettings {
            light,
            slices: 64,
            light_buffer_px: 64,
            ..VolumeSettings::default()
        };
        let cpu = slicing_image(&ball, &camera, &sun, &orders, &settings).unwrap();
        let on_gpu = slicing_image_gpu(&gpu, &ball, &camera, &sun, &orders, &settings).unwrap();
        compare(name, &on_gpu, &cpu);
    }
    // The shipped cumulus at 64 x 64, its own view and sun.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/clouds/cumulus.toml");
    let scene = VolumeScene::load(&path, phase()).unwrap();
    let camera = VolumeCamera {
        width_px: 64,
        height_px: 64,
        ..scene.camera
    };
    let settings = VolumeSettings {
        slices: 96,
        light_buffer_px: 96,
        ..scene.settings
    };
    let cpu = slicing_image(&scene.cloud, &camera, &scene.sun, &orders, &settings).unwrap();
    let on_gpu =
        slicing_image_gpu(&gpu, &scene.cloud, &camera, &scene.sun, &orders, &settings).unwrap();
    compare("cumulus, riley", &on_gpu, &cpu);
}
