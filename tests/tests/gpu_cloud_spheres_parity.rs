//! The cloud spheres on the GPU (`shaders/clouds/spheres/image.wgsl`) against their CPU
//! twin (atmosphere-core's `clouds/spheres/composite.rs`, `spheres_only`), pixel by pixel
//! on 64 x 36 images: from 400 km over the limb (rays that end on the ground, rays that
//! enter the shells and leave them again, rays into space) and from 30 km looking 8
//! degrees down through the shells, under a sun 35 and 4 degrees up (the planet's
//! shadow on part of the view), over a cover with cells about 30 km across. The frames'
//! spheres step at a resolution divisor of 3 (`frame_reduced.wgsl`, `frame_upsample.wgsl`)
//! against its twin (`clouds/spheres/reduced.rs`, `spheres_image`) on the limb view
//! with a wall 100 km away over the left third: the same tolerance, and the wall's
//! pixels exactly clear.
//!
//! Tolerance: each pixel's radiance within 3 % of itself plus 1 % of the image's
//! brightest pixel, and its transmittance within 0.01, but for one value in a hundred,
//! which may be off by four times that: the GPU solves the rays' crossings with spheres
//! 6.4e6 m in radius in f32 (the discriminant carries about 5e6 m^2 of rounding, so a
//! crossing near its tangent moves by tens of metres against shells 300 m thick).
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::spheres::composite::spheres_only;
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use atmosphere_core::clouds::spheres::reduced::{SphereView, spheres_image};
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::geo::equirectangular::lat_lon;
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;
use render_wgpu::clouds::layer_uniform::LayerCamera;
use render_wgpu::clouds::spheres::frame_spheres::{FrameSpherePass, SphereScene};
use render_wgpu::clouds::spheres::image_formats::CLOUD_IMAGE_FORMAT;
use render_wgpu::clouds::spheres::sphere_cache::SphereCache;
use render_wgpu::clouds::spheres::sphere_inputs::SphereInputs;
use render_wgpu::clouds::spheres::sphere_pass::CloudSpherePass;
use render_wgpu::clouds::spheres::sphere_uniform::SphereUniform;

const BOTTOM_M: f64 = 6_360_000.0;
const RELATIVE: f64 = 0.03;
const OF_BRIGHTEST: f64 = 0.01;
const TRANSMITTANCE: f64 = 0.01;
const OUTLIER_FACTOR: f64 = 4.0;

/// Henyey-Greenstein tables, another g at each wavelength so that a swapped channel
/// shows.
fn orders() -> ScatteringOrders {
    let series: Vec<LegendreSeries> = [0.84, 0.85, 0.86]
        .iter()
        .map(|&g| LegendreSeries::henyey_greenstein(g, 300))
        .collect();
    ScatteringOrders::new(&series).unwrap()
}

fn cover() -> CoverGrid {
    CoverGrid::rasterize(1024, 512, |p| {
        let (lat, lon) = lat_lon(p);
        0.5 + 0.8 * (lat * 200.0).sin() * (lon * 150.0).cos()
    })
    .unwrap()
}

fn layer_settings() -> LayerSettings {
    LayerSettings {
        extinction_per_m: 0.004,
        method: LayerMethod::Octaves,
        ..LayerSettings::default()
    }
}

fn layer_lit_by(method: LayerMethod) -> CloudLayer {
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let settings = LayerSettings {
        method,
        ..layer_settings()
    };
    CloudLayer::new(settings, BOTTOM_M, cover(), phase).unwrap()
}

