//! What the GPU parity tests share: a renderer (or a skip without an adapter), frames on
//! the earth preset, and the comparison of a rendered frame with the CPU model of the
//! same id on the same pixel rays (`Frame::pixel_ray`), the sun disk added from
//! `atmosphere_core::optics::sun_disk`, the tone map against its CPU twin.
//!
//! Needs a GPU adapter (lavapipe will do). Without one the tests fail with the
//! `NoAdapter` message saying what to install, unless `ATMOS_SKIP_GPU_TESTS=1`, when
//! they record that they skipped (the app tests' `record_skip`, shared by path).
//!
//! Each test file that declares `mod support;` uses only part of it.
#![allow(dead_code)]

pub mod beams;
pub mod bruneton;
pub mod clouds;
pub mod golden;
#[path = "../../../crates/app/tests/common/skip.rs"]
mod skip;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel};
use atmosphere_core::optics::sea_surface::{SeaHit, radiance_with_sea, slope_variance};
use atmosphere_core::optics::sun_disk;
use atmosphere_core::optics::surface_lighting::{SurfaceHit, radiance_with_surface};
use atmosphere_core::optics::view_segment::{SegmentEnd, ViewSegment};
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::frame::surface_buffer::SurfaceTexel;
use render_wgpu::frame::{Frame, LocalView};
use render_wgpu::post::tone_map::ToneMap;
use render_wgpu::sky::table_sampling::TableSampling;
use render_wgpu::{GpuContext, GpuError, RenderError, Renderer};

/// The bruneton model's table-building steps, in the order its plan lists them.
pub const BRUNETON_TABLES: [&str; 6] = [
    "transmittance",
    "density",
    "sun_transmittance",
    "single_scattering",
    "scattering_orders",
    "scattering_texture",
];

/// Radiance below which errors count as absolute, W m^-2 sr^-1 nm^-1: 1e-3 of a bright
/// daytime sky (about 0.1), far below what an 8-bit display shows.
pub const FLOOR: f64 = 1e-4;

/// Pixels whose ray the CPU sees ending on the ground while a ray 2e-6 rad away ends in
/// space (or the reverse) lie on the planet's limb, where f32 and f64 may decide
/// differently; they are left out (and counted).
const LIMB_ANGLE_RAD: f64 = 2e-6;

/// Whether `test` skips for `error`: there is no adapter and `ATMOS_SKIP_GPU_TESTS=1`
/// (then the skip is recorded).
fn skips_for(test: &str, error: &GpuError) -> bool {
    let skip = matches!(error, GpuError::NoAdapter { .. })
        && std::env::var("ATMOS_SKIP_GPU_TESTS").as_deref() == Ok("1");
    if skip {
        skip::record_skip(&format!("{test}: ATMOS_SKIP_GPU_TESTS=1 and {error}"));
    }
    skip
}

/// The GPU context, or `None` after recording why when there is no adapter and
/// `ATMOS_SKIP_GPU_TESTS=1`.
pub fn gpu_or_skip(test: &str) -> Option<GpuContext> {
    match GpuContext::headless() {
        Ok(gpu) => Some(gpu),
        Err(e) if skips_for(test, &e) => None,
        Err(e) => panic!("{e}"),
    }
}

/// The renderer, or `None` as [`gpu_or_skip`].
pub fn renderer_or_skip(test: &str) -> Option<Renderer> {
    match Renderer::headless() {
        Ok(r) => Some(r),
        Err(RenderError::Gpu(e)) if skips_for(test, &e) => None,
        Err(e) => panic!("{e}"),
    }
}

/// A renderer whose device lacks `FLOAT32_FILTERABLE` even where the adapter has it, so
/// that the passes read their tables texel by texel (`render_wgpu::sky::table_sampling`), or
/// `None` as [`gpu_or_skip`].
pub fn texel_read_renderer_or_skip(test: &str) -> Option<Renderer> {
    match GpuContext::headless_without(wgpu::Features::FLOAT32_FILTERABLE) {
        Ok(gpu) => {
            assert!(!TableSampling::device_filters(&gpu));
            Some(Renderer::new(gpu).unwrap())
        }
        Err(e) if skips_for(test, &e) => None,
        Err(e) => panic!("{e}"),
    }
}

