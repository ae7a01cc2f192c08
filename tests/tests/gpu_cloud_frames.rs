//! The cloud layer composited into `Renderer` frames (`clouds/frame_pass.rs`,
//! `shaders/clouds/frame_march.wgsl` and `frame_composite.wgsl`) against its CPU twin,
//! atmosphere-core's `clouds/layer/composite.rs`, on whole 48 x 27 frames of three
//! models, with a surface in front of, inside and behind the cloud (in its shadow); the
//! interactive preset's march at a third of the resolution against `segment_upsample.rs`,
//! the mountain in front of the cloud left as at full resolution, and inside the layer,
//! where the upsample composites each pixel itself (`frame_upsample.wgsl`'s `OVER_MODEL`, no
//! composite pass); cover 0 leaves the
//! frame exactly as without clouds; pruning changes nothing; bad input is named. The
//! interactive frame's layer is lit by the frame's sun map (`sun_light = map`), its CPU
//! twin by `march_in_sun_map` with the CPU's map.
//!
//! Tolerance: each pixel's radiance within 4 % of itself plus 1 % of the frame's
//! brightest value, but for one value in a hundred, which may be off by four times that
//! (the cloud layer's parity test says why: Riley's order index jumps where the sun's
//! optical depth crosses an integer). On top of the march's f32 error (3 % in its own
//! test) come the model's own GPU error, the f16 images the composite reads, and the
//! transmittance in front of the cloud, the atmosphere's (32 midpoint steps) on the GPU
//! and the model's on the CPU.
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::presets::MarchQuality;
use atmosphere_core::clouds::layer::segment_upsample::{
    ReducedMarch, Segment, upsample_by_segment,
};
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings, SunLight};
use atmosphere_core::clouds::layer::upsample::{marched_coordinate, nearest_pixel, reduced_size};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::spheres::handover::CloudForm;
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::geo::equirectangular::lat_lon;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{RayRadiance, SkyModel};
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;
use render_wgpu::Renderer;
use render_wgpu::clouds::frame_clouds::{
    CAMERA_IN_LAYER, COMPOSITE_IN_UPSAMPLE, FrameClouds, LAYER_NOT_IN_VIEW, NO_CLOUD_IN_COVER,
    frame_light,
};
use render_wgpu::clouds::frame_pass::frame_camera;
use render_wgpu::frame::surface_buffer::SurfaceTexel;
use render_wgpu::frame::{Frame, look_orientation};
use support::clouds::{cpu_march, cpu_pixel, pixel_segment};

const RELATIVE: f64 = 0.04;
const OF_BRIGHTEST: f64 = 0.01;
const JUMP_FACTOR: f64 = 4.0;
/// The columns of the frame with a surface ("a mountain"), 2 km from the camera.
const MOUNTAIN_COLUMNS: u32 = 16;
const MOUNTAIN_M: f32 = 2_000.0;

/// Cells about 15 km across near (0 N, 0 E), where the camera is, scaled by `scale`.
fn cover(scale: f64) -> CoverGrid {
    CoverGrid::rasterize(2048, 1024, |p| {
        let (lat, lon) = lat_lon(p);
        scale * (0.5 + 0.8 * (lat * 400.0).sin() * (lon * 300.0).cos())
    })
    .unwrap()
}

fn settings() -> LayerSettings {
    LayerSettings {
        steps: 24,
        shadow_steps: 6,
        ..LayerSettings::default()
    }
}

/// 500 m above (0 N, 0 E), looking 20 degrees above the horizon, the sun 40 degrees up
/// behind the camera's right shoulder.
fn frame(model: ModelId) -> Frame {
    let atmosphere = atmosphere_core::atmosphere::Atmosphere::preset("earth").unwrap();
    let up = DVec3::X;
    let pitch = 20f64.to_radians();
    let forward = DVec3::new(pitch.sin(), pitch.cos(), 0.0);
    let sun = 40f64.to_radians();
    Frame {
        camera_position_m: up * (atmosphere.bottom_radius_m + 500.0),
        orientation: look_orientation(forward, up).unwrap(),
        vertical_fov_deg: 60.0,
        sun_direction: DVec3::new(sun.sin(), -sun.cos() * 0.6, sun.cos() * 0.8),
        atmosphere,
        model,
        settings: Default::default(),
        exposure_ev100: 14.0,
        width: 48,
        height: 27,
        terrain: None,
    }
}

