//! The voxel cloud rendered by the ray march, by half-angle slicing and by the path
//! tracer: all three against the closed form of single scattering in a thin homogeneous
//! box, slicing converging to the march as its slices double, both within their energy
//! bounds, the path tracer's standard error honest and shrinking as its paths grow, and
//! the half vector's flip when the view turns away from the sun.

use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::LayerMethod;
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::volume::camera::{VolumeCamera, VolumeSun};
use atmosphere_core::clouds::volume::cloud::VoxelCloud;
use atmosphere_core::clouds::volume::grid::VoxelGrid;
use atmosphere_core::clouds::volume::half_angle::{HalfAngle, half_vector};
use atmosphere_core::clouds::volume::image::VolumeImage;
use atmosphere_core::clouds::volume::march_image::march_image;
use atmosphere_core::clouds::volume::path_traced::{
    MAX_PATHS_PER_PIXEL, PathTracedImage, PathTracing, path_traced_image,
};
use atmosphere_core::clouds::volume::settings::VolumeSettings;
use atmosphere_core::clouds::volume::slicing::slicing_image;
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::{PhaseFunction, henyey_greenstein};
use glam::DVec3;

mod common;

use common::voxel_ball::smooth_ball;

const G: f64 = 0.7;

fn orders() -> ScatteringOrders {
    ScatteringOrders::new(&[LegendreSeries::henyey_greenstein(G, 300)]).unwrap()
}

fn phase() -> CloudPhase {
    CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: G }).unwrap()
}

/// A 100 m box of uniform extinction `sigma` from the origin.
fn homogeneous_box(sigma: f64) -> VoxelCloud {
    let grid = VoxelGrid::new([8, 8, 8], vec![1.0; 512]).unwrap();
    VoxelCloud::new(grid, DVec3::ZERO, 12.5, sigma, 1.0, phase()).unwrap()
}

/// A smooth ball of cloud (`common/voxel_ball.rs`), albedo 1.
fn ball(sigma: f64) -> VoxelCloud {
    smooth_ball(sigma, 1.0, phase())
}

/// The path tracer's image with `paths` paths per pixel from `seed`, the forward peak
/// within `forward_peak_deg` taken as no scattering.
fn traced(
    cloud: &VoxelCloud,
    camera: &VolumeCamera,
    sun: &VolumeSun,
    orders: &ScatteringOrders,
    paths: u64,
    seed: u64,
    forward_peak_deg: f64,
) -> PathTracedImage {
    let tracing = PathTracing {
        paths,
        seed,
        forward_peak_deg,
    };
    path_traced_image(cloud, camera, sun, orders, &tracing, &|| {}).unwrap()
}

fn settings(light: LayerMethod, slices: u32) -> VolumeSettings {
    VolumeSettings {
        light,
        slices,
        light_buffer_px: 64,
        steps: 512,
        shadow_steps: 64,
        backscatter_xi: 0.0,
        octaves: 1,
    }
}

fn sun(elevation_deg: f64, azimuth_deg: f64) -> VolumeSun {
    VolumeSun::new(elevation_deg, azimuth_deg, vec![1.0]).unwrap()
}

fn largest(image: &VolumeImage) -> f64 {
    image.radiance.iter().copied().fold(0.0, f64::max)
}

/// Single scattering with the sun straight overhead, in closed form: along the ray
/// o + v t inside the box [t0, t1] the sun's optical depth sigma (100 - z(t)) is linear
/// in t, so with k = sigma (1 - v_z)
///     L = p(v_z) sigma exp(sigma t0 - sigma (100 - z0)) (exp(-k t0) - exp(-k t1)) / k,
/// z0 the camera's height; with `attenuated` false the sun's depth is left out (k = sigma).
fn closed_form(
    cloud: &VoxelCloud,
    camera: &VolumeCamera,
    sigma: f64,
    attenuated: bool,
) -> Vec<f64> {
    let mut out = Vec::new();
    for y in 0..camera.height_px {
        for x in 0..camera.width_px {
            let v = camera.direction(f64::from(x) + 0.5, f64::from(y) + 0.5);
            let Some((t0, t1)) = cloud.crossing(camera.position_m, v) else {
                out.push(0.0);
                continue;
            };
            let p = henyey_greenstein(G, v.z);
            let z0 = camera.position_m.z;
            out.push(if attenuated {
                let k = sigma * (1.0 - v.z);
                p * sigma
                    * (sigma * t0 - sigma * (100.0 - z0)).exp()
                    * ((-k * t0).exp() - (-k * t1).exp())
                    / k
            } else {
                p * (1.0 - (-sigma * (t1 - t0)).exp())
            });
        }
    }
    out
}