fn layer() -> CloudLayer {
    layer_lit_by(LayerMethod::Octaves)
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

/// The sun `elevation_deg` above the camera's horizon, ahead and to the right.
fn light(elevation_deg: f64) -> CloudLight {
    let e = elevation_deg.to_radians();
    CloudLight {
        sun_direction: DVec3::new(e.sin(), e.cos() * 0.8, e.cos() * 0.6),
        sun_irradiance: vec![1.47, 1.85, 1.91],
        sky_irradiance: vec![0.05, 0.12, 0.25],
        up: DVec3::X,
    }
}

#[test]
fn the_spheres_match_the_cpu_pixel_by_pixel() {
    let Some(gpu) = support::gpu_or_skip("the_spheres_match_the_cpu_pixel_by_pixel") else {
        return;
    };
    let orders = orders();
    let pass = CloudSpherePass::new(&gpu).unwrap();
    let views = [
        ("400 km over the limb, sun 35 deg", camera(4e5, -35.0), 35.0),
        ("400 km over the limb, sun 4 deg", camera(4e5, -35.0), 4.0),
        ("30 km, 8 deg down", camera(3e4, -8.0), 35.0),
    ];
    // The octaves on every view; the slab lights (`slab_light.rs`) from orbit and from
    // 30 km.
    let cases = views.iter().map(|v| (LayerMethod::Octaves, v)).chain(
        [LayerMethod::Eddington, LayerMethod::FourStream]
            .iter()
            .flat_map(|&m| [(m, &views[0]), (m, &views[2])]),
    );
    for (method, (name, camera, sun_elevation)) in cases {
        let layer = layer_lit_by(method);
        let light = light(*sun_elevation);
        let settings = SphereSettings {
            count: 5,
            attenuation_width: 512,
            ..SphereSettings::default()
        };
        let spheres = CloudSpheres::new(&layer, &settings, light.sun_direction).unwrap();
        let inputs = SphereInputs::new(&gpu, &spheres, &orders).unwrap();
        let params = SphereUniform::new(camera, &light, &spheres).unwrap();
        let gpu_image = pass.render(&gpu, (&params, method), &inputs).unwrap();
        let mut cpu_image = Vec::new();
        for y in 0..camera.height {
            for x in 0..camera.width {
                let d = camera.pixel_direction(x, y);
                let (cloud, _) = spheres_only(
                    &spheres,
                    &orders,
                    &light,
                    camera.position_m,
                    d,
                    f64::INFINITY,
                );
                cpu_image.push([
                    cloud.radiance[0],
                    cloud.radiance[1],
                    cloud.radiance[2],
                    cloud.transmittance[0],
                ]);
            }
        }
        assert_within_tolerance(&format!("{method}, {name}"), &cpu_image, &gpu_image);
    }
}

/// Checks `gpu_image` against `cpu_image` within the module's tolerance and prints the
/// worst value's share of it.
fn assert_within_tolerance(name: &str, cpu_image: &[[f64; 4]], gpu_image: &[[f32; 4]]) {
    {
        let brightest = cpu_image
            .iter()
            .flat_map(|p| p[..3].iter().copied())
            .fold(0.0, f64::max);
        let clouded = cpu_image.iter().filter(|p| p[3] < 0.5).count();
        assert!(
            brightest > 0.01 && clouded > 100,
            "{name}: the view must hold cloud ({clouded} pixels, brightest {brightest})"
        );
        let (mut outside, mut worst) = (0, 0.0f64);
        for (cpu, gpu) in cpu_image.iter().zip(gpu_image) {
            for c in 0..4 {
                let (want, got) = (cpu[c], f64::from(gpu[c]));
                let tolerance = if c < 3 {
                    RELATIVE * want.abs() + OF_BRIGHTEST * brightest
                } else {
                    TRANSMITTANCE
                };
                let ratio = (got - want).abs() / tolerance;
                assert!(got.is_finite(), "{name}: {got}");
                worst = worst.max(ratio);
                if ratio > 1.0 {
                    outside += 1;
                    assert!(
                        ratio <= OUTLIER_FACTOR,
                        "{name}: channel {c}: GPU {got} against CPU {want}"
                    );
                }
            }
        }
        println!(
            "{name}: {clouded} clouded pixels, brightest {brightest:.4}, worst {worst:.3} of \
             the tolerance, {outside} of {} values outside it",
            cpu_image.len() * 4
        );
        assert!(
            outside * 100 <= cpu_image.len() * 4,
            "{name}: {outside} values outside the tolerance"
        );
    }
}

/// The distance of the wall over the left third of the reduced test's frame, m: in
/// front of the layer, 400 km below.
const WALL_M: f64 = 100_000.0;

#[test]
fn the_reduced_frame_spheres_match_their_cpu_twin() {
    let Some(gpu) = support::gpu_or_skip("the_reduced_frame_spheres_match_their_cpu_twin") else {
        return;
    };
    let orders = orders();
    let camera = camera(4e5, -35.0);
    let light = light(35.0);
    let settings = SphereSettings {
        count: 5,
        attenuation_width: 512,
        resolution_divisor: 3,
    };
    let (width, height) = (camera.width, camera.height);
    let on_wall = |x: u32| x < width / 3;
    let mut surface = vec![[0.0f32; 4]; (width * height) as usize];
    for (i, texel) in surface.iter_mut().enumerate() {
        if on_wall(i as u32 % width) {
            *texel = [0.0, 0.0, 1.0, WALL_M as f32];
        }
    }
    let surface_texture = render_wgpu::gpu::pipeline::texture_2d(
        &gpu.device,
        "wall",
        (width, height),
        CLOUD_IMAGE_FORMAT,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    gpu.queue.write_texture(
        surface_texture.as_image_copy(),
        bytemuck::cast_slice(&surface),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(width * 16),
            rows_per_image: Some(height),
        },
        surface_texture.size(),
    );
    let surface_view = surface_texture.create_view(&Default::default());
    let cache = SphereCache::new(cover(), orders.clone());
    let layer_settings = layer_settings();
    let scene = SphereScene {
        camera,
        layer: &layer_settings,
        spheres: &settings,
        light: &light,
        bottom_radius_m: BOTTOM_M,
        cache: &cache,
        surface: &surface_view,
        has_surface: true,
        weight: 1.0,
    };
    let gpu_image = FrameSpherePass::new(&gpu)
        .unwrap()
        .render(&gpu, &scene)
        .unwrap();
    let spheres = CloudSpheres::new(&layer(), &settings, light.sun_direction).unwrap();
    let direction = |x: f64, y: f64| camera.direction_at(x, y);
    let end_m = |x: u32, _: u32| if on_wall(x) { WALL_M } else { f64::INFINITY };
    let view = SphereView {
        origin: camera.position_m,
        size: (width, height),
        direction: &direction,
        end_m: &end_m,
    };
    let cpu_image = spheres_image(&spheres, &orders, &light, &view, 3).unwrap();
    assert_within_tolerance("reduced by 3, a wall over a third", &cpu_image, &gpu_image);
    for (i, (cpu, gpu)) in cpu_image.iter().zip(&gpu_image).enumerate() {
        if on_wall(i as u32 % width) {
            assert_eq!(*cpu, [0.0, 0.0, 0.0, 1.0], "CPU, wall pixel {i}");
            assert_eq!(*gpu, [0.0, 0.0, 0.0, 1.0], "GPU, wall pixel {i}");
        }
    }
}
