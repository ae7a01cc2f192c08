//! The cloud layer's shadow on the surface in renderer frames (the sun map,
//! `clouds/frame_sun_map.rs`, read at each pixel's surface and multiplied into every
//! model's `element_irradiance`) against the CPU twin (`clouds/layer/shadowed_surface.rs`
//! with the CPU's map of the same grid), on 64 x 36 frames of the ground seen from 1 km
//! up under the layer, the sun 30 degrees up: each value within 1 % of itself (the
//! models' own parity tolerance is 0.2 %; the map's f32 march adds its own,
//! `gpu_cloud_sun_map.rs`). The shadow's ratio to the frame without clouds follows the
//! CPU's within 0.01, a third of the pixels lie in shadows darker than 0.7 of it (a lost
//! shadow fails), and the ratio spans more than 0.1 over the frame (a shadow of one value
//! fails). Cover 0 run through the steps gives the frame without clouds bit for bit.
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::layer::shadowed_surface::radiance_with_shadowed_surface;
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::spheres::handover::CloudForm;
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::optics::phase::PhaseFunction;
use atmosphere_core::optics::surface_lighting::{SurfaceHit, radiance_with_surface};
use glam::DVec3;
use render_wgpu::Renderer;
use render_wgpu::clouds::frame_clouds::{FrameClouds, frame_light};
use render_wgpu::clouds::frame_sun_map::NO_SURFACE;
use render_wgpu::frame::surface_buffer::SurfaceTexel;
use render_wgpu::frame::{Frame, look_orientation};

const RELATIVE: f64 = 0.01;
const RATIO: f64 = 0.01;
const ALBEDO: f32 = 0.3;

/// A uniform cover broken by the detail noise at full strength into cloud a few km
/// across; thin enough (extinction 0.001 m^-1) that the shadows are partial.
fn settings() -> LayerSettings {
    LayerSettings {
        extinction_per_m: 0.001,
        detail_strength: 1.0,
        detail_scale_m: 4_000.0,
        ..LayerSettings::default()
    }
}

fn cover() -> CoverGrid {
    CoverGrid::from_values("uniform cover", 4, 2, vec![0.6; 8]).unwrap()
}

/// 1 km up, looking 30 degrees below the horizon; the sun 30 degrees up.
fn frame(model: ModelId) -> Frame {
    let atmosphere = atmosphere_core::atmosphere::Atmosphere::preset("earth").unwrap();
    let up = DVec3::X;
    let pitch = -30f64.to_radians();
    let sun = 30f64.to_radians();
    Frame {
        camera_position_m: up * (atmosphere.bottom_radius_m + 1_000.0),
        orientation: look_orientation(DVec3::new(pitch.sin(), pitch.cos(), 0.0), up).unwrap(),
        vertical_fov_deg: 40.0,
        sun_direction: DVec3::new(sun.sin(), sun.cos() * 0.6, sun.cos() * 0.8),
        atmosphere,
        model,
        settings: Default::default(),
        exposure_ev100: 14.0,
        width: 64,
        height: 36,
        terrain: None,
    }
}

/// The ground sphere in every pixel, facing up.
fn ground(frame: &Frame) -> Vec<SurfaceTexel> {
    let r = frame.atmosphere.bottom_radius_m;
    let mut texels = Vec::new();
    for row in 0..frame.height {
        for column in 0..frame.width {
            let ray = frame.pixel_ray(column, row);
            let (o, d) = (ray.origin_m, ray.direction.normalize());
            let b = o.dot(d);
            let t = -b - (b * b - o.length_squared() + r * r).sqrt();
            assert!(t > 0.0, "pixel ({column}, {row}) misses the ground");
            let n = (o + d * t).normalize();
            texels.push(SurfaceTexel {
                normal: n.as_vec3().to_array(),
                distance_m: t as f32,
                albedo: [ALBEDO; 3],
                water: false,
            });
        }
    }
    texels
}

fn clouds(renderer: &mut Renderer, frame: &Frame, settings: &LayerSettings, prune: bool) {
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    let light = frame_light(model.as_ref(), frame, settings).unwrap();
    renderer
        .set_clouds(Some(FrameClouds {
            settings: *settings,
            light,
            form: CloudForm::Layer,
            spheres: SphereSettings::default(),
            prune,
            shafts: false,
        }))
        .unwrap();
}