/// Largest relative difference of a pixel read through the filter from the same pixel
/// read texel by texel: the same interpolation up to the filter's f32 weights, and the
/// f16 store (4.9e-4 per rounding).
pub const MAX_FILTER_DIFFERENCE: f32 = 1e-3;

/// The texel-by-texel table reads, which a device without `FLOAT32_FILTERABLE` runs:
/// `frames` (and `surface`'s frame over [`synthetic_surface`]) rendered that way against
/// the CPU within `max_relative_error`, and `frames` against the default renderer's
/// (filtered where its device filters Rgba32Float, as lavapipe does) within
/// [`MAX_FILTER_DIFFERENCE`] per pixel and channel.
pub fn check_texel_reads(
    test: &str,
    frames: &[(&str, Frame)],
    surface: Option<(&str, &Frame)>,
    max_relative_error: f64,
) {
    let Some(mut texel_reads) = texel_read_renderer_or_skip(test) else {
        return;
    };
    let Some(mut default) = renderer_or_skip(test) else {
        return;
    };
    let filtered = TableSampling::device_filters(default.gpu());
    for (name, frame) in frames {
        let label = format!("{name}, texel reads");
        check(&mut texel_reads, &label, frame, max_relative_error);
        texel_reads.render(frame).unwrap();
        default.render(frame).unwrap();
        let (a, b) = (texel_reads.read_hdr().unwrap(), default.read_hdr().unwrap());
        let worst = a
            .iter()
            .zip(&b)
            .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs() / a[c].abs().max(1e-3)))
            .fold(0.0f32, f32::max);
        println!(
            "{test}, {name}: filtered reads ({filtered}) against texel reads: worst relative \
             difference {worst:.2e}"
        );
        assert!(worst <= MAX_FILTER_DIFFERENCE, "{name}: {worst:e}");
    }
    if let Some((name, frame)) = surface {
        let label = format!("{name}, texel reads");
        check_surface(&mut texel_reads, &label, frame, max_relative_error);
    }
}

/// A frame of `model` on the earth preset, default settings, exposure EV100 14.
pub fn frame(model: ModelId, view: LocalView, fov_deg: f64, width: u32, height: u32) -> Frame {
    let earth = Atmosphere::preset("earth").unwrap();
    frame_in(earth, model, view, fov_deg, width, height)
}

/// A frame of `model` in `atmosphere`, default settings, exposure EV100 14.
pub fn frame_in(
    atmosphere: Atmosphere,
    model: ModelId,
    view: LocalView,
    fov_deg: f64,
    width: u32,
    height: u32,
) -> Frame {
    Frame {
        camera_position_m: view.position_m(atmosphere.bottom_radius_m),
        orientation: view.orientation(),
        vertical_fov_deg: fov_deg,
        sun_direction: view.sun_direction(),
        atmosphere,
        model,
        settings: ModelSettings::default(),
        exposure_ev100: 14.0,
        width,
        height,
        terrain: None,
    }
}

/// The standard frames' ground frame of `model` in `atmosphere`: 1 m above the ground
/// at the horizon in the afternoon.
pub fn ground_frame_in(atmosphere: Atmosphere, model: ModelId) -> Frame {
    frame_in(atmosphere, model, view(1.0, 85.0, 50.0), 70.0, 64, 36)
}

/// The ground frame of `model` in the hazy and the Mars presets.
pub fn other_atmosphere_frames(model: ModelId) -> Vec<(&'static str, Frame)> {
    ["hazy", "mars"]
        .into_iter()
        .map(|name| {
            (
                name,
                ground_frame_in(Atmosphere::preset(name).unwrap(), model),
            )
        })
        .collect()
}