/// The layer of `settings` lit by `light`, without the cloud's shadow in the air (the
/// CPU twins here have none; `gpu_cloud_shafts.rs` tests it).
fn layer_clouds(settings: LayerSettings, light: &CloudLight, prune: bool) -> FrameClouds {
    FrameClouds {
        settings,
        light: light.clone(),
        form: CloudForm::Layer,
        spheres: SphereSettings::default(),
        prune,
        shafts: false,
    }
}

/// A wall facing the camera 2 km away over the left third of the frame: in front of the
/// cloud's base low in the frame, inside the layer high in it.
fn mountain(frame: &Frame) -> Vec<SurfaceTexel> {
    support::wall(frame, MOUNTAIN_COLUMNS, MOUNTAIN_M)
}

/// How far `gpu` lies from `cpu`: the worst error over the tolerance, how many values
/// lie outside it and how many outside four times it; asserts at most one value in a
/// hundred outside and none four times outside.
fn assert_within_tolerance(what: &str, gpu: &[[f32; 4]], cpu: &[RayRadiance]) -> (f64, usize) {
    let brightest = cpu
        .iter()
        .flat_map(|p| p.radiance.iter().copied())
        .fold(0.0, f64::max);
    let (mut worst, mut outside, mut far_outside) = (0.0f64, 0, 0);
    for (g, c) in gpu.iter().zip(cpu) {
        for w in 0..3 {
            let error = (f64::from(g[w]) - c.radiance[w]).abs();
            let allowed = RELATIVE * c.radiance[w] + OF_BRIGHTEST * brightest;
            worst = worst.max(error / allowed);
            outside += usize::from(error > allowed);
            far_outside += usize::from(error > JUMP_FACTOR * allowed);
        }
    }
    assert!(
        outside * 100 <= 3 * cpu.len() && far_outside == 0,
        "{what}: {outside} values outside the tolerance, {far_outside} far outside; \
         worst {worst:.2} of it"
    );
    (worst, outside)
}

/// The CPU's composite of every pixel of `frame` over `surface`, each marched at full
/// resolution.
fn cpu_frame(
    model: &dyn SkyModel,
    (layer, orders, light): (&CloudLayer, &ScatteringOrders, &CloudLight),
    frame: &Frame,
    surface: &[SurfaceTexel],
) -> Vec<RayRadiance> {
    let map = support::clouds::frame_sun_map(layer, frame);
    (0..frame.height)
        .flat_map(|row| (0..frame.width).map(move |column| (column, row)))
        .zip(surface)
        .map(|(px, texel)| {
            let ray = frame.pixel_ray(px.0, px.1);
            let cloud = pixel_segment(layer, frame, px, texel).map(|s| {
                let o_d = (ray.origin_m, ray.direction);
                (s.0, cpu_march(layer, orders, (light, &map), o_d, s))
            });
            cpu_pixel(model, frame, px, (texel, &map), cloud)
        })
        .collect()
}

#[test]
fn inside_the_layer_the_second_run_is_skipped_and_the_frame_still_matches_the_cpu() {
    let Some(mut renderer) = support::renderer_or_skip("cloud frames inside") else {
        return;
    };
    let (orders, cover) = (support::clouds::orders(), cover(1.0));
    renderer.set_cloud_inputs(&cover, &orders).unwrap();
    let mut frame = frame(ModelId::Riley);
    frame.camera_position_m = DVec3::X * (frame.atmosphere.bottom_radius_m + 2_000.0);
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    // Octaves: Riley's order index jumps too often inside the layer for this tolerance
    // (`gpu_cloud_layer_parity.rs` tests it there).
    let settings = LayerSettings {
        method: LayerMethod::Octaves,
        ..settings()
    };
    let light = frame_light(model.as_ref(), &frame, &settings).unwrap();
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let radius = frame.atmosphere.bottom_radius_m;
    let layer = CloudLayer::new(settings, radius, cover, phase).unwrap();
    let clouds = layer_clouds(settings, &light, true);
    let (gpu, plan) = render(&mut renderer, &frame, Some(clouds));
    assert!(
        !plan.runs("cloud_front") && plan.runs("cloud_composite"),
        "{plan}"
    );
    assert!(
        plan.skipped.contains(&("cloud_front", CAMERA_IN_LAYER)),
        "{plan}"
    );
    let surface = vec![SurfaceTexel::default(); (frame.width * frame.height) as usize];
    let cpu = cpu_frame(model.as_ref(), (&layer, &orders, &light), &frame, &surface);
    let (worst, outside) = assert_within_tolerance("inside", &gpu, &cpu);
    println!("inside: worst {worst:.2} of the tolerance, {outside} values outside; {plan}");
}

