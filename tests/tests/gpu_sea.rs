//! The sea on the GPU (`shaders/common/sea_surface.wgsl` in every model's pixel pass)
//! against its CPU twin (`optics::sea_surface::radiance_with_sea`) on a flat sea, the
//! ground sphere given as the frame's surface and marked as water: the sky's reflection
//! is each model's own sky along the mirror direction (the CPU asks the same model's
//! `radiance` for it), and the glint's brightest pixel is where the CPU puts it, in the
//! sun's specular direction.
//!
//! Needs a GPU adapter (lavapipe will do); see `support/mod.rs`.

mod support;

use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::optics::sea_surface::{SeaHit, radiance_with_sea, slope_variance};
use glam::DVec3;
use render_wgpu::Frame;
use render_wgpu::frame::TerrainOptions;
use render_wgpu::frame::surface_buffer::SurfaceTexel;
use support::{check_given_surface, frame, renderer_or_skip, view};

/// The water body's albedo: the Blue Marble's open sea, about.
const BODY: [f32; 3] = [0.012, 0.025, 0.06];

/// Each model with the bound on its pixels' relative error against the CPU (its parity
/// bound, but hillaire's, whose GPU marches the mirror ray where its CPU reads a sky
/// view tabulated at the sea point: the two agree to the table's error, 2.3e-3 here)
/// and the image's size in pixels (hillaire's CPU builds a sky view for each sea point,
/// so its frame is small).
const MODELS: [(ModelId, f64, (u32, u32)); 6] = [
    (ModelId::Nishita, 2e-3, (64, 36)),
    (ModelId::Oneil, 2e-3, (64, 36)),
    (ModelId::Riley, 3e-3, (64, 36)),
    (ModelId::Dobashi, 2e-3, (64, 36)),
    (ModelId::Bruneton, 5e-3, (64, 36)),
    (ModelId::Hillaire, 5e-3, (16, 9)),
];

/// The ground sphere under `frame`'s camera as the sea, in every pixel whose ray meets
/// it: the distance to it, the sphere's normal.
fn flat_sea(frame: &Frame) -> Vec<SurfaceTexel> {
    let bottom = frame.atmosphere.bottom_radius_m;
    let mut texels = Vec::new();
    for row in 0..frame.height {
        for column in 0..frame.width {
            let ray = frame.pixel_ray(column, row);
            let (o, d) = (ray.origin_m, ray.direction);
            let b = o.dot(d);
            let c = (o.length() - bottom) * (o.length() + bottom);
            let disc = b * b - c;
            if b >= 0.0 || disc < 0.0 {
                texels.push(SurfaceTexel::default());
                continue;
            }
            let t = c / (-b + disc.sqrt());
            let normal = (o + d * t).normalize();
            texels.push(SurfaceTexel {
                normal: normal.as_vec3().to_array(),
                distance_m: t as f32,
                albedo: BODY,
                water: true,
            });
        }
    }
    texels
}

/// A frame of `model` 30 m above the sea, `size` pixels, looking `view_zenith_deg` from
/// the zenith, the sun `sun_zenith_deg` from the zenith at `sun_azimuth_deg` from the
/// view, the wind `wind_m_s`.
fn sea_frame(
    model: ModelId,
    size: (u32, u32),
    view_zenith_deg: f64,
    (sun_zenith_deg, sun_azimuth_deg): (f64, f64),
    wind_m_s: f64,
) -> Frame {
    let mut v = view(30.0, view_zenith_deg, sun_zenith_deg);
    v.sun_azimuth_deg = sun_azimuth_deg;
    let mut f = frame(model, v, 30.0, size.0, size.1);
    f.terrain = Some(TerrainOptions {
        wind_m_s,
        ..TerrainOptions::default()
    });
    f
}

#[test]
fn each_model_s_sea_reflects_its_sky_and_the_sun_as_the_cpu_does() {
    let Some(mut renderer) = renderer_or_skip("sea parity") else {
        return;
    };
    for (model, bound, size) in MODELS {
        // Looking 3 deg down, the sun behind the camera: the sky's reflection and the
        // body; then ahead and low over a windy sea: the glint.
        for (name, f) in [
            ("sky", sea_frame(model, size, 93.0, (60.0, 160.0), 0.0)),
            ("glint", sea_frame(model, size, 93.0, (80.0, 10.0), 8.0)),
        ] {
            let surface = flat_sea(&f);
            let sea = surface.iter().filter(|t| t.water).count();
            assert!(sea > surface.len() / 4, "{name}: {sea} sea pixels");
            check_given_surface(&mut renderer, name, &f, &surface, bound);
        }
    }
}

