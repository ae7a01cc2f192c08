//! The cloud layer's march on the GPU (`shaders/clouds/layer_image.wgsl`) against its
//! CPU twin (atmosphere-core's `clouds/layer/shell.rs` and `march.rs`), pixel by pixel on
//! 64 x 36 images: from the ground, from inside the layer and from above the deck, with
//! both methods, over a cover with structure at the scale of the view; and the
//! interactive and offline presets (`MarchQuality`), the interactive one marched at a third
//! of the resolution and interpolated (`clouds/layer/upsample.rs`), whose distance from the
//! full-resolution march is bounded too. A layer lit by the sun map (`sun_light = map`)
//! reads a map filled on the GPU (`sun_map_fill.wgsl`) against
//! `march_in_sun_map` with the CPU's map (`CloudSunMap`, of `SunMapResolution::LIT`), the
//! two maps agreeing within 0.005 in transmittance (`gpu_cloud_sun_map.rs`).
//!
//! Tolerance: each pixel's radiance within 3 % of itself plus 1 % of the image's
//! brightest pixel, but for one value in a hundred (of three per pixel), which may be
//! off by four times that (`JUMP_FACTOR`); the transmittance within 0.01. The GPU works in f32 about the
//! planet's centre (a point 6.36e6 m out carries 0.5 m of rounding, 3e-4 of a 1500 m
//! layer and of a 2 km noise cell) and the march's early stop at T < 1e-4 may fall one
//! step apart (under a preset that stops at T < 0.02, the transmittance may differ by
//! that much).
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::{CloudLight, MarchRay, march, march_in_sun_map};
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::presets::MarchQuality;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings, SunLight};
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::clouds::layer::upsample::{marched_coordinate, reduced_size, upsample};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::geo::equirectangular::lat_lon;
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;
use render_wgpu::clouds::layer_inputs::LayerInputs;
use render_wgpu::clouds::layer_pass::CloudLayerPass;
use render_wgpu::clouds::layer_uniform::{LayerCamera, LayerUniform};
use render_wgpu::clouds::sun_map_pass::SunMapPass;
use render_wgpu::clouds::sun_map_texture::{SunMapTexture, SunMapUniform};

const BOTTOM_M: f64 = 6_360_000.0;
const RELATIVE: f64 = 0.03;
const OF_BRIGHTEST: f64 = 0.01;
const TRANSMITTANCE: f64 = 0.01;
/// How far past the tolerance one value in a hundred may lie: Riley's order index
/// floor(albedo tau) + 1 jumps A_n where the sun's optical depth crosses an integer, and
/// f32 rounding may put a pixel on either side.
const JUMP_FACTOR: f64 = 4.0;

/// Henyey-Greenstein tables, another g at each wavelength so that a swapped channel
/// shows.
fn orders() -> ScatteringOrders {
    let series: Vec<LegendreSeries> = [0.84, 0.85, 0.86]
        .iter()
        .map(|&g| LegendreSeries::henyey_greenstein(g, 300))
        .collect();
    ScatteringOrders::new(&series).unwrap()
}

/// The test cover's grid: 20 km texels.
const COVER_WIDTH: usize = 2048;
const COVER_HEIGHT: usize = 1024;

/// Cells about 15 km across near (0 N, 0 E), where the cameras are, on the
/// `COVER_WIDTH` x `COVER_HEIGHT` grid: cover from 0 to 1 within a view.
fn cover() -> CoverGrid {
    CoverGrid::rasterize(COVER_WIDTH, COVER_HEIGHT, |p| {
        let (lat, lon) = lat_lon(p);
        0.5 + 0.8 * (lat * 400.0).sin() * (lon * 300.0).cos()
    })
    .unwrap()
}

/// The pass's parameters for `camera` under a sun `sun_elevation_deg` up, over
/// [`cover`]'s grid.
fn params(camera: &LayerCamera, sun_elevation_deg: f64, settings: &LayerSettings) -> LayerUniform {
    LayerUniform::new(
        camera,
        &light(sun_elevation_deg),
        settings,
        BOTTOM_M,
        (COVER_WIDTH, COVER_HEIGHT),
    )
    .unwrap()
}

fn camera(altitude_m: f64, pitch_deg: f64) -> LayerCamera {
    let position_m = DVec3::new(BOTTOM_M + altitude_m, 0.0, 0.0);
    let pitch = pitch_deg.to_radians();
    let forward = DVec3::new(pitch.sin(), pitch.cos(), 0.0);
    let right = DVec3::Z;
    LayerCamera {
        position_m,
        forward,
        right,
        up: right.cross(forward),
        fov_deg: 60.0,
        width: 64,
        height: 36,
    }
}