/// A view at `altitude_m`, looking `view_zenith_deg` from the zenith at azimuth 0, the
/// sun `sun_zenith_deg` from the zenith at azimuth 30 deg.
pub fn view(altitude_m: f64, view_zenith_deg: f64, sun_zenith_deg: f64) -> LocalView {
    LocalView {
        altitude_m,
        view_zenith_deg,
        view_azimuth_deg: 0.0,
        sun_zenith_deg,
        sun_azimuth_deg: 30.0,
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

/// The CPU's radiance of a pixel: the model, ending on the pixel's surface where it has
/// one (`radiance_with_surface`), plus the transmitted sun disk where the ray reaches
/// space.
pub fn cpu_pixel(
    model: &dyn SkyModel,
    frame: &Frame,
    column: u32,
    row: u32,
    surface: Option<&SurfaceTexel>,
) -> [f64; 3] {
    let ray = frame.pixel_ray(column, row);
    if let Some(texel) = surface.filter(|t| t.distance_m > 0.0 && t.water) {
        let wind = frame.terrain.unwrap_or_default().wind_m_s;
        let hit = SeaHit {
            distance_m: f64::from(texel.distance_m),
            normal: glam::Vec3::from_array(texel.normal).as_dvec3(),
            body_albedo: texel.stored_albedo().map(f64::from).to_vec(),
            slope_variance: slope_variance(wind),
        };
        let answer = radiance_with_sea(model, &frame.atmosphere, &ray, &hit).unwrap();
        return std::array::from_fn(|w| answer.radiance[w]);
    }
    if let Some(texel) = surface.filter(|t| t.distance_m > 0.0) {
        let hit = SurfaceHit {
            distance_m: f64::from(texel.distance_m),
            normal: glam::Vec3::from_array(texel.normal).as_dvec3(),
            albedo: texel.stored_albedo().map(f64::from).to_vec(),
        };
        let answer = radiance_with_surface(model, &frame.atmosphere, &ray, &hit).unwrap();
        return std::array::from_fn(|w| answer.radiance[w]);
    }
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

/// Renders `frame` with its model, compares every pixel off the limb with the CPU model
/// of the same id (|L_gpu - L_cpu| / max(L_cpu, FLOOR) per channel, every value finite)
/// and the tone map with its twin (within one 8-bit level); prints the worst error and
/// fails above `max_relative_error`. Returns the worst relative error.
pub fn check(renderer: &mut Renderer, name: &str, frame: &Frame, max_relative_error: f64) -> f64 {
    check_over(renderer, name, frame, None, max_relative_error)
}

/// [`check`] of each of `frames`.
pub fn check_each(renderer: &mut Renderer, frames: &[(&str, Frame)], max_relative_error: f64) {
    for (name, frame) in frames {
        check(renderer, name, frame, max_relative_error);
    }
}

/// [`check_each`] of `model`'s [`standard_frames`].
pub fn check_standard_frames(renderer: &mut Renderer, model: ModelId, max_relative_error: f64) {
    check_each(renderer, &standard_frames(model), max_relative_error);
}

/// [`check_each`] of `model`'s [`other_atmosphere_frames`].
pub fn check_other_atmospheres(renderer: &mut Renderer, model: ModelId, max_relative_error: f64) {
    check_each(
        renderer,
        &other_atmosphere_frames(model),
        max_relative_error,
    );
}

/// The first four of `model`'s [`standard_frames`] over [`synthetic_surface`] against the
/// CPU ([`check_surface`]), on a renderer of its own.
pub fn check_standard_surfaces(test: &str, model: ModelId, max_relative_error: f64) {
    let Some(mut renderer) = renderer_or_skip(test) else {
        return;
    };
    for (name, frame) in standard_frames(model).iter().take(4) {
        check_surface(&mut renderer, name, frame, max_relative_error);
    }
}

/// `model`'s sun-disk frame (the last of [`standard_frames`]) against the CPU, and the
/// disk limb-darkened: its centre brighter than a pixel near its edge.
pub fn check_sun_disk(test: &str, model: ModelId, max_relative_error: f64) {
    let Some(mut renderer) = renderer_or_skip(test) else {
        return;
    };
    let (name, frame) = &standard_frames(model)[4];
    check(&mut renderer, name, frame, max_relative_error);
    let hdr = renderer.read_hdr().unwrap();
    let middle = (frame.height / 2 * frame.width + frame.width / 2) as usize;
    let (centre, near_limb) = (hdr[middle][1], hdr[middle + 4][1]);
    assert!(centre > 1e4 && near_limb < centre, "{centre} {near_limb}");
}

/// As [`check`], the frame's rays ending on `surface` (the sea's pixels by
/// `radiance_with_sea` on the CPU).
pub fn check_given_surface(
    renderer: &mut Renderer,
    name: &str,
    frame: &Frame,
    surface: &[SurfaceTexel],
    max_relative_error: f64,
) -> f64 {
    check_over(renderer, name, frame, Some(surface), max_relative_error)
}

/// As [`check`], the frame's rays ending on [`synthetic_surface`].
pub fn check_surface(
    renderer: &mut Renderer,
    name: &str,
    frame: &Frame,
    max_relative_error: f64,
) -> f64 {
    let surface = synthetic_surface(frame);
    check_over(renderer, name, frame, Some(&surface), max_relative_error)
}

fn check_over(
    renderer: &mut Renderer,
    name: &str,
    frame: &Frame,
    surface: Option<&[SurfaceTexel]>,
    max_relative_error: f64,
) -> f64 {
    let plan = match surface {
        Some(texels) => renderer.render_with_surface(frame, texels).unwrap(),
        None => renderer.render(frame).unwrap(),
    };
    let hdr = renderer.read_hdr().unwrap();
    let ldr = renderer.read_ldr().unwrap();
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    let tone_map = ToneMap::new(RGB_WAVELENGTHS_NM, frame.exposure_ev100).unwrap();
    let (mut worst, mut at, mut limb, mut lit) = (0.0f64, (0, 0, 0), 0, 0);
    let mut values = (0.0, 0.0);
    let mut worst_ldr = 0i32;
    for row in 0..frame.height {
        for column in 0..frame.width {
            let index = (row * frame.width + column) as usize;
            let gpu = hdr[index];
            assert_eq!(gpu[3], 1.0);
            assert!(
                gpu.iter().all(|v| v.is_finite()),
                "{name}: pixel ({column}, {row}) is {gpu:?}"
            );
            let expected = tone_map.pixel(std::array::from_fn(|c| f64::from(gpu[c])));
            for c in 0..3 {
                worst_ldr =
                    worst_ldr.max((i32::from(ldr[index][c]) - i32::from(expected[c])).abs());
            }
            if on_limb(frame, column, row) {
                limb += 1;
                continue;
            }
            let texel = surface.map(|t| &t[index]);
            let cpu = cpu_pixel(model.as_ref(), frame, column, row, texel);
            if cpu[1] > FLOOR {
                lit += 1;
            }
            for c in 0..3 {
                let error = (f64::from(gpu[c]) - cpu[c]).abs() / cpu[c].max(FLOOR);
                if error > worst || error.is_nan() {
                    worst = error;
                    at = (column, row, c);
                    values = (f64::from(gpu[c]), cpu[c]);
                }
            }
        }
    }
    println!(
        "{} {name} on {}: worst relative error {worst:.2e} at pixel ({}, {}) channel {} \
         (GPU {:.5e}, CPU {:.5e}); \
         {lit} lit pixels, {limb} on the limb left out; tone map within {worst_ldr} of the CPU; plan: {plan}",
        frame.model,
        renderer.gpu().adapter_summary(),
        at.0,
        at.1,
        at.2,
        values.0,
        values.1,
    );
    assert!(
        worst <= max_relative_error,
        "{} {name}: worst relative error {worst:e}",
        frame.model
    );
    assert!(worst_ldr <= 1, "{name}: tone map off by {worst_ldr} levels");
    worst
}

/// The five frames every model's parity test renders: 1 m above the ground at the
/// horizon in the afternoon, sunset from 2 km towards the sun, the limb from 100 km,
/// the whole planet from 1e8 m with the terminator in view (64 x 36), and a 33 x 19
/// frame of 1 deg on a sun 60 deg from the zenith, whose disk spans about 10 pixels.
pub fn standard_frames(model: ModelId) -> Vec<(&'static str, Frame)> {
    let mut sunset = view(2_000.0, 88.0, 89.0);
    sunset.sun_azimuth_deg = 5.0;
    let sun = LocalView {
        altitude_m: 500.0,
        view_zenith_deg: 60.0,
        view_azimuth_deg: 0.0,
        sun_zenith_deg: 60.0,
        sun_azimuth_deg: 0.0,
    };
    vec![
        (
            "ground",
            ground_frame_in(Atmosphere::preset("earth").unwrap(), model),
        ),
        ("sunset", frame(model, sunset, 60.0, 64, 36)),
        (
            "100 km",
            frame(model, view(100_000.0, 100.0, 60.0), 40.0, 64, 36),
        ),
        ("1e8 m", frame(model, view(1e8, 180.0, 80.0), 9.0, 64, 36)),
        ("sun disk", frame(model, sun, 1.0, 33, 19)),
    ]
}

/// A surface over every other pixel of `frame`, made to reach each way a ray can end on
/// one: at 30 % and 70 % of the pixel's segment through the atmosphere, beyond its end
/// (on the ground it ends there; towards space, beyond the top), before the atmosphere
/// for a camera in space, and in space for rays that miss it. Normals lean up to 60 deg
/// from the local vertical, towards and away from the sun; albedos vary per pixel.
pub fn synthetic_surface(frame: &Frame) -> Vec<SurfaceTexel> {
    let mut texels = Vec::with_capacity((frame.width * frame.height) as usize);
    for row in 0..frame.height {
        for column in 0..frame.width {
            let k = row * 7 + column * 3;
            if (row + column) % 2 == 0 {
                texels.push(SurfaceTexel::default());
                continue;
            }
            let ray = frame.pixel_ray(column, row);
            let segment = ViewSegment::new(&frame.atmosphere, &ray).unwrap();
            let distance = match segment {
                Some(s) => match k % 4 {
                    0 => s.t_enter + 0.3 * s.length,
                    1 => s.t_enter + 0.7 * s.length,
                    2 => s.t_enter + 1.2 * s.length + 10.0,
                    _ if s.t_enter > 0.0 => 0.9 * s.t_enter,
                    _ => s.t_enter + 0.5 * s.length,
                },
                None => 0.5 * ray.origin_m.length(),
            };
            let point = ray.origin_m + ray.direction * distance;
            let up = point.normalize();
            let lean = (f64::from(k % 5) - 2.0) * 0.5;
            let normal = (up
                + ray.sun_direction.cross(up).normalize_or_zero() * lean
                + ray.sun_direction * 0.3 * (f64::from(k % 3) - 1.0))
                .normalize();
            texels.push(SurfaceTexel {
                normal: normal.as_vec3().to_array(),
                distance_m: distance as f32,
                albedo: [
                    0.1 + 0.8 * column as f32 / frame.width as f32,
                    0.1 + 0.8 * row as f32 / frame.height as f32,
                    0.05 * (k % 7) as f32,
                ],
                water: false,
            });
        }
    }
    texels
}

/// A wall facing the camera `distance_m` away over the frame's first `columns` columns,
/// of a rock's albedo; no surface elsewhere.
pub fn wall(frame: &Frame, columns: u32, distance_m: f32) -> Vec<SurfaceTexel> {
    let mut texels = Vec::new();
    for row in 0..frame.height {
        for column in 0..frame.width {
            texels.push(if column < columns {
                let d = frame.pixel_ray(column, row).direction;
                SurfaceTexel {
                    normal: (-d).as_vec3().to_array(),
                    distance_m,
                    albedo: [0.3, 0.25, 0.2],
                    water: false,
                }
            } else {
                SurfaceTexel::default()
            });
        }
    }
    texels
}