#[test]
fn composited_frames_match_the_cpu_composite_for_three_models() {
    let Some(mut renderer) = support::renderer_or_skip("cloud frames parity") else {
        return;
    };
    let orders = support::clouds::orders();
    let cover = cover(1.0);
    renderer.set_cloud_inputs(&cover, &orders).unwrap();
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    for model_id in [ModelId::Nishita, ModelId::Riley, ModelId::Hillaire] {
        let frame = frame(model_id);
        let model = prepare(model_id, &frame.atmosphere, &frame.settings).unwrap();
        let settings = settings();
        let light = frame_light(model.as_ref(), &frame, &settings).unwrap();
        let layer = CloudLayer::new(
            settings,
            frame.atmosphere.bottom_radius_m,
            cover.clone(),
            phase.clone(),
        )
        .unwrap();
        renderer
            .set_clouds(Some(layer_clouds(settings, &light, true)))
            .unwrap();
        let surface = mountain(&frame);
        let plan = renderer.render_with_surface(&frame, &surface).unwrap();
        assert!(
            plan.runs("clouds") && plan.runs("cloud_front") && plan.runs("cloud_composite"),
            "{plan}"
        );
        let gpu = renderer.read_hdr().unwrap();
        let cpu = cpu_frame(model.as_ref(), (&layer, &orders, &light), &frame, &surface);
        let (worst, outside) = assert_within_tolerance(&model_id.to_string(), &gpu, &cpu);
        // The cloud shows, and the mountain's rays meet the layer behind it (the march
        // must not run) and inside it (the march must stop on it).
        let clouded = cpu.iter().filter(|p| p.transmittance[1] < 0.5).count();
        let (mut behind, mut inside) = (0, 0);
        for row in 0..frame.height {
            for column in 0..MOUNTAIN_COLUMNS {
                let ray = frame.pixel_ray(column, row);
                let to_mountain = f64::from(MOUNTAIN_M);
                if let Some((t0, t1)) =
                    layer
                        .shell()
                        .first_segment(ray.origin_m, ray.direction, f64::INFINITY)
                {
                    behind += usize::from(t0 > to_mountain);
                    inside += usize::from(t0 < to_mountain && to_mountain < t1);
                }
            }
        }
        println!(
            "{model_id}: worst {worst:.2} of the tolerance, {outside} of {} values outside, \
             {clouded} clouded pixels, the mountain before the layer in {behind} pixels and \
             inside it in {inside}; plan: {plan}",
            3 * cpu.len()
        );
        assert!(clouded > 100, "{model_id}: {clouded} clouded pixels");
        assert!(
            behind > 20 && inside > 20,
            "{model_id}: {behind} and {inside}"
        );
    }
}

/// The interactive preset's frame of `frame` over the mountain, and what it is checked
/// against.
struct Interactive {
    gpu: Vec<[f32; 4]>,
    /// The same frame with the layer marched at full resolution.
    full_resolution: Vec<[f32; 4]>,
    /// Each pixel's segment of the layer.
    segments: Vec<Segment>,
    /// The pixels the CPU's upsample marched itself.
    marched: usize,
    /// The plan of the interactive frame.
    plan: render_wgpu::frame::plan::FramePlan,
}

