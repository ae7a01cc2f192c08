//! The cloud spheres in `Renderer` frames (`clouds/spheres/frame_spheres.rs`,
//! `shaders/clouds/spheres/frame_image.wgsl`, the layer's composite): a frame from orbit
//! against its CPU twin (`spheres_only` through `layer/composite.rs`'s `composite` with
//! riley's answers for the whole ray and the ray ended where it enters the cloud); a
//! surface in front of the clouds hides them; and an ascent through the hand-over band
//! (atmosphere-core's `clouds/spheres/handover.rs`) whose frames blend the layer and
//! the spheres and whose mean radiance changes without a step.
//!
//! Tolerance of the orbit frame: each value within 4 % of itself plus 1 % of the frame's
//! brightest, but for one value in a hundred, which may be off by four times that: the
//! spheres' own f32 crossings (`gpu_cloud_spheres_parity.rs`, 3 % and 1 %), the
//! model's GPU error, the f16 images the composite reads and its transmittance in front
//! of the cloud (32 midpoint steps on the GPU, the model's on the CPU), as in
//! `gpu_cloud_frames.rs`.
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::composite::composite;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::front_upsample::{ReducedFront, front_at};
use atmosphere_core::clouds::layer::march::{CloudLight, CloudSegment};
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings};
use atmosphere_core::clouds::layer::upsample::{marched_coordinate, reduced_size};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::spheres::composite::spheres_only;
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use atmosphere_core::clouds::spheres::handover::{CloudForm, sphere_weight};
use atmosphere_core::clouds::spheres::reduced::{SphereView, span, spheres_image};
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::geo::equirectangular::lat_lon;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{RayRadiance, ViewRay};
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;
use render_wgpu::Renderer;
use render_wgpu::clouds::frame_clouds::{
    ABOVE_HANDOVER, COMPOSITE_IN_SPHERES, FRONT_GRID_SCALE, FrameClouds, frame_light,
};
use render_wgpu::frame::surface_buffer::SurfaceTexel;
use render_wgpu::frame::{Frame, look_orientation};

const RELATIVE: f64 = 0.04;
const OF_BRIGHTEST: f64 = 0.01;
const OUTLIER_FACTOR: f64 = 4.0;
/// The ascent's altitudes, m: below, through and above the hand-over band (50-100 km).
const ASCENT_M: [f64; 8] = [40e3, 55e3, 62e3, 70e3, 78e3, 86e3, 94e3, 110e3];
/// Largest step of the ascent's mean radiance at 550 nm between neighbours, relative to
/// their mean, beyond the larger step of the two forced ascents over the same interval.
const STEP_ALLOWANCE: f64 = 0.015;

/// Cells about 200 km across, with clear gaps.
fn cover() -> CoverGrid {
    CoverGrid::rasterize(2048, 1024, |p| {
        let (lat, lon) = lat_lon(p);
        0.45 + 0.7 * (lat * 100.0).sin() * (lon * 80.0).cos()
    })
    .unwrap()
}

fn settings() -> LayerSettings {
    lit_by(LayerMethod::Octaves)
}

fn lit_by(method: LayerMethod) -> LayerSettings {
    LayerSettings {
        method,
        steps: 64,
        shadow_steps: 16,
        ..LayerSettings::default()
    }
}

/// `altitude_m` above (0 N, 0 E) looking `pitch_deg` below the horizon, the sun 40
/// degrees up ahead and to the right, riley's sky.
fn frame(altitude_m: f64, pitch_deg: f64, (width, height): (u32, u32)) -> Frame {
    let atmosphere = atmosphere_core::atmosphere::Atmosphere::preset("earth").unwrap();
    let up = DVec3::X;
    let pitch = (-pitch_deg).to_radians();
    let forward = DVec3::new(pitch.sin(), pitch.cos(), 0.0);
    let sun = 40f64.to_radians();
    Frame {
        camera_position_m: up * (atmosphere.bottom_radius_m + altitude_m),
        orientation: look_orientation(forward, up).unwrap(),
        vertical_fov_deg: 40.0,
        sun_direction: DVec3::new(sun.sin(), sun.cos() * 0.8, sun.cos() * 0.6),
        atmosphere,
        model: ModelId::Riley,
        settings: Default::default(),
        exposure_ev100: 14.0,
        width,
        height,
        terrain: None,
    }
}

fn clouds(frame: &Frame, form: CloudForm) -> FrameClouds {
    clouds_lit_by(frame, form, LayerMethod::Octaves)
}