fn light(sun_elevation_deg: f64) -> CloudLight {
    let e = sun_elevation_deg.to_radians();
    CloudLight {
        sun_direction: DVec3::new(e.sin(), e.cos() * 0.6, e.cos() * 0.8),
        sun_irradiance: vec![1.2, 1.5, 1.4],
        sky_irradiance: vec![0.1, 0.2, 0.35],
        up: DVec3::X,
    }
}

/// The sun maps of `layer` under `camera` for `light`'s sun, on the CPU and filled on
/// the GPU (with the layer's parameters `params`).
fn sun_maps(
    gpu: &render_wgpu::GpuContext,
    inputs: &LayerInputs,
    (layer, camera, light): (&CloudLayer, &LayerCamera, &CloudLight),
    params: &LayerUniform,
) -> (CloudSunMap, SunMapTexture) {
    let resolution = SunMapResolution::LIT;
    let grid = CloudSunMap::grid_for(layer.shell(), camera.position_m, &resolution).unwrap();
    let sun = light.sun_direction;
    let top = layer.shell().top_radius_m;
    let uniform = SunMapUniform::new(&grid, sun, top, &resolution);
    let cpu = CloudSunMap::new(layer, grid, sun, &resolution).unwrap();
    let mut texture = SunMapTexture::new(gpu);
    texture.set(gpu, Some(&uniform), (1, 1)).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let fill = SunMapPass::new(gpu).unwrap();
    fill.encode(gpu, &mut encoder, params, &inputs.cover, &texture, None);
    gpu.queue.submit([encoder.finish()]);
    (cpu, texture)
}

/// The CPU's [radiance x 3, transmittance] of every pixel: marched at the layer's
/// resolution divisor (lit through `map` when given) and interpolated to full size.
fn cpu_image(
    layer: &CloudLayer,
    camera: &LayerCamera,
    (light, map): (&CloudLight, Option<&CloudSunMap>),
    orders: &ScatteringOrders,
) -> Vec<[f64; 4]> {
    let (w, h) = reduced_size(
        camera.width,
        camera.height,
        layer.settings().resolution_divisor,
    );
    let mut image = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let d = camera.direction_at(
                marched_coordinate(x, w, camera.width),
                marched_coordinate(y, h, camera.height),
            );
            let o = camera.position_m;
            image.push(match layer.shell().first_segment(o, d, f64::INFINITY) {
                Some((t0, t1)) => {
                    let light = CloudLight {
                        up: (o + d * t0).normalize(),
                        ..light.clone()
                    };
                    let ray = MarchRay {
                        origin: o,
                        direction: d,
                        t0,
                        t1,
                    };
                    let s = layer.settings();
                    let c = match map {
                        Some(m) => march_in_sun_map(layer, &ray, &light, orders, s, m),
                        None => march(layer, &ray, &light, orders, s),
                    };
                    [
                        c.radiance[0],
                        c.radiance[1],
                        c.radiance[2],
                        c.transmittance[0],
                    ]
                }
                None => [0.0, 0.0, 0.0, 1.0],
            });
        }
    }
    upsample(&image, (w, h), camera.width, camera.height)
}

/// Renders `settings` on the GPU and the CPU and checks every pixel against the
/// module's tolerance (the transmittance's at least the settings' stopping
/// transmittance); returns the GPU image.
fn check_parity(
    gpu: &render_wgpu::GpuContext,
    (pass, inputs): (&CloudLayerPass, &LayerInputs),
    name: &str,
    (camera, sun_elevation): (LayerCamera, f64),
    settings: LayerSettings,
) -> Vec<[f32; 4]> {
    let (orders, cover) = (orders(), cover());
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let layer = CloudLayer::new(settings, BOTTOM_M, cover.clone(), phase).unwrap();
    let light = light(sun_elevation);
    let params = params(&camera, sun_elevation, &settings);
    let maps = (settings.sun_light == SunLight::Map)
        .then(|| sun_maps(gpu, inputs, (&layer, &camera, &light), &params));
    let gpu_image = pass
        .render(gpu, (&params, inputs), maps.as_ref().map(|m| &m.1))
        .unwrap();
    let cpu = cpu_image(
        &layer,
        &camera,
        (&light, maps.as_ref().map(|m| &m.0)),
        &orders,
    );
    let brightest = cpu
        .iter()
        .flat_map(|p| p[..3].iter().copied())
        .fold(0.0, f64::max);
    let clouded = cpu.iter().filter(|p| p[3] < 0.5).count();
    let clear = cpu.iter().filter(|p| p[3] > 0.99).count();
    assert!(brightest > 1e-3, "{name}: no cloud lit");
    assert!(clouded > 100, "{name}: {clouded} clouded pixels");
    let transmittance_tolerance = TRANSMITTANCE.max(settings.min_transmittance);
    let mut worst: f64 = 0.0;
    let mut outside = 0;
    for (k, (g, c)) in gpu_image.iter().zip(&cpu).enumerate() {
        for w in 0..3 {
            let error = (f64::from(g[w]) - c[w]).abs();
            let allowed = RELATIVE * c[w] + OF_BRIGHTEST * brightest;
            worst = worst.max(error / allowed);
            if error > allowed {
                outside += 1;
            }
            assert!(
                error <= JUMP_FACTOR * allowed,
                "{name}: pixel {k} wavelength {w}: GPU {} CPU {}",
                g[w],
                c[w]
            );
        }
        assert!(
            (f64::from(g[3]) - c[3]).abs() <= transmittance_tolerance,
            "{name}: pixel {k} T: GPU {} CPU {}",
            g[3],
            c[3]
        );
    }
    println!(
        "{name}: brightest {brightest:.4}, {clouded} of {} pixels clouded, {clear} clear, \
         {outside} values outside the tolerance, worst {worst:.3} of it",
        cpu.len()
    );
    assert!(
        outside * 100 <= 3 * cpu.len(),
        "{name}: {outside} values outside"
    );
    gpu_image
}

