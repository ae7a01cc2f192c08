//! What the cloud spheres pass costs against the hillaire sky pass, in one run on one
//! device at 1280 x 720: the hillaire frame of an orbit view (400 km up, looking 60
//! degrees below the horizon, sun 40 degrees up) through the `Renderer` (its per-step
//! GPU times), then the spheres pass of the same view over the generated cover at
//! 2048 x 1024 (the default 5 spheres, attenuation textures of 1,024 x 512), rounds
//! interleaved, medians. The spheres pass is timed by the wall clock around its dispatch
//! and read-back (lavapipe's timestamps around a lone compute pass read about 0.1 ms
//! whatever it does), so its ratio includes the read-back; the attenuation textures are
//! made on the CPU once for the sun and timed apart. The frames' spheres step
//! (`FrameSpherePass`, no surface, the layer's weight 0) is timed the same way at each
//! resolution divisor, every pixel shaded (1) and reduced and upsampled by span (2, 3,
//! 4), and each reduced image's error against the divisor 1 image is printed: the mean
//! absolute radiance difference over the mean radiance, and the largest transmittance
//! difference. The frames' step is also timed lit by the layer's slab methods
//! (`slab_light.rs`: eddington, four-stream) at divisors 1 and 3, each with its own
//! spheres (made before the rounds).
//!
//! Run: `cargo bench -p render-wgpu --bench cloud_spheres` (on lavapipe:
//! `WGPU_BACKEND=vulkan VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json`).

use std::time::Instant;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::cover::generated::{CoverParameters, GeneratedCover};
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;
use render_wgpu::Renderer;
use render_wgpu::clouds::layer_uniform::LayerCamera;
use render_wgpu::clouds::spheres::frame_spheres::{FrameSpherePass, SphereScene};
use render_wgpu::clouds::spheres::image_formats::CLOUD_IMAGE_FORMAT;
use render_wgpu::clouds::spheres::sphere_cache::SphereCache;
use render_wgpu::clouds::spheres::sphere_inputs::SphereInputs;
use render_wgpu::clouds::spheres::sphere_pass::CloudSpherePass;
use render_wgpu::clouds::spheres::sphere_uniform::SphereUniform;
use render_wgpu::frame::{Frame, LocalView};

const ROUNDS: usize = 3;
const WIDTH: u32 = 1280;
const HEIGHT: u32 = 720;
/// The frames' spheres step's resolution divisors timed.
const DIVISORS: [u32; 4] = [1, 2, 3, 4];

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Henyey-Greenstein tables of g = 0.85 at the three wavelengths.
fn orders_of_droplets() -> ScatteringOrders {
    let series = LegendreSeries::henyey_greenstein(0.85, 300);
    ScatteringOrders::new(&vec![series; 3]).unwrap()
}

/// The mean absolute radiance difference of `image` from `reference` over the
/// reference's mean radiance, and the largest transmittance difference.
fn image_error(image: &[[f32; 4]], reference: &[[f32; 4]]) -> (f64, f64) {
    let (mut difference, mut total, mut transmittance) = (0.0, 0.0, 0.0f64);
    for (p, q) in image.iter().zip(reference) {
        for c in 0..3 {
            difference += f64::from((p[c] - q[c]).abs());
            total += f64::from(q[c]);
        }
        transmittance = transmittance.max(f64::from((p[3] - q[3]).abs()));
    }
    (difference / total, transmittance)
}