/// Renders `frame` over the mountain at the interactive preset (lit by the sun map) with
/// the light `method` and asserts it within the tolerance of its CPU twin: the reduced
/// march, each ray ended on its nearest pixel's surface, brought to full size by
/// `segment_upsample.rs` and composited over the model's pixels.
fn interactive_against_cpu(
    renderer: &mut Renderer,
    frame: &Frame,
    method: LayerMethod,
) -> Interactive {
    let orders = support::clouds::orders();
    let cover = cover(1.0);
    renderer.set_cloud_inputs(&cover, &orders).unwrap();
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    let settings = LayerSettings {
        sun_light: SunLight::Map,
        method,
        ..MarchQuality::Interactive.apply(LayerSettings::default())
    };
    assert_eq!(settings.resolution_divisor, 3);
    let light = frame_light(model.as_ref(), frame, &settings).unwrap();
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let radius = frame.atmosphere.bottom_radius_m;
    let layer = CloudLayer::new(settings, radius, cover.clone(), phase).unwrap();
    let surface = mountain(frame);
    let map = support::clouds::frame_sun_map(&layer, frame);
    let full = LayerSettings {
        resolution_divisor: 1,
        ..settings
    };
    let clouds = |settings| layer_clouds(settings, &light, true);
    renderer.set_clouds(Some(clouds(full))).unwrap();
    renderer.render_with_surface(frame, &surface).unwrap();
    let full_resolution = renderer.read_hdr().unwrap();
    renderer.set_clouds(Some(clouds(settings))).unwrap();
    let plan = renderer.render_with_surface(frame, &surface).unwrap();
    let gpu = renderer.read_hdr().unwrap();

    let camera = frame_camera(frame);
    let (w, h) = reduced_size(frame.width, frame.height, settings.resolution_divisor);
    let (mut image, mut reduced_segments) = (Vec::new(), Vec::new());
    for j in 0..h {
        for i in 0..w {
            let x = marched_coordinate(i, w, frame.width);
            let y = marched_coordinate(j, h, frame.height);
            let d = camera.direction_at(x, y);
            let near = (
                nearest_pixel(x, frame.width),
                nearest_pixel(y, frame.height),
            );
            let texel = &surface[(near.1 * frame.width + near.0) as usize];
            let end = if texel.distance_m > 0.0 {
                f64::from(texel.distance_m)
            } else {
                f64::INFINITY
            };
            let segment = layer.shell().first_segment(camera.position_m, d, end);
            image.push(segment.map_or([0.0, 0.0, 0.0, 1.0], |s| {
                cpu_march(&layer, &orders, (&light, &map), (camera.position_m, d), s)
            }));
            reduced_segments.push(segment);
        }
    }
    let pixels: Vec<(u32, u32)> = (0..frame.height)
        .flat_map(|row| (0..frame.width).map(move |column| (column, row)))
        .collect();
    let segments: Vec<Segment> = pixels
        .iter()
        .zip(&surface)
        .map(|(&px, texel)| pixel_segment(&layer, frame, px, texel))
        .collect();
    let reduced = ReducedMarch {
        image: &image,
        segments: &reduced_segments,
        size: (w, h),
        extinction_per_m: settings.extinction_per_m,
    };
    let mut marched = 0;
    let clouds = upsample_by_segment(
        &reduced,
        (frame.width, frame.height),
        &segments,
        |x, y, s| {
            marched += 1;
            let ray = frame.pixel_ray(x, y);
            let o_d = (ray.origin_m, ray.direction);
            cpu_march(&layer, &orders, (&light, &map), o_d, s)
        },
    );
    let cpu: Vec<RayRadiance> = pixels
        .iter()
        .zip(&surface)
        .zip(segments.iter().zip(&clouds))
        .map(|((&px, texel), (segment, cloud))| {
            let cloud = segment.map(|s| (s.0, *cloud));
            cpu_pixel(model.as_ref(), frame, px, (texel, &map), cloud)
        })
        .collect();
    let (worst, outside) = assert_within_tolerance("interactive", &gpu, &cpu);
    println!(
        "interactive, {:.0} m up: worst {worst:.2} of the tolerance, {outside} of {} values \
         outside; {marched} pixels marched themselves; {plan}",
        frame.camera_position_m.length() - radius,
        3 * cpu.len()
    );
    Interactive {
        gpu,
        full_resolution,
        segments,
        marched,
        plan,
    }
}