fn clouds_lit_by(frame: &Frame, form: CloudForm, method: LayerMethod) -> FrameClouds {
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    FrameClouds {
        settings: lit_by(method),
        light: frame_light(model.as_ref(), frame, &settings()).unwrap(),
        form,
        spheres: SphereSettings::default(),
        prune: true,
        shafts: false,
    }
}

/// The CPU's frame: each pixel's spheres, lit as `method` lights them, composited with
/// riley's answers.
fn cpu_frame(frame: &Frame, light: &CloudLight, method: LayerMethod) -> Vec<RayRadiance> {
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.0 }).unwrap();
    let bottom = frame.atmosphere.bottom_radius_m;
    let layer = CloudLayer::new(lit_by(method), bottom, cover(), phase).unwrap();
    let spheres =
        CloudSpheres::new(&layer, &SphereSettings::default(), light.sun_direction).unwrap();
    let orders = support::clouds::orders();
    (0..frame.height)
        .flat_map(|row| (0..frame.width).map(move |column| (column, row)))
        .map(|(column, row)| {
            let ray = frame.pixel_ray(column, row);
            let full = model.radiance(&ray).unwrap();
            let (cloud, first) = spheres_only(
                &spheres,
                &orders,
                light,
                ray.origin_m,
                ray.direction,
                f64::INFINITY,
            );
            let Some(t0) = first.filter(|_| cloud.transmittance[0] < 1.0) else {
                return full;
            };
            let front = model
                .radiance(&ViewRay {
                    max_distance_m: Some(t0),
                    ..ray
                })
                .unwrap();
            composite(&full, &front, &cloud)
        })
        .collect()
}

fn render(renderer: &mut Renderer, frame: &Frame, clouds: Option<FrameClouds>) -> Vec<[f32; 4]> {
    renderer.set_clouds(clouds).unwrap();
    renderer.render(frame).unwrap();
    renderer.read_hdr().unwrap()
}

/// Lit by the octaves and by the four-stream slab (`slab_light.rs`).
#[test]
fn a_frame_from_orbit_shows_the_spheres_as_the_cpu_does() {
    let Some(mut renderer) = support::renderer_or_skip("cloud spheres in a frame") else {
        return;
    };
    renderer
        .set_cloud_inputs(&cover(), &support::clouds::orders())
        .unwrap();
    for method in [LayerMethod::Octaves, LayerMethod::FourStream] {
        orbit_frame_as_the_cpu(&mut renderer, method);
    }
}

fn orbit_frame_as_the_cpu(renderer: &mut Renderer, method: LayerMethod) {
    let frame = frame(4e5, 50.0, (64, 36));
    let clouds = clouds_lit_by(&frame, CloudForm::Auto, method);
    renderer.set_clouds(Some(clouds.clone())).unwrap();
    let plan = renderer.render(&frame).unwrap();
    assert!(plan.runs("cloud_spheres") && !plan.runs("clouds"), "{plan}");
    assert!(plan.skipped.contains(&("clouds", ABOVE_HANDOVER)), "{plan}");
    let gpu = renderer.read_hdr().unwrap();
    let clear = render(renderer, &frame, None);
    let cpu = cpu_frame(&frame, &clouds.light, method);
    let brightest = cpu
        .iter()
        .flat_map(|p| p.radiance.iter().copied())
        .fold(0.0, f64::max);
    let clouded = gpu
        .iter()
        .zip(&clear)
        .filter(|(g, c)| (g[1] - c[1]).abs() > 0.05 * c[1])
        .count();
    assert!(
        clouded > gpu.len() / 4,
        "the spheres must change the frame: {clouded} of {} pixels",
        gpu.len()
    );
    let (worst, outside, far) = against(&gpu, &cpu, brightest);
    println!("{method} orbit frame: worst {worst:.3} of the tolerance, {outside} values outside");
    assert!(
        outside * 100 <= 3 * cpu.len() && far == 0,
        "{outside} values outside the tolerance, {far} four times outside; worst {worst:.2}"
    );
}

/// How `image` (radiance per pixel) compares with `cpu` by the module's tolerance (of the
/// brightest value `brightest`): the worst error as a share of it, the values outside
/// it, and those outside four times it.
fn against(image: &[[f32; 4]], cpu: &[RayRadiance], brightest: f64) -> (f64, usize, usize) {
    let (mut worst, mut outside, mut far) = (0.0f64, 0, 0);
    for (g, c) in image.iter().zip(cpu) {
        for w in 0..3 {
            let error = (f64::from(g[w]) - c.radiance[w]).abs();
            let allowed = RELATIVE * c.radiance[w] + OF_BRIGHTEST * brightest;
            worst = worst.max(error / allowed);
            outside += usize::from(error > allowed);
            far += usize::from(error > OUTLIER_FACTOR * allowed);
        }
    }
    (worst, outside, far)
}