#[test]
fn the_gpu_march_matches_the_cpu_from_below_inside_and_above() {
    let Some(gpu) = support::gpu_or_skip("cloud layer parity") else {
        return;
    };
    let inputs = LayerInputs::new(&gpu, &cover(), &orders()).unwrap();
    let pass = CloudLayerPass::new(&gpu).unwrap();
    let (march, map) = (SunLight::March, SunLight::Map);
    let views = [
        (
            "below, riley",
            camera(10.0, 35.0),
            LayerMethod::Riley,
            40.0,
            march,
        ),
        (
            "inside, octaves",
            camera(2200.0, 0.0),
            LayerMethod::Octaves,
            25.0,
            march,
        ),
        (
            "inside, riley, low sun",
            camera(2200.0, 5.0),
            LayerMethod::Riley,
            10.0,
            march,
        ),
        (
            "above, riley",
            camera(5000.0, -30.0),
            LayerMethod::Riley,
            50.0,
            march,
        ),
        (
            "below, riley, map",
            camera(10.0, 35.0),
            LayerMethod::Riley,
            40.0,
            map,
        ),
        (
            "inside, octaves, map",
            camera(2200.0, 0.0),
            LayerMethod::Octaves,
            25.0,
            map,
        ),
        (
            "above, octaves, map, low sun",
            camera(5000.0, -30.0),
            LayerMethod::Octaves,
            10.0,
            map,
        ),
        (
            "below, eddington",
            camera(10.0, 35.0),
            LayerMethod::Eddington,
            40.0,
            march,
        ),
        (
            "inside, eddington, map, low sun",
            camera(2200.0, 5.0),
            LayerMethod::Eddington,
            10.0,
            map,
        ),
        (
            "above, eddington",
            camera(5000.0, -30.0),
            LayerMethod::Eddington,
            50.0,
            march,
        ),
        (
            "below, four-stream",
            camera(10.0, 35.0),
            LayerMethod::FourStream,
            40.0,
            march,
        ),
        (
            "inside, four-stream, map, low sun",
            camera(2200.0, 5.0),
            LayerMethod::FourStream,
            10.0,
            map,
        ),
        (
            "above, four-stream",
            camera(5000.0, -30.0),
            LayerMethod::FourStream,
            50.0,
            march,
        ),
    ];
    for (name, camera, method, sun_elevation, sun_light) in views {
        let settings = LayerSettings {
            method,
            sun_light,
            steps: 32,
            shadow_steps: 6,
            ..LayerSettings::default()
        };
        check_parity(
            &gpu,
            (&pass, &inputs),
            name,
            (camera, sun_elevation),
            settings,
        );
    }
}

/// The interactive preset's reduced-resolution image lies within this mean absolute
/// radiance error (relative to the mean radiance) of the same march at full resolution.
/// At 64 x 36 over 60 degrees a pixel spans a degree, twenty times a 1280 x 720 pixel,
/// and the interpolation spans three: the worst case of the views the renderer draws.
const UPSAMPLE_MEAN_ERROR: f64 = 0.2;

