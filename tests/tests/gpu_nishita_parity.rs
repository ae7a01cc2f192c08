//! The GPU nishita frame (`shaders/nishita.wgsl` through the `Renderer`) against the CPU
//! model (`atmosphere_core::model::prepare("nishita", ..)`) on the same pixel rays, the
//! sun disk against `atmosphere_core::sun_disk`, and the tone map against its CPU twin
//! (`render_wgpu::tone_map`).
//!
//! Needs a GPU adapter (lavapipe will do). Without one the tests fail with the
//! `NoAdapter` message saying what to install, unless `ATMOS_SKIP_GPU_TESTS=1`, when
//! they print that they skipped.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::model::{ModelSettings, SkyModel, prepare};
use atmosphere_core::sun_disk;
use atmosphere_core::view_segment::{SegmentEnd, ViewSegment};
use render_wgpu::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::frame::{Frame, LocalView};
use render_wgpu::tone_map::ToneMap;
use render_wgpu::{GpuError, RenderError, Renderer};

/// Largest allowed |L_gpu - L_cpu| / max(L_cpu, FLOOR) per pixel and channel. The HDR
/// target stores f16 (relative rounding 4.9e-4); the rest is f32 arithmetic along 100
/// samples and the f32 table. Measured on lavapipe: see the test output.
const MAX_RELATIVE_ERROR: f64 = 2e-3;

/// Radiance below which errors count as absolute, W m^-2 sr^-1 nm^-1: 1e-3 of a bright
/// daytime sky (about 0.1), far below what an 8-bit display shows.
const FLOOR: f64 = 1e-4;

/// Pixels whose ray the CPU sees ending on the ground while a ray 2e-6 rad away ends in
/// space (or the reverse) lie on the planet's limb, where f32 and f64 may decide
/// differently; they are left out (and counted).
const LIMB_ANGLE_RAD: f64 = 2e-6;

/// The renderer, or `None` after printing why when there is no adapter and
/// `ATMOS_SKIP_GPU_TESTS=1`.
fn renderer_or_skip(test: &str) -> Option<Renderer> {
    match Renderer::headless() {
        Ok(r) => Some(r),
        Err(RenderError::Gpu(e @ GpuError::NoAdapter { .. }))
            if std::env::var("ATMOS_SKIP_GPU_TESTS").as_deref() == Ok("1") =>
        {
            println!("{test}: SKIPPED (ATMOS_SKIP_GPU_TESTS=1): {e}");
            None
        }
        Err(e) => panic!("{e}"),
    }
}

fn frame(view: LocalView, fov_deg: f64, width: u32, height: u32) -> Frame {
    let atmosphere = Atmosphere::preset("earth").unwrap();
    Frame {
        camera_position_m: view.position_m(atmosphere.bottom_radius_m),
        orientation: view.orientation(),
        vertical_fov_deg: fov_deg,
        sun_direction: view.sun_direction(),
        atmosphere,
        model: "nishita".into(),
        settings: ModelSettings::default(),
        exposure_ev100: 14.0,
        width,
        height,
    }
}

/// Whether the CPU's segment end changes within `LIMB_ANGLE_RAD` of the pixel's ray.
fn on_limb(frame: &Frame, column: u32, row: u32) -> bool {
    let ray = frame.pixel_ray(column, row);
    let end = |direction| {
        let mut r = ray;
        r.direction = direction;
        ViewSegment::new(&frame.atmosphere, &r)
            .unwrap()
            .map(|s| s.end == SegmentEnd::Ground)
    };
    let [right, up, _] = frame.axes();
    let here = end(ray.direction);
    [right, -right, up, -up]
        .iter()
        .any(|&d| end((ray.direction + d * LIMB_ANGLE_RAD).normalize()) != here)
}

/// The CPU's radiance of a pixel: the model plus the transmitted sun disk where the ray
/// reaches space.
fn cpu_pixel(model: &dyn SkyModel, frame: &Frame, column: u32, row: u32) -> [f64; 3] {
    let ray = frame.pixel_ray(column, row);
    let answer = model.radiance(&ray).unwrap();
    let to_space = ViewSegment::new(&frame.atmosphere, &ray)
        .unwrap()
        .is_none_or(|s| s.end != SegmentEnd::Ground);
    let angle = ray
        .direction
        .cross(ray.sun_direction)
        .length()
        .atan2(ray.direction.dot(ray.sun_direction));
    std::array::from_fn(|w| {
        let disk = if to_space {
            answer.transmittance[w]
                * sun_disk::radiance(
                    model.solar_irradiance_w_m2_nm()[w],
                    frame.atmosphere.sun.angular_radius_rad,
                    RGB_WAVELENGTHS_NM[w],
                    angle,
                )
        } else {
            0.0
        };
        answer.radiance[w] + disk
    })
}