/// From orbit with the spheres at divisor 3 the model's second run takes one ray per
/// FRONT_GRID_SCALE x 3 pixels each way (`clouds/frame_front.rs`): the frame against its
/// CPU twin (the reduced spheres of `reduced.rs`, the air in front from
/// `front_upsample.rs`), and the twin against the same spheres with every pixel's own air
/// in front; looking down and across the limb of the layer's top, with pixels twenty
/// times as large as a 1280 x 720 frame's of 40 degrees and with pixels of that size.
#[test]
fn from_orbit_the_reduced_run_in_front_of_the_spheres_keeps_the_frame() {
    let Some(mut renderer) = support::renderer_or_skip("cloud spheres' reduced front") else {
        return;
    };
    renderer
        .set_cloud_inputs(&cover(), &support::clouds::orders())
        .unwrap();
    for (pitch_deg, fov_deg) in [(50.0, 40.0), (22.0, 40.0), (50.0, 2.0), (20.5, 2.0)] {
        let frame = Frame {
            vertical_fov_deg: fov_deg,
            ..frame(4e5, pitch_deg, (64, 36))
        };
        let mut clouds = clouds(&frame, CloudForm::Auto);
        clouds.spheres.resolution_divisor = 3;
        renderer.set_clouds(Some(clouds.clone())).unwrap();
        let plan = renderer.render(&frame).unwrap();
        assert!(plan.runs("cloud_front"), "{plan}");
        // The spheres' upsample composites, its listed pixels' pass where the taps cannot.
        let composite = plan
            .skipped
            .iter()
            .find(|(name, _)| *name == "cloud_composite");
        assert_eq!(composite.map(|s| s.1), Some(COMPOSITE_IN_SPHERES), "{plan}");
        let gpu = renderer.read_hdr().unwrap();
        let divisors = (3, 3 * FRONT_GRID_SCALE);
        let ([twin, exact, no_front], missing) =
            cpu_reduced_frames(&frame, &clouds.light, divisors);
        if pitch_deg < 25.0 {
            let pixels = twin.len();
            assert!(
                0 < missing && missing < pixels,
                "{missing} of {pixels} miss the layer"
            );
        }
        let brightest = exact
            .iter()
            .flat_map(|p| p.radiance.iter().copied())
            .fold(0.0, f64::max);
        let as_image = |frame: &[RayRadiance]| -> Vec<[f32; 4]> {
            let f = |p: &RayRadiance, w: usize| p.radiance[w] as f32;
            frame
                .iter()
                .map(|p| [f(p, 0), f(p, 1), f(p, 2), 1.0])
                .collect()
        };
        let (worst, outside, far) = against(&gpu, &twin, brightest);
        let (twin_worst, twin_outside, twin_far) = against(&as_image(&twin), &exact, brightest);
        let (_, without, _) = against(&as_image(&no_front), &exact, brightest);
        println!(
            "{pitch_deg} degrees down, {fov_deg} degrees across: GPU against the twin worst {worst:.3} of the \
             tolerance, {outside} values outside; the twin against every pixel's front \
             worst {twin_worst:.3}, {twin_outside} outside; without the air in front \
             {without} outside"
        );
        let values = 3 * twin.len();
        assert!(
            outside * 100 <= 3 * values && far == 0,
            "GPU: {outside} values outside the tolerance, {far} four times; worst {worst:.2}"
        );
        assert!(
            twin_outside * 100 <= values && twin_far == 0,
            "reduced front: {twin_outside} values outside the tolerance, {twin_far} four \
             times; worst {twin_worst:.2}"
        );
        // The test can fail: the air in front matters here.
        assert!(
            without * 10 > values,
            "{without} of {values} values need the air in front"
        );
    }
}