#[test]
fn an_interactive_frame_matches_the_cpu_upsample_by_segment_and_keeps_the_mountain_clear() {
    let Some(mut renderer) = support::renderer_or_skip("cloud frames interactive") else {
        return;
    };
    let frame = frame(ModelId::Nishita);
    let checked = interactive_against_cpu(&mut renderer, &frame, LayerMethod::Riley);
    assert!(checked.plan.runs("cloud_composite"), "{}", checked.plan);
    // The mountain in front of the cloud stays exactly as at full resolution, its edge
    // included, where a plain bilinear read would mix in the cloud beside it.
    let (mut kept, mut at_edge) = (0, 0);
    for (k, segment) in checked.segments.iter().enumerate() {
        let column = k as u32 % frame.width;
        if segment.is_none() && column < MOUNTAIN_COLUMNS {
            let (gpu, full) = (checked.gpu[k], checked.full_resolution[k]);
            assert_eq!(gpu, full, "pixel {k} of the mountain changed");
            kept += 1;
            at_edge += usize::from(column + 2 >= MOUNTAIN_COLUMNS);
        }
    }
    println!("{kept} mountain pixels kept ({at_edge} at its edge)");
    assert!(
        at_edge >= 10 && kept >= 100,
        "{kept} kept, {at_edge} at the edge"
    );
    // The mountain's edge inside the layer has no matching tap on its other side.
    assert!(checked.marched > 0, "no pixel was marched itself");
}

#[test]
fn inside_the_layer_the_interactive_upsample_composites_and_matches_the_cpu() {
    let Some(mut renderer) = support::renderer_or_skip("cloud frames interactive inside") else {
        return;
    };
    let mut frame = frame(ModelId::Nishita);
    frame.camera_position_m = DVec3::X * (frame.atmosphere.bottom_radius_m + 2_000.0);
    // Octaves: Riley's order index jumps too often inside the layer for this tolerance,
    // as in the test above at full resolution.
    let checked = interactive_against_cpu(&mut renderer, &frame, LayerMethod::Octaves);
    let plan = &checked.plan;
    assert!(
        plan.skipped
            .contains(&("cloud_composite", COMPOSITE_IN_UPSAMPLE))
            && plan.skipped.contains(&("cloud_front", CAMERA_IN_LAYER)),
        "{plan}"
    );
    // The mountain inside the layer ends rays that reduced rays beside it cross.
    assert!(checked.marched > 0, "no pixel was marched itself");
}

/// Above the layer's top the model's run in front of the cloud takes one ray per
/// `FRONT_GRID_SCALE` x 3 pixels each way (`clouds/frame_front.rs`), and the frame still
/// matches the CPU's, whose air in front is every pixel's own.
#[test]
fn above_the_layer_the_reduced_run_in_front_keeps_the_frame_as_the_cpu() {
    let Some(mut renderer) = support::renderer_or_skip("cloud frames above the layer") else {
        return;
    };
    let mut frame = frame(ModelId::Nishita);
    frame.camera_position_m = DVec3::X * (frame.atmosphere.bottom_radius_m + 5_000.0);
    let pitch = (-30f64).to_radians();
    let forward = DVec3::new(pitch.sin(), pitch.cos(), 0.0);
    frame.orientation = look_orientation(forward, DVec3::X).unwrap();
    let checked = interactive_against_cpu(&mut renderer, &frame, LayerMethod::Octaves);
    assert!(checked.plan.runs("cloud_front"), "{}", checked.plan);
    let clouded = checked.segments.iter().filter(|s| s.is_some()).count();
    assert!(
        clouded * 2 > checked.segments.len(),
        "{clouded} pixels see the layer"
    );
}

/// Renders `frame` over `surface` with `clouds` and returns the HDR image and the plan.
fn render(
    renderer: &mut Renderer,
    frame: &Frame,
    clouds: Option<FrameClouds>,
) -> (Vec<[f32; 4]>, render_wgpu::frame::plan::FramePlan) {
    renderer.set_clouds(clouds).unwrap();
    let plan = renderer.render(frame).unwrap();
    (renderer.read_hdr().unwrap(), plan)
}