#[test]
fn clouds_shade_the_ground_as_the_cpu_twin_does() {
    let Some(mut renderer) = support::renderer_or_skip("cloud shadow") else {
        return;
    };
    renderer
        .set_cloud_inputs(&cover(), &support::clouds::orders())
        .unwrap();
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    for model_id in [ModelId::Nishita, ModelId::Hillaire] {
        let frame = frame(model_id);
        let surface = ground(&frame);
        renderer.set_clouds(None).unwrap();
        renderer.render_with_surface(&frame, &surface).unwrap();
        let plain = renderer.read_hdr().unwrap();
        clouds(&mut renderer, &frame, &settings(), true);
        let plan = renderer.render_with_surface(&frame, &surface).unwrap();
        assert!(plan.runs("cloud_shadow"), "{plan}");
        let shaded = renderer.read_hdr().unwrap();

        let model = prepare(model_id, &frame.atmosphere, &frame.settings).unwrap();
        let radius = frame.atmosphere.bottom_radius_m;
        let layer = CloudLayer::new(settings(), radius, cover(), phase.clone()).unwrap();
        let resolution = SunMapResolution::default();
        let grid = CloudSunMap::grid_for(layer.shell(), frame.camera_position_m, &resolution);
        let sun = frame.sun_direction.normalize();
        let map = CloudSunMap::new(&layer, grid.unwrap(), sun, &resolution).unwrap();
        let (mut worst, mut worst_ratio, mut dark) = (0.0f64, 0.0f64, 0);
        let (mut least, mut most) = (f64::INFINITY, 0.0f64);
        for (k, texel) in surface.iter().enumerate() {
            let ray = frame.pixel_ray(k as u32 % frame.width, k as u32 / frame.width);
            let hit = SurfaceHit {
                distance_m: f64::from(texel.distance_m),
                normal: glam::Vec3::from_array(texel.normal).as_dvec3(),
                albedo: texel.stored_albedo().map(f64::from).to_vec(),
            };
            let a = &frame.atmosphere;
            let cpu = radiance_with_shadowed_surface(model.as_ref(), a, &ray, &hit, &map).unwrap();
            let cpu_plain = radiance_with_surface(model.as_ref(), a, &ray, &hit).unwrap();
            for w in 0..3 {
                let (g, c) = (f64::from(shaded[k][w]), cpu.radiance[w]);
                worst = worst.max((g - c).abs() / (RELATIVE * c));
                let gpu_ratio = g / f64::from(plain[k][w]);
                let cpu_ratio = c / cpu_plain.radiance[w];
                worst_ratio = worst_ratio.max((gpu_ratio - cpu_ratio).abs() / RATIO);
                if w == 1 && cpu_ratio < 0.7 {
                    dark += 1;
                }
                if w == 1 {
                    least = least.min(cpu_ratio);
                    most = most.max(cpu_ratio);
                }
            }
        }
        println!(
            "{model_id}: worst {worst:.3} of the tolerance, ratio to the clear frame {worst_ratio:.3} \
             of its tolerance; of {} pixels {dark} below 0.7 of it, the CPU's ratio from \
             {least:.3} to {most:.3}; plan: {plan}",
            surface.len()
        );
        assert!(worst <= 1.0 && worst_ratio <= 1.0, "{worst} {worst_ratio}");
        assert!(dark > surface.len() / 3, "{dark}");
        // The shadow has structure across the frame, not one value.
        assert!(most - least > 0.1, "{least} {most}");
    }
}

#[test]
fn cover_zero_leaves_the_ground_bit_for_bit_and_the_planner_says_why() {
    let Some(mut renderer) = support::renderer_or_skip("cloud shadow cover 0") else {
        return;
    };
    renderer
        .set_cloud_inputs(&cover(), &support::clouds::orders())
        .unwrap();
    let frame = frame(ModelId::Nishita);
    let surface = ground(&frame);
    renderer.set_clouds(None).unwrap();
    renderer.render_with_surface(&frame, &surface).unwrap();
    let plain = renderer.read_hdr().unwrap();
    let empty = LayerSettings {
        coverage_scale: 0.0,
        ..settings()
    };
    clouds(&mut renderer, &frame, &empty, false);
    let plan = renderer.render_with_surface(&frame, &surface).unwrap();
    assert!(plan.runs("cloud_shadow"), "{plan}");
    let bits =
        |image: &[[f32; 4]]| -> Vec<u32> { image.iter().flatten().map(|v| v.to_bits()).collect() };
    assert_eq!(bits(&renderer.read_hdr().unwrap()), bits(&plain));
    // Pruned: no cloud, no map.
    clouds(&mut renderer, &frame, &empty, true);
    let plan = renderer.render_with_surface(&frame, &surface).unwrap();
    assert!(!plan.runs("cloud_shadow"), "{plan}");
    assert_eq!(bits(&renderer.read_hdr().unwrap()), bits(&plain));
    // Clouds over a frame without a surface: nothing to shade.
    clouds(&mut renderer, &frame, &settings(), true);
    let plan = renderer.render(&frame).unwrap();
    assert!(
        plan.skipped.contains(&("cloud_shadow", NO_SURFACE)),
        "{plan}"
    );
}