/// The CPU's frames of the spheres at the first of `divisors` composited with riley's
/// answers, the air in front of the cloud from the reduced rays at the second (the GPU's
/// twin), from each pixel's own ray, and left out; and how many pixels' rays miss the
/// layer's top.
fn cpu_reduced_frames(
    frame: &Frame,
    light: &CloudLight,
    (divisor, front_divisor): (u32, u32),
) -> ([Vec<RayRadiance>; 3], usize) {
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.0 }).unwrap();
    let layer = CloudLayer::new(settings(), frame.atmosphere.bottom_radius_m, cover(), phase);
    let spheres = CloudSpheres::new(
        &layer.unwrap(),
        &SphereSettings::default(),
        light.sun_direction,
    )
    .unwrap();
    let orders = support::clouds::orders();
    let size = (frame.width, frame.height);
    let origin = frame.camera_position_m;
    let direction = |x: f64, y: f64| frame.direction_through(x + 0.5, y + 0.5).normalize();
    let view = SphereView {
        origin,
        size,
        direction: &direction,
        end_m: &|_, _| f64::INFINITY,
    };
    let image = spheres_image(&spheres, &orders, light, &view, divisor).unwrap();
    let ray_to = |direction: DVec3, t: f64| ViewRay {
        origin_m: origin,
        direction,
        sun_direction: frame.sun_direction.normalize(),
        max_distance_m: Some(t),
    };
    let low = reduced_size(size.0, size.1, front_divisor);
    let rays: Vec<(RayRadiance, f64)> = (0..low.1)
        .flat_map(|j| (0..low.0).map(move |i| (i, j)))
        .map(|(i, j)| {
            let x = marched_coordinate(i, low.0, size.0);
            let d = direction(x, marched_coordinate(j, low.1, size.1));
            match span(spheres.shells(), origin, d, f64::INFINITY) {
                Some((t0, _)) => (model.radiance(&ray_to(d, t0)).unwrap(), t0),
                None => (RayRadiance::unattenuated(3), 0.0),
            }
        })
        .collect();
    let three = |v: &[f64]| [v[0], v[1], v[2]];
    let radiance: Vec<[f64; 3]> = rays.iter().map(|(r, _)| three(&r.radiance)).collect();
    let transmittance: Vec<[f64; 3]> = rays.iter().map(|(r, _)| three(&r.transmittance)).collect();
    let entry_m: Vec<f64> = rays.iter().map(|(_, t0)| *t0).collect();
    let reduced = ReducedFront {
        size: low,
        radiance: &radiance,
        transmittance: &transmittance,
        entry_m: &entry_m,
    };
    let mut frames: [Vec<RayRadiance>; 3] = Default::default();
    let mut missing = 0;
    for (k, c) in image.iter().enumerate() {
        let (x, y) = (k as u32 % size.0, k as u32 / size.0);
        let ray = frame.pixel_ray(x, y);
        let full = model.radiance(&ray).unwrap();
        let cloud = CloudSegment {
            radiance: c[..3].to_vec(),
            transmittance: vec![c[3]; 3],
        };
        let entry = span(spheres.shells(), origin, ray.direction, f64::INFINITY);
        missing += usize::from(entry.is_none());
        let Some((t0, _)) = entry.filter(|_| c[3] < 1.0) else {
            frames.iter_mut().for_each(|f| f.push(full.clone()));
            continue;
        };
        let exact = model.radiance(&ray_to(ray.direction, t0)).unwrap();
        let air = front_at(&reduced, size, (x, y), t0, || three(&exact.transmittance));
        let twin = RayRadiance {
            radiance: air.radiance.to_vec(),
            transmittance: air.transmittance.to_vec(),
            ..exact.clone()
        };
        let none = RayRadiance {
            radiance: vec![0.0; 3],
            transmittance: vec![1.0; 3],
            ..exact.clone()
        };
        for (f, front) in frames.iter_mut().zip([&twin, &exact, &none]) {
            f.push(composite(&full, front, &cloud));
        }
    }
    (frames, missing)
}