#[test]
fn cover_zero_leaves_the_frame_exactly_as_without_clouds() {
    let Some(mut renderer) = support::renderer_or_skip("cloud frames cover 0") else {
        return;
    };
    renderer
        .set_cloud_inputs(&cover(0.0), &support::clouds::orders())
        .unwrap();
    let frame = frame(ModelId::Nishita);
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    let light = frame_light(model.as_ref(), &frame, &settings()).unwrap();
    let clouds = |prune| layer_clouds(settings(), &light, prune);
    let (clear, _) = render(&mut renderer, &frame, None);
    let (run, plan) = render(&mut renderer, &frame, Some(clouds(false)));
    assert!(plan.runs("clouds"), "{plan}");
    assert_eq!(clear, run, "cover 0 changed the frame");
    let (pruned, plan) = render(&mut renderer, &frame, Some(clouds(true)));
    assert!(!plan.runs("clouds"), "{plan}");
    assert!(
        plan.skipped.contains(&("clouds", NO_CLOUD_IN_COVER)),
        "{plan}"
    );
    assert_eq!(clear, pruned);
}

#[test]
fn pruning_a_layer_out_of_view_changes_nothing() {
    let Some(mut renderer) = support::renderer_or_skip("cloud frames pruning") else {
        return;
    };
    renderer
        .set_cloud_inputs(&cover(1.0), &support::clouds::orders())
        .unwrap();
    // 400 km up, looking 30 degrees above the horizon: the planet and the layer lie
    // below the frame.
    let mut frame = frame(ModelId::Nishita);
    frame.camera_position_m = DVec3::X * (frame.atmosphere.bottom_radius_m + 400_000.0);
    let pitch = 30f64.to_radians();
    frame.orientation =
        look_orientation(DVec3::new(pitch.sin(), pitch.cos(), 0.0), DVec3::X).unwrap();
    frame.vertical_fov_deg = 40.0;
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    let light = frame_light(model.as_ref(), &frame, &settings()).unwrap();
    let clouds = |prune| layer_clouds(settings(), &light, prune);
    let (run, plan) = render(&mut renderer, &frame, Some(clouds(false)));
    assert!(plan.runs("clouds"), "{plan}");
    let (pruned, plan) = render(&mut renderer, &frame, Some(clouds(true)));
    assert!(
        plan.skipped.contains(&("clouds", LAYER_NOT_IN_VIEW)),
        "{plan}"
    );
    assert!(
        plan.to_string()
            .contains("clouds (the cloud layer is not in view)")
    );
    assert_eq!(run, pruned, "pruning changed the frame");
    // Looking down at the deck the planner keeps the layer.
    frame.orientation = look_orientation(-DVec3::X, DVec3::Y).unwrap();
    let (_, plan) = render(&mut renderer, &frame, Some(clouds(true)));
    assert!(plan.runs("clouds"), "{plan}");
}

#[test]
fn bad_cloud_input_is_refused_by_name() {
    let Some(mut renderer) = support::renderer_or_skip("cloud frames bad input") else {
        return;
    };
    let frame = frame(ModelId::Nishita);
    let light = CloudLight {
        sun_direction: frame.sun_direction,
        sun_irradiance: vec![1.0; 3],
        sky_irradiance: vec![0.1; 3],
        up: DVec3::X,
    };
    let bad = FrameClouds {
        settings: LayerSettings {
            base_m: -5.0,
            ..settings()
        },
        light: light.clone(),
        form: CloudForm::Layer,
        spheres: SphereSettings::default(),
        prune: true,
        shafts: false,
    };
    let e = renderer.set_clouds(Some(bad)).unwrap_err().to_string();
    assert!(e.contains("cloud base_m") && e.contains("-5"), "{e}");
    renderer
        .set_clouds(Some(layer_clouds(settings(), &light, true)))
        .unwrap();
    let e = renderer.render(&frame).unwrap_err().to_string();
    assert!(e.contains("no cloud cover"), "{e}");
}