/// Renders `frame`, compares every pixel with the CPU and the tone map with its twin;
/// returns the worst relative error.
fn check(renderer: &mut Renderer, name: &str, frame: &Frame) -> f64 {
    let plan = renderer.render(frame).unwrap();
    let hdr = renderer.read_hdr().unwrap();
    let ldr = renderer.read_ldr().unwrap();
    let model = prepare("nishita", &frame.atmosphere, &frame.settings).unwrap();
    let tone_map = ToneMap::new(RGB_WAVELENGTHS_NM, frame.exposure_ev100).unwrap();
    let (mut worst, mut at, mut limb, mut lit) = (0.0f64, (0, 0, 0), 0, 0);
    let mut worst_ldr = 0i32;
    for row in 0..frame.height {
        for column in 0..frame.width {
            let index = (row * frame.width + column) as usize;
            let gpu = hdr[index];
            assert_eq!(gpu[3], 1.0);
            let expected = tone_map.pixel(std::array::from_fn(|c| f64::from(gpu[c])));
            for c in 0..3 {
                worst_ldr =
                    worst_ldr.max((i32::from(ldr[index][c]) - i32::from(expected[c])).abs());
            }
            if on_limb(frame, column, row) {
                limb += 1;
                continue;
            }
            let cpu = cpu_pixel(model.as_ref(), frame, column, row);
            if cpu[1] > FLOOR {
                lit += 1;
            }
            for c in 0..3 {
                let error = (f64::from(gpu[c]) - cpu[c]).abs() / cpu[c].max(FLOOR);
                if error > worst || error.is_nan() {
                    worst = error;
                    at = (column, row, c);
                }
            }
        }
    }
    println!(
        "{name} on {}: worst relative error {worst:.2e} at pixel ({}, {}) channel {}; \
         {lit} lit pixels, {limb} on the limb left out; tone map within {worst_ldr} of the CPU; plan: {plan}",
        renderer.gpu().adapter_summary(),
        at.0,
        at.1,
        at.2,
    );
    assert!(
        worst <= MAX_RELATIVE_ERROR,
        "{name}: worst relative error {worst:e}"
    );
    assert!(worst_ldr <= 1, "{name}: tone map off by {worst_ldr} levels");
    worst
}

#[test]
fn nishita_frames_match_the_cpu_from_the_ground_to_far_orbit() {
    let Some(mut renderer) = renderer_or_skip("nishita parity") else {
        return;
    };
    let view = |altitude_m, view_zenith_deg, sun_zenith_deg| LocalView {
        altitude_m,
        view_zenith_deg,
        view_azimuth_deg: 0.0,
        sun_zenith_deg,
        sun_azimuth_deg: 30.0,
    };
    // 1 m above the ground looking at the horizon, afternoon sun.
    check(
        &mut renderer,
        "ground",
        &frame(view(1.0, 85.0, 50.0), 70.0, 64, 36),
    );
    // Sunset from 2 km, looking towards the sun.
    let mut sunset = view(2_000.0, 88.0, 89.0);
    sunset.sun_azimuth_deg = 5.0;
    check(&mut renderer, "sunset", &frame(sunset, 60.0, 64, 36));
    // The limb from 100 km.
    check(
        &mut renderer,
        "100 km",
        &frame(view(100_000.0, 100.0, 60.0), 40.0, 64, 36),
    );
    // The whole planet from 1e8 m, the terminator in view.
    check(
        &mut renderer,
        "1e8 m",
        &frame(view(1e8, 180.0, 80.0), 9.0, 64, 36),
    );
}

#[test]
fn the_sun_disk_is_limb_darkened_as_on_the_cpu() {
    let Some(mut renderer) = renderer_or_skip("sun disk") else {
        return;
    };
    // Looking at a sun 60 deg from the zenith with 1 deg of field: the disk spans about
    // 10 pixels.
    let view = LocalView {
        altitude_m: 500.0,
        view_zenith_deg: 60.0,
        view_azimuth_deg: 0.0,
        sun_zenith_deg: 60.0,
        sun_azimuth_deg: 0.0,
    };
    let f = frame(view, 1.0, 33, 19);
    check(&mut renderer, "sun disk", &f);
    let hdr = renderer.read_hdr().unwrap();
    let centre = hdr[(9 * 33 + 16) as usize][1];
    let near_limb = hdr[(9 * 33 + 20) as usize][1];
    assert!(centre > 1e4 && near_limb < centre, "{centre} {near_limb}");
}

#[test]
fn unchanged_tables_are_not_rebuilt_and_other_models_are_refused() {
    let Some(mut renderer) = renderer_or_skip("plan") else {
        return;
    };
    let view = LocalView {
        altitude_m: 10.0,
        view_zenith_deg: 80.0,
        view_azimuth_deg: 0.0,
        sun_zenith_deg: 40.0,
        sun_azimuth_deg: 0.0,
    };
    let mut f = frame(view, 60.0, 16, 9);
    assert!(renderer.render(&f).unwrap().runs("g_l"));
    f.exposure_ev100 = 12.0;
    assert!(!renderer.render(&f).unwrap().runs("g_l"));
    f.atmosphere = f.atmosphere.with_aerosol_scale(2.0);
    assert!(renderer.render(&f).unwrap().runs("g_l"));
    f.model = "reference".into();
    let err = renderer.render(&f).unwrap_err();
    assert!(err.to_string().contains("not yet on the GPU"), "{err}");
}