#[test]
fn a_surface_in_front_of_the_spheres_hides_them() {
    let Some(mut renderer) = support::renderer_or_skip("cloud spheres behind a surface") else {
        return;
    };
    renderer
        .set_cloud_inputs(&cover(), &support::clouds::orders())
        .unwrap();
    let frame = frame(4e5, 50.0, (32, 18));
    // A wall 100 km from the camera over the left half, the cloud some 500 km away.
    let surface: Vec<SurfaceTexel> = (0..frame.height)
        .flat_map(|row| (0..frame.width).map(move |column| (column, row)))
        .map(|(column, row)| match column < frame.width / 2 {
            true => SurfaceTexel {
                normal: (-frame.pixel_ray(column, row).direction)
                    .as_vec3()
                    .to_array(),
                distance_m: 1e5,
                albedo: [0.3, 0.25, 0.2],
                water: false,
            },
            false => SurfaceTexel::default(),
        })
        .collect();
    let mut images = Vec::new();
    for clouds in [None, Some(clouds(&frame, CloudForm::Spheres))] {
        renderer.set_clouds(clouds).unwrap();
        renderer.render_with_surface(&frame, &surface).unwrap();
        images.push(renderer.read_hdr().unwrap());
    }
    let (mut wall_same, mut open_changed) = (true, 0);
    for (i, (clear, cloudy)) in images[0].iter().zip(&images[1]).enumerate() {
        if surface[i].distance_m > 0.0 {
            wall_same &= clear == cloudy;
        } else {
            open_changed += usize::from((clear[1] - cloudy[1]).abs() > 0.05 * clear[1]);
        }
    }
    assert!(
        wall_same,
        "the wall in front of the cloud must stay as without it"
    );
    assert!(
        open_changed > 50,
        "the open half must show cloud: {open_changed} pixels"
    );
}

/// The mean radiance at 550 nm of an image.
fn mean_green(image: &[[f32; 4]]) -> f64 {
    image.iter().map(|p| f64::from(p[1])).sum::<f64>() / image.len() as f64
}

#[test]
fn an_ascent_through_the_hand_over_blends_the_layer_and_the_spheres_without_a_step() {
    let Some(mut renderer) = support::renderer_or_skip("cloud hand-over ascent") else {
        return;
    };
    renderer
        .set_cloud_inputs(&cover(), &support::clouds::orders())
        .unwrap();
    let size = (32, 18);
    let mut means = [[0.0; 3]; ASCENT_M.len()];
    for (i, &altitude_m) in ASCENT_M.iter().enumerate() {
        let frame = frame(altitude_m, 60.0, size);
        let images: Vec<Vec<[f32; 4]>> = [CloudForm::Auto, CloudForm::Layer, CloudForm::Spheres]
            .iter()
            .map(|&form| render(&mut renderer, &frame, Some(clouds(&frame, form))))
            .collect();
        // The composite is linear in the cloud's radiance and transmittance, so the
        // blended frame is the forced frames' blend, pixel by pixel (f16 images).
        let w = sphere_weight(CloudForm::Auto, altitude_m) as f32;
        for ((a, l), s) in images[0].iter().zip(&images[1]).zip(&images[2]) {
            for c in 0..3 {
                let blend = (1.0 - w) * l[c] + w * s[c];
                assert!(
                    (a[c] - blend).abs() <= 2e-3 * blend.abs() + 1e-4,
                    "{altitude_m} m: {} against the blend {blend} (w {w})",
                    a[c]
                );
            }
        }
        means[i] = [0, 1, 2].map(|k| mean_green(&images[k]));
    }
    for (h, m) in ASCENT_M.iter().zip(&means) {
        println!(
            "{:>6.0} km  auto {:.5}  layer {:.5}  spheres {:.5}",
            h / 1e3,
            m[0],
            m[1],
            m[2]
        );
    }
    let step = |k: usize, i: usize| {
        (means[i + 1][k] - means[i][k]).abs() / (0.5 * (means[i + 1][k] + means[i][k]))
    };
    // The test can fail: switching from the layer to the spheres at once, between the
    // ascent's two middle altitudes, steps by the gap between them.
    let middle = ASCENT_M.len() / 2 - 1;
    let switch = (means[middle + 1][2] - means[middle][1]).abs()
        / (0.5 * (means[middle + 1][2] + means[middle][1]));
    let forced_there = step(1, middle).max(step(2, middle));
    println!("a switch at once would step by {switch:.4}");
    assert!(
        switch > forced_there + STEP_ALLOWANCE,
        "the layer and the spheres differ too little here for the ascent to show a pop"
    );
    for i in 0..ASCENT_M.len() - 1 {
        let forced = step(1, i).max(step(2, i));
        println!(
            "{:.0}-{:.0} km: auto step {:.4}, forced {:.4}",
            ASCENT_M[i] / 1e3,
            ASCENT_M[i + 1] / 1e3,
            step(0, i),
            forced
        );
        assert!(
            step(0, i) <= forced + STEP_ALLOWANCE,
            "{} to {} m: the mean radiance steps by {:.4}, the forced ascents by {forced:.4}",
            ASCENT_M[i],
            ASCENT_M[i + 1],
            step(0, i)
        );
    }
}