/// The largest difference from `truth` over its largest value.
fn worst_error(image: &VolumeImage, truth: &[f64]) -> f64 {
    let top = truth.iter().copied().fold(0.0, f64::max);
    image
        .radiance
        .iter()
        .zip(truth)
        .map(|(a, b)| (a - b).abs() / top)
        .fold(0.0, f64::max)
}

#[test]
fn a_thin_box_under_an_overhead_sun_is_single_scattering_in_closed_form() {
    let sigma = 1e-3;
    let cloud = homogeneous_box(sigma);
    let camera = VolumeCamera::looking_at(
        DVec3::new(-300.0, 40.0, 70.0),
        DVec3::new(50.0, 50.0, 50.0),
        30.0,
        21,
        17,
    )
    .unwrap();
    let overhead = sun(90.0, 0.0);
    let orders = orders();
    // One octave is A_1 exp(-tau): single scattering with the sun's attenuation.
    let octave = settings(LayerMethod::Octaves, 512);
    let truth = closed_form(&cloud, &camera, sigma, true);
    let march = march_image(&cloud, &camera, &overhead, &orders, &octave).unwrap();
    let slicing = slicing_image(&cloud, &camera, &overhead, &orders, &octave).unwrap();
    let (em, es) = (worst_error(&march, &truth), worst_error(&slicing, &truth));
    println!("one octave: march {em:.5}, slicing {es:.5} of the brightest pixel");
    assert!(em < 1e-3, "march: {em}");
    assert!(es < 0.01, "slicing: {es}");
    assert!(
        slicing.relative_error(&march) < 0.01,
        "{}",
        slicing.relative_error(&march)
    );
    // Riley's Eq. 25 keeps forward-scattered light: a thin cloud barely dims the sun.
    let riley = settings(LayerMethod::Riley, 512);
    let unattenuated = closed_form(&cloud, &camera, sigma, false);
    for image in [
        march_image(&cloud, &camera, &overhead, &orders, &riley).unwrap(),
        slicing_image(&cloud, &camera, &overhead, &orders, &riley).unwrap(),
    ] {
        let e = worst_error(&image, &unattenuated);
        println!("riley: {e:.5}");
        assert!(e < 0.01, "riley: {e}");
    }
    // The view's transmittance is the box's chord.
    let v = camera.direction(10.5, 8.5);
    let (t0, t1) = cloud.crossing(camera.position_m, v).unwrap();
    let t = (-sigma * (t1 - t0)).exp();
    let pixel = 8 * 21 + 10;
    assert!((march.transmittance[pixel] - t).abs() < 1e-6);
    assert!(
        (slicing.transmittance[pixel] - t).abs() < 2e-3,
        "{}",
        slicing.transmittance[pixel]
    );
}