fn main() {
    let view = LocalView {
        altitude_m: 400_000.0,
        view_zenith_deg: 150.0,
        view_azimuth_deg: 0.0,
        sun_zenith_deg: 50.0,
        sun_azimuth_deg: 120.0,
    };
    let atmosphere = Atmosphere::preset("earth").unwrap();
    let frame = Frame {
        camera_position_m: view.position_m(atmosphere.bottom_radius_m),
        orientation: view.orientation(),
        vertical_fov_deg: 60.0,
        sun_direction: view.sun_direction(),
        atmosphere: atmosphere.clone(),
        model: ModelId::Hillaire,
        settings: ModelSettings::default(),
        exposure_ev100: 14.0,
        width: WIDTH,
        height: HEIGHT,
        terrain: None,
    };
    let mut renderer = Renderer::headless().expect("a GPU adapter");
    let cover = GeneratedCover::new(CoverParameters::default()).unwrap();
    let grid = CoverGrid::rasterize(2048, 1024, |p| cover.cover(p)).unwrap();
    let cache = SphereCache::new(grid.clone(), orders_of_droplets());
    let settings = LayerSettings {
        method: LayerMethod::Octaves,
        ..LayerSettings::default()
    };
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let layer = CloudLayer::new(settings, atmosphere.bottom_radius_m, grid.clone(), phase).unwrap();
    let orders = orders_of_droplets();
    let start = Instant::now();
    let spheres =
        CloudSpheres::new(&layer, &SphereSettings::default(), frame.sun_direction).unwrap();
    let textures_ms = start.elapsed().as_secs_f64() * 1e3;
    let gpu = renderer.gpu();
    let inputs = SphereInputs::new(gpu, &spheres, &orders).unwrap();
    let pass = CloudSpherePass::new(gpu).unwrap();
    let orientation = frame.orientation;
    let camera = LayerCamera {
        position_m: frame.camera_position_m,
        forward: orientation * -DVec3::Z,
        right: orientation * DVec3::X,
        up: orientation * DVec3::Y,
        fov_deg: 60.0,
        width: WIDTH,
        height: HEIGHT,
    };
    let light = CloudLight {
        sun_direction: frame.sun_direction,
        sun_irradiance: vec![1.3, 1.5, 1.4],
        sky_irradiance: vec![0.1, 0.2, 0.35],
        up: frame.camera_position_m.normalize(),
    };
    let params = SphereUniform::new(&camera, &light, &spheres).unwrap();
    let frame_pass = FrameSpherePass::new(gpu).unwrap();
    let usage = wgpu::TextureUsages::TEXTURE_BINDING;
    let no_surface = render_wgpu::gpu::pipeline::texture_2d(
        &gpu.device,
        "no surface",
        (1, 1),
        CLOUD_IMAGE_FORMAT,
        usage,
    )
    .create_view(&Default::default());
    let sphere_settings: Vec<SphereSettings> = DIVISORS
        .iter()
        .map(|&resolution_divisor| SphereSettings {
            resolution_divisor,
            ..SphereSettings::default()
        })
        .collect();
    let scene = |spheres| SphereScene {
        camera,
        layer: &settings,
        spheres,
        light: &light,
        bottom_radius_m: atmosphere.bottom_radius_m,
        cache: &cache,
        surface: &no_surface,
        has_surface: false,
        weight: 1.0,
    };
    // The frames' spheres are made on the CPU at their first use; not timed.
    let reference = frame_pass
        .render(renderer.gpu(), &scene(&sphere_settings[0]))
        .unwrap();
    // The slab lights: their layer settings and spheres, each at divisors 1 and 3.
    let slab_lights: Vec<(LayerSettings, SphereCache)> =
        [LayerMethod::Eddington, LayerMethod::FourStream]
            .into_iter()
            .map(|method| {
                let lit = LayerSettings { method, ..settings };
                (lit, SphereCache::new(grid.clone(), orders_of_droplets()))
            })
            .collect();
    let slab_scenes: Vec<Vec<SphereScene>> = slab_lights
        .iter()
        .map(|(lit, cache)| {
            [0, 2]
                .into_iter()
                .map(|k| SphereScene {
                    layer: lit,
                    cache,
                    ..scene(&sphere_settings[k])
                })
                .collect()
        })
        .collect();
    for scenes in &slab_scenes {
        frame_pass.render(renderer.gpu(), &scenes[0]).unwrap();
    }
    let mut slab_ms = vec![[Vec::new(), Vec::new()]; slab_lights.len()];
    let (mut sky_ms, mut frame_ms, mut spheres_ms) = (Vec::new(), Vec::new(), Vec::new());
    let mut step_ms = vec![Vec::new(); DIVISORS.len()];
    let mut errors = vec![(0.0, 0.0); DIVISORS.len()];
    let mut clouded = 0;
    for _ in 0..ROUNDS {
        let start = Instant::now();
        let plan = renderer.render(&frame).expect("the hillaire frame");
        frame_ms.push(start.elapsed().as_secs_f64() * 1e3);
        let step = plan.steps.iter().find(|s| s.name == "hillaire");
        sky_ms.push(
            step.and_then(|s| s.gpu_ms)
                .expect("the hillaire pass's GPU time"),
        );
        let start = Instant::now();
        let pixels = pass
            .render(renderer.gpu(), (&params, spheres.method()), &inputs)
            .unwrap();
        spheres_ms.push(start.elapsed().as_secs_f64() * 1e3);
        clouded = pixels.iter().filter(|p| p[3] < 0.5).count();
        for (k, spheres) in sphere_settings.iter().enumerate() {
            let start = Instant::now();
            let image = frame_pass.render(renderer.gpu(), &scene(spheres)).unwrap();
            step_ms[k].push(start.elapsed().as_secs_f64() * 1e3);
            errors[k] = image_error(&image, &reference);
        }
        for (scenes, times) in slab_scenes.iter().zip(slab_ms.iter_mut()) {
            for (scene, divisor_times) in scenes.iter().zip(times.iter_mut()) {
                let start = Instant::now();
                frame_pass.render(renderer.gpu(), scene).unwrap();
                divisor_times.push(start.elapsed().as_secs_f64() * 1e3);
            }
        }
    }
    let (sky, whole, spheres) = (median(sky_ms), median(frame_ms), median(spheres_ms));
    println!(
        "{}: hillaire pass {sky:.1} ms (GPU timer), whole hillaire frame {whole:.1} ms (wall \
         clock, with read-back); {clouded} of {} pixels behind cloud (T < 0.5)",
        renderer.gpu().adapter_summary(),
        WIDTH * HEIGHT
    );
    println!(
        "cloud spheres: {spheres:.1} ms (wall clock, with read-back), {:.3} x the hillaire \
         pass, {:.3} x the whole frame; attenuation textures on the CPU {textures_ms:.0} ms",
        spheres / sky,
        spheres / whole
    );
    for ((divisor, times), (radiance, transmittance)) in DIVISORS.iter().zip(step_ms).zip(errors) {
        let step = median(times);
        println!(
            "frames' spheres step, divisor {divisor}: {step:.1} ms (wall clock, with \
             read-back), {:.3} x the hillaire pass; against divisor 1: radiance {:.2} %, \
             transmittance {transmittance:.3}",
            step / sky,
            100.0 * radiance
        );
    }
    for ((lit, _), times) in slab_lights.iter().zip(slab_ms) {
        for (divisor, divisor_times) in [1, 3].into_iter().zip(times) {
            let step = median(divisor_times);
            println!(
                "frames' spheres step lit by {}, divisor {divisor}: {step:.1} ms (wall clock, \
                 with read-back), {:.3} x the hillaire pass",
                lit.method,
                step / sky
            );
        }
    }
}