#[test]
fn the_presets_match_the_cpu_and_the_reduced_march_stays_near_the_full() {
    let Some(gpu) = support::gpu_or_skip("cloud layer presets") else {
        return;
    };
    let inputs = LayerInputs::new(&gpu, &cover(), &orders()).unwrap();
    let pass = CloudLayerPass::new(&gpu).unwrap();
    let riley = LayerSettings::default();
    let octaves = LayerSettings {
        method: LayerMethod::Octaves,
        ..riley
    };
    let interactive = MarchQuality::Interactive;
    let views = [
        (
            "interactive, below, riley",
            camera(10.0, 35.0),
            40.0,
            interactive.apply(riley),
        ),
        (
            "interactive, inside, octaves",
            camera(2200.0, 0.0),
            25.0,
            interactive.apply(octaves),
        ),
        (
            "interactive, inside, octaves, map",
            camera(2200.0, 0.0),
            25.0,
            LayerSettings {
                sun_light: SunLight::Map,
                ..interactive.apply(octaves)
            },
        ),
        (
            "interactive, above, riley",
            camera(5000.0, -30.0),
            50.0,
            interactive.apply(riley),
        ),
        (
            "offline, below, octaves",
            camera(10.0, 35.0),
            40.0,
            MarchQuality::Offline.apply(octaves),
        ),
    ];
    for (name, camera, sun_elevation, settings) in views {
        let image = check_parity(
            &gpu,
            (&pass, &inputs),
            name,
            (camera, sun_elevation),
            settings,
        );
        if settings.resolution_divisor == 1 {
            continue;
        }
        let full = LayerSettings {
            resolution_divisor: 1,
            ..settings
        };
        let params = params(&camera, sun_elevation, &full);
        let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
        let layer = CloudLayer::new(full, BOTTOM_M, cover(), phase).unwrap();
        let light = light(sun_elevation);
        let maps = (full.sun_light == SunLight::Map)
            .then(|| sun_maps(&gpu, &inputs, (&layer, &camera, &light), &params));
        let map = maps.as_ref().map(|m| &m.1);
        let reference = pass.render(&gpu, (&params, &inputs), map).unwrap();
        let (mut error, mut total) = (0.0, 0.0);
        for (p, q) in image.iter().zip(&reference) {
            for w in 0..3 {
                error += f64::from((p[w] - q[w]).abs());
                total += f64::from(q[w]);
            }
        }
        println!(
            "{name}: reduced resolution against full, mean radiance error {:.4} of the mean",
            error / total
        );
        assert!(
            error <= UPSAMPLE_MEAN_ERROR * total,
            "{name}: {error} of {total}"
        );
    }
}

#[test]
fn tables_for_other_than_three_wavelengths_are_refused_by_name() {
    let Some(gpu) = support::gpu_or_skip("cloud layer inputs") else {
        return;
    };
    let one = ScatteringOrders::new(&[LegendreSeries::henyey_greenstein(0.5, 30)]).unwrap();
    let e = LayerInputs::new(&gpu, &cover(), &one).unwrap_err();
    assert!(
        e.to_string()
            .contains("cloud phase tables for 1 wavelengths"),
        "{e}"
    );
}

#[test]
fn a_light_method_outside_its_range_is_refused_by_name() {
    let Some(gpu) = support::gpu_or_skip("cloud layer method") else {
        return;
    };
    let inputs = LayerInputs::new(&gpu, &cover(), &orders()).unwrap();
    let pass = CloudLayerPass::new(&gpu).unwrap();
    let mut params = params(&camera(500.0, 10.0), 30.0, &LayerSettings::default());
    params.counts[2] = 4;
    let e = pass.render(&gpu, (&params, &inputs), None).unwrap_err();
    assert!(e.to_string().contains("light method 4"), "{e}");
}

/// The slab methods on the GPU stay finite and non-negative where their slab is extreme:
/// a thousand times the default deck's optical depth (extinction 1 m^-1 over 1.5 km:
/// 1,500) seen from inside and from above, and the sun 10 degrees below the horizon.
#[test]
fn the_slab_methods_stay_finite_in_dense_cloud_and_at_night() {
    let Some(gpu) = support::gpu_or_skip("cloud layer slab methods, dense and at night") else {
        return;
    };
    let inputs = LayerInputs::new(&gpu, &cover(), &orders()).unwrap();
    let pass = CloudLayerPass::new(&gpu).unwrap();
    for method in [LayerMethod::Eddington, LayerMethod::FourStream] {
        for (extinction_per_m, sun_elevation) in [(1.0, 30.0), (0.04, -10.0)] {
            for camera in [camera(2200.0, 0.0), camera(5000.0, -30.0)] {
                let settings = LayerSettings {
                    method,
                    extinction_per_m,
                    steps: 32,
                    shadow_steps: 6,
                    ..LayerSettings::default()
                };
                let params = params(&camera, sun_elevation, &settings);
                let image = pass.render(&gpu, (&params, &inputs), None).unwrap();
                let bad = image
                    .iter()
                    .flatten()
                    .filter(|v| !v.is_finite() || **v < 0.0)
                    .count();
                assert_eq!(
                    bad, 0,
                    "{method}, extinction {extinction_per_m}, sun {sun_elevation}"
                );
                assert!(
                    image.iter().any(|p| p[3] < 0.5),
                    "{method}: no cloud in view"
                );
            }
        }
    }
}