/// In a box of optical depth about 0.01 the light scattered more than once is about a
/// hundredth of the rest: the path tracer, all orders, is the closed form's single
/// scattering within its standard error and that hundredth, pixel by pixel and in sum.
#[test]
fn the_path_tracer_in_a_thin_box_is_single_scattering_in_closed_form() {
    let sigma = 1e-4;
    let cloud = homogeneous_box(sigma);
    let camera = VolumeCamera::looking_at(
        DVec3::new(-300.0, 40.0, 70.0),
        DVec3::splat(50.0),
        10.0,
        5,
        4,
    )
    .unwrap();
    let truth = closed_form(&cloud, &camera, sigma, true);
    let traced = traced(&cloud, &camera, &sun(90.0, 0.0), &orders(), 40_000, 7, 0.0);
    let image = &traced.image;
    let (mut sum, mut sum_truth, mut variance) = (0.0, 0.0, 0.0);
    for (k, &l) in truth.iter().enumerate() {
        let (got, error) = (image.radiance[k], traced.standard_error[k]);
        println!("pixel {k}: {got:.4e} +- {error:.1e}, closed form {l:.4e}");
        assert!(l > 0.0, "every pixel sees the box");
        assert!((got - l).abs() <= 4.0 * error + 0.02 * l, "pixel {k}");
        let v = camera.direction((k % 5) as f64 + 0.5, (k / 5) as f64 + 0.5);
        let (t0, t1) = cloud.crossing(camera.position_m, v).unwrap();
        assert!((image.transmittance[k] - (-sigma * (t1 - t0)).exp()).abs() < 1e-9);
        (sum, sum_truth, variance) = (sum + got, sum_truth + l, variance + error * error);
    }
    println!(
        "sum {sum:.5e} +- {:.1e}, closed form {sum_truth:.5e}",
        variance.sqrt()
    );
    assert!((sum - sum_truth).abs() <= 3.0 * variance.sqrt() + 0.015 * sum_truth);
    assert!(variance.sqrt() < 0.02 * sum_truth, "the test's own noise");
}

/// In a thick ball (optical depth about 10 through its centre) two independent runs of
/// the path tracer differ by what their standard errors say, and four times the paths
/// halve the noise; a path count out of range is refused by name.
#[test]
fn the_path_tracers_standard_error_is_honest_and_shrinks_with_its_paths() {
    let cloud = ball(0.05);
    let light = sun(30.0, 40.0);
    let camera =
        VolumeCamera::looking_at(DVec3::new(-500.0, -300.0, 100.0), DVec3::ZERO, 30.0, 8, 6)
            .unwrap();
    let orders = orders();
    let run = |paths, seed| traced(&cloud, &camera, &light, &orders, paths, seed, 0.0);
    let (a, b, fine) = (run(64, 1), run(64, 2), run(256, 3));
    let difference = a.relative_rms_error(&b.image);
    println!(
        "noise {:.4} and {:.4}; a against b beyond a's noise {difference:.4}; 4x paths {:.4}",
        a.relative_noise(),
        b.relative_noise(),
        fine.relative_noise()
    );
    // What is left of the difference beyond a's noise is b's noise.
    assert!(difference < 1.5 * b.relative_noise(), "{difference}");
    assert!(difference > 0.5 * b.relative_noise(), "{difference}");
    let ratio = fine.relative_noise() / a.relative_noise();
    assert!((0.4..0.6).contains(&ratio), "{ratio}");
    for paths in [0, MAX_PATHS_PER_PIXEL + 1] {
        let tracing = PathTracing {
            paths,
            seed: 1,
            forward_peak_deg: 0.0,
        };
        let error = path_traced_image(&cloud, &camera, &light, &orders, &tracing, &|| {})
            .unwrap_err()
            .to_string();
        assert!(error.contains("paths per pixel"), "{error}");
    }
    for forward_peak_deg in [-1.0, 20.5, f64::NAN] {
        let tracing = PathTracing {
            paths: 1,
            seed: 1,
            forward_peak_deg,
        };
        let error = path_traced_image(&cloud, &camera, &light, &orders, &tracing, &|| {})
            .unwrap_err()
            .to_string();
        assert!(error.contains("forward peak"), "{error}");
    }
}