#[test]
fn the_glint_s_brightest_pixel_lies_in_the_sun_s_specular_direction() {
    let Some(mut renderer) = renderer_or_skip("sea glint") else {
        return;
    };
    // A calm sea seen 35 deg down, the sun 45 deg up, 3 deg right of ahead: its mirror
    // image 45 deg down (a lower sun's glitter runs to the horizon).
    let f = sea_frame(ModelId::Nishita, (64, 36), 125.0, (45.0, 3.0), 0.0);
    let surface = flat_sea(&f);
    renderer.render_with_surface(&f, &surface).unwrap();
    let hdr = renderer.read_hdr().unwrap();
    let model = prepare(f.model, &f.atmosphere, &f.settings).unwrap();
    let brightest = |value: &dyn Fn(usize, u32, u32) -> f64| {
        let mut best = (f64::MIN, (0, 0));
        for row in 0..f.height {
            for column in 0..f.width {
                let index = (row * f.width + column) as usize;
                if surface[index].water {
                    let v = value(index, column, row);
                    if v > best.0 {
                        best = (v, (column, row));
                    }
                }
            }
        }
        best.1
    };
    let gpu = brightest(&|index, _, _| f64::from(hdr[index][1]));
    let cpu = brightest(&|index, column, row| {
        let texel = &surface[index];
        let hit = SeaHit {
            distance_m: f64::from(texel.distance_m),
            normal: glam::Vec3::from_array(texel.normal).as_dvec3(),
            body_albedo: texel.stored_albedo().map(f64::from).to_vec(),
            slope_variance: slope_variance(0.0),
        };
        let ray = f.pixel_ray(column, row);
        radiance_with_sea(model.as_ref(), &f.atmosphere, &ray, &hit)
            .unwrap()
            .radiance[1]
    });
    // The pixel whose ray, mirrored in the sea, comes nearest the sun.
    let specular = brightest(&|index, column, row| {
        let d = f.pixel_ray(column, row).direction;
        let n = glam::Vec3::from_array(surface[index].normal).as_dvec3();
        let mirror: DVec3 = d - 2.0 * d.dot(n) * n;
        mirror.dot(f.sun_direction.normalize())
    });
    println!("glint: brightest pixel GPU {gpu:?}, CPU {cpu:?}, specular {specular:?}");
    // Pixels of 0.8 deg across a glint some 6 deg wide: neighbours near its peak differ
    // by a few per cent, so the two agree to a pixel.
    let off = |a: (u32, u32), b: (u32, u32)| a.0.abs_diff(b.0).max(a.1.abs_diff(b.1));
    assert!(off(gpu, cpu) <= 1, "{gpu:?} against the CPU's {cpu:?}");
    assert!(off(gpu, specular) <= 1, "{gpu:?} against {specular:?}");
    // The glint outshines the sky's reflection a few pixels away by far.
    let at = |(c, r): (u32, u32)| hdr[(r * f.width + c) as usize][1];
    let aside = (gpu.0 + 12, gpu.1);
    assert!(
        at(gpu) > 20.0 * at(aside),
        "{} against {}",
        at(gpu),
        at(aside)
    );
}

#[test]
fn a_frame_without_sea_skips_the_sea_and_its_land_is_the_same() {
    let Some(mut renderer) = renderer_or_skip("sea skipped") else {
        return;
    };
    // The same flat surface as land, then with one pixel of sea: the second frame runs
    // the passes' sea variant, the first their variant without it; every other pixel is
    // the same bit for bit.
    let f = sea_frame(ModelId::Nishita, (32, 18), 93.0, (60.0, 160.0), 5.0);
    let mut land = flat_sea(&f);
    for t in &mut land {
        t.water = false;
    }
    renderer.render_with_surface(&f, &land).unwrap();
    let without = renderer.read_hdr().unwrap();
    let sea_pixel = (f.width * (f.height - 2) + 5) as usize;
    let mut one_sea = land.clone();
    one_sea[sea_pixel].water = true;
    renderer.render_with_surface(&f, &one_sea).unwrap();
    let with = renderer.read_hdr().unwrap();
    for (i, (a, b)) in without.iter().zip(&with).enumerate() {
        if i != sea_pixel {
            assert_eq!(a, b, "pixel {i}");
        }
    }
    assert_ne!(without[sea_pixel], with[sea_pixel]);
}