/// The octaves' slicing error against a fine march at 16 to 128 slices, the camera
/// facing away from the sun (front to back) and towards it (back to front).
#[test]
fn slicing_converges_to_the_march_as_the_slices_double() {
    let cloud = ball(0.02);
    let orders = orders();
    let light = sun(40.0, 20.0);
    for (name, position) in [
        ("facing away from the sun", DVec3::new(700.0, 300.0, 500.0)),
        ("facing the sun", DVec3::new(-700.0, -300.0, 200.0)),
    ] {
        let camera = VolumeCamera::looking_at(position, DVec3::ZERO, 25.0, 32, 32).unwrap();
        let slices = HalfAngle::new(&camera, light.direction, &cloud.corners(), 16).unwrap();
        assert_eq!(
            slices.front_to_back,
            name.starts_with("facing away"),
            "{name}"
        );
        let mut octaves = settings(LayerMethod::Octaves, 16);
        octaves.octaves = 4;
        octaves.light_buffer_px = 128;
        let march = march_image(&cloud, &camera, &light, &orders, &octaves).unwrap();
        let errors: Vec<f64> = [16, 32, 64, 128]
            .iter()
            .map(|&n| {
                let s = VolumeSettings {
                    slices: n,
                    ..octaves
                };
                slicing_image(&cloud, &camera, &light, &orders, &s)
                    .unwrap()
                    .relative_error(&march)
            })
            .collect();
        println!("{name}: mean error at 16, 32, 64, 128 slices {errors:.4?}");
        for pair in errors.windows(2) {
            assert!(pair[1] < 0.7 * pair[0], "{name}: {errors:?}");
        }
        assert!(errors[3] < 0.01, "{name}: {errors:?}");
    }
}

/// Every pixel of both methods, both lights, is finite, non-negative and at most
/// E albedo (max_n A_n(theta) + xi) (1 - T), the most a sum of opacities times sources
/// of at most that can reach; T lies in [0, 1].
#[test]
fn both_methods_stay_within_their_energy_bounds() {
    let cloud = ball(0.2);
    let orders = orders();
    let light = sun(25.0, 200.0);
    let camera =
        VolumeCamera::looking_at(DVec3::new(-500.0, -400.0, 150.0), DVec3::ZERO, 30.0, 24, 20)
            .unwrap();
    for light_method in [LayerMethod::Riley, LayerMethod::Octaves] {
        let s = VolumeSettings {
            backscatter_xi: 0.05,
            octaves: 4,
            ..settings(light_method, 96)
        };
        let images = [
            march_image(&cloud, &camera, &light, &orders, &s).unwrap(),
            slicing_image(&cloud, &camera, &light, &orders, &s).unwrap(),
        ];
        for image in &images {
            for (pixel, &t) in image.transmittance.iter().enumerate() {
                let (x, y) = (pixel % 24, pixel / 24);
                let v = camera.direction(x as f64 + 0.5, y as f64 + 0.5);
                let nu = v.dot(light.direction);
                let peak = (1..=26)
                    .map(|n| orders.distribution(0, n, nu))
                    .fold(0.0, f64::max);
                let bound = (peak + s.backscatter_xi) * (1.0 - t) * (1.0 + 1e-9);
                let l = image.radiance[pixel];
                assert!(
                    l.is_finite() && l >= 0.0 && l <= bound,
                    "{light_method}: pixel {pixel}: {l} > {bound}"
                );
                assert!((0.0..=1.0).contains(&t), "{t}");
            }
            assert!(largest(image) > 0.0);
        }
        println!(
            "{light_method}: slicing (96 slices) against the march {:.4}",
            images[1].relative_error(&images[0])
        );
    }
}

#[test]
fn the_half_vector_flips_when_the_view_turns_away_from_the_sun() {
    let sun = DVec3::new(0.0, 0.6, 0.8);
    let light = -sun;
    let across = DVec3::X;
    for epsilon in [1e-3, 0.3] {
        // Views just on either side of perpendicular to the light.
        let away = (across + light * epsilon).normalize();
        let towards = (across - light * epsilon).normalize();
        let (h_away, front_away) = half_vector(away, sun);
        let (h_towards, front_towards) = half_vector(towards, sun);
        assert!(front_away && !front_towards);
        assert!((h_away - (away + light).normalize()).length() < 1e-12);
        assert!((h_towards - (light - towards).normalize()).length() < 1e-12);
        // The view's component flips; the light crosses the slices in order either way.
        assert!(away.dot(h_away) > 0.0 && towards.dot(h_towards) < 0.0);
        for h in [h_away, h_towards] {
            assert!(light.dot(h) >= 0.5f64.sqrt() - 1e-12, "{h}");
        }
    }
    // Straight at the sun and straight away from it, h is the light itself.
    assert!((half_vector(-sun, sun).0 - light).length() < 1e-12);
    assert!((half_vector(sun, sun).0 - light).length() < 1e-12);
}
