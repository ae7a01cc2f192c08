//! The progressive bruneton build (`Renderer::set_progressive`): single scattering in the
//! first frame, then the loop over orders spread over frames (Delta J and Delta E, then
//! each Delta S slice of an order), against one-shot builds of the same frames: bit for
//! bit once complete, after the first frame equal to one order, after k orders equal to
//! `max_orders = k + 1`; the plan's `building` while under way; a parameter change
//! mid-build starts it again and still ends at the fresh result.
//!
//! Needs a GPU adapter (lavapipe will do), with the skip policy of the other GPU tests.

mod support;

use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use render_wgpu::frame::plan::FramePlan;
use render_wgpu::{Frame, Renderer};
use support::{BRUNETON_TABLES, frame, renderer_or_skip, view};

/// Small tables of 131072 texels, so that an order's Delta S is two slices
/// (`render_wgpu::sky::bruneton::SLICE_TEXELS`), built on lavapipe in seconds.
const SMALL: [&str; 5] = ["r=16", "mu=32", "mu_s=16", "nu=16", "view_samples=20"];

/// Frames a progressive build may take at most here: single scattering, then per order
/// Delta J and two Delta S slices, for the orders up to the GPU's end of the loop (five
/// on Earth) and the frame that learns of it.
const MAX_FRAMES: usize = 40;

fn small_frame(albedo: f64, max_orders: Option<u32>) -> Frame {
    let mut f = frame(ModelId::Bruneton, view(1_000.0, 80.0, 70.0), 70.0, 32, 18);
    let mut settings = ModelSettings::default();
    for item in SMALL {
        let (k, v) = item.split_once('=').unwrap();
        settings.options.set(k, v);
    }
    settings.max_orders = max_orders;
    f.settings = settings;
    f.atmosphere.ground_albedo = albedo;
    f
}

/// A renderer that builds tables progressively, or `None` (skip the test) without an
/// adapter.
fn progressive_renderer_or_skip(test: &str) -> Option<Renderer> {
    let mut renderer = renderer_or_skip(test)?;
    renderer.set_progressive(true);
    Some(renderer)
}

/// The HDR image of `f` built in one frame by a fresh renderer.
fn one_shot(f: &Frame) -> Vec<[f32; 4]> {
    let mut renderer = Renderer::headless().unwrap();
    let plan = renderer.render(f).unwrap();
    assert_eq!(plan.building, None, "{plan}");
    renderer.read_hdr().unwrap()
}

/// Renders `f` until the plan no longer says a build is under way; returns the plans.
fn finish(renderer: &mut Renderer, f: &Frame) -> Vec<FramePlan> {
    let mut plans = Vec::new();
    loop {
        let plan = renderer.render(f).unwrap();
        println!("{plan}");
        let done = plan.building.is_none();
        plans.push(plan);
        if done {
            return plans;
        }
        assert!(
            plans.len() < MAX_FRAMES,
            "still building after {MAX_FRAMES} frames"
        );
    }
}

#[test]
fn a_finished_progressive_build_renders_the_one_shot_image() {
    let Some(mut renderer) = progressive_renderer_or_skip("bruneton progressive") else {
        return;
    };
    let f = small_frame(0.1, None);
    let plans = finish(&mut renderer, &f);
    let start = std::time::Instant::now();
    let reference = one_shot(&f);
    println!(
        "{} progressive frames; one-shot build and render {:.0} ms",
        plans.len(),
        start.elapsed().as_secs_f64() * 1e3
    );
    assert_eq!(renderer.read_hdr().unwrap(), reference);
    // Nothing is left to build: the next frame only renders.
    let again = renderer.render(&f).unwrap();
    assert!(
        !again.runs("scattering_orders") && again.building.is_none(),
        "{again}"
    );
    assert_eq!(renderer.read_hdr().unwrap(), reference);
}

#[test]
fn progressive_frames_show_single_scattering_then_one_more_order_each() {
    let Some(mut renderer) = progressive_renderer_or_skip("bruneton progressive orders") else {
        return;
    };
    let f = small_frame(0.1, None);
    // The first frame builds every table up to single scattering and says more follows.
    let first = renderer.render(&f).unwrap();
    for step in BRUNETON_TABLES {
        assert!(first.runs(step), "{first}");
    }
    assert_eq!(
        first.building.as_deref(),
        Some("bruneton: single scattering"),
        "{first}"
    );
    assert_eq!(
        renderer.read_hdr().unwrap(),
        one_shot(&small_frame(0.1, Some(1)))
    );
    // Each order takes Delta J and Delta E, then two Delta S slices; the scattering
    // textures are refreshed with the order's last.
    for k in 1..=2u32 {
        let plans: Vec<FramePlan> = (0..3).map(|_| renderer.render(&f).unwrap()).collect();
        let order = k + 1;
        let described: Vec<_> = plans.iter().map(|p| p.building.clone()).collect();
        assert_eq!(
            described,
            [
                format!("bruneton: order {order} of at most 32, Delta J and Delta E"),
                format!("bruneton: order {order} of at most 32, Delta S slice 1 of 2"),
                format!("bruneton: order {order} of at most 32, Delta S slice 2 of 2"),
            ]
            .map(Some),
        );
        assert!(plans.iter().all(|p| p.runs("scattering_orders")));
        let refreshed: Vec<_> = plans.iter().map(|p| p.runs("scattering_texture")).collect();
        assert_eq!(refreshed, [false, false, true]);
        assert_eq!(
            renderer.read_hdr().unwrap(),
            one_shot(&small_frame(0.1, Some(k + 1))),
            "after {k} orders"
        );
    }
}

#[test]
fn a_parameter_change_mid_build_starts_again_and_ends_at_the_fresh_result() {
    let Some(mut renderer) = progressive_renderer_or_skip("bruneton progressive restart") else {
        return;
    };
    let mut f = small_frame(0.1, None);
    for _ in 0..3 {
        assert!(renderer.render(&f).unwrap().building.is_some());
    }
    // A new ground albedo: the orders start again (single scattering is kept).
    f.atmosphere.ground_albedo = 0.3;
    let restart = renderer.render(&f).unwrap();
    assert!(
        restart.runs("scattering_orders") && !restart.runs("single_scattering"),
        "{restart}"
    );
    assert_eq!(
        restart.building.as_deref(),
        Some("bruneton: single scattering")
    );
    // A new sun mid-build changes no table: the build goes on.
    renderer.render(&f).unwrap();
    f.sun_direction = view(1_000.0, 80.0, 60.0).sun_direction();
    let moved = renderer.render(&f).unwrap();
    assert_eq!(
        moved.building.as_deref(),
        Some("bruneton: order 2 of at most 32, Delta S slice 1 of 2"),
        "{moved}"
    );
    finish(&mut renderer, &f);
    assert_eq!(renderer.read_hdr().unwrap(), one_shot(&f));
    // Turning progressive building off mid-build finishes it in the next frame.
    f.atmosphere.ground_albedo = 0.2;
    renderer.render(&f).unwrap();
    renderer.set_progressive(false);
    let rest = renderer.render(&f).unwrap();
    assert!(
        rest.runs("scattering_orders") && rest.building.is_none(),
        "{rest}"
    );
    assert_eq!(renderer.read_hdr().unwrap(), one_shot(&f));
}

/// Wall-clock time of each frame of a progressive build at the paper's table sizes (or
/// with `ATMOS_PROGRESSIVE_SET` options, `key=value` separated by spaces), at
/// `ATMOS_PROGRESSIVE_SIZE` pixels (`640x360`), measured rather than asserted. Run with
/// `./scripts/test.sh -p atmos-tests --test gpu_bruneton_progressive frame_times --
/// --ignored --nocapture`.
#[test]
#[ignore = "a measurement: a minute or more on lavapipe"]
fn frame_times_of_a_progressive_build() {
    let Some(mut renderer) = renderer_or_skip("bruneton progressive frame times") else {
        return;
    };
    let size = std::env::var("ATMOS_PROGRESSIVE_SIZE").unwrap_or_else(|_| "640x360".into());
    let (w, h) = size.split_once('x').unwrap();
    let mut f = frame(
        ModelId::Bruneton,
        view(1_000.0, 80.0, 70.0),
        70.0,
        w.parse().unwrap(),
        h.parse().unwrap(),
    );
    for item in std::env::var("ATMOS_PROGRESSIVE_SET")
        .unwrap_or_default()
        .split_whitespace()
    {
        let (k, v) = item.split_once('=').unwrap();
        f.settings.options.set(k, v);
    }
    // A first one-shot build compiles lavapipe's shaders; the progressive build follows
    // a change of the ground albedo (orders only) and one of the aerosol (everything).
    renderer.render(&f).unwrap();
    renderer.set_progressive(true);
    for (what, change) in [
        (
            "ground albedo 0.3",
            Box::new(|f: &mut Frame| f.atmosphere.ground_albedo = 0.3) as Box<dyn Fn(&mut Frame)>,
        ),
        (
            "aerosol x2",
            Box::new(|f: &mut Frame| f.atmosphere = f.atmosphere.with_aerosol_scale(2.0)),
        ),
    ] {
        change(&mut f);
        let (mut total, mut worst, mut frames) = (0.0f64, 0.0f64, 0);
        loop {
            let start = std::time::Instant::now();
            let plan = renderer.render(&f).unwrap();
            let ms = start.elapsed().as_secs_f64() * 1e3;
            println!(
                "{ms:7.0} ms  {}",
                plan.building.as_deref().unwrap_or("(complete)")
            );
            total += ms;
            worst = worst.max(ms);
            frames += 1;
            if plan.building.is_none() {
                break;
            }
        }
        println!(
            "{what} at {size}: {frames} frames, {:.1} s in all, worst frame {worst:.0} ms",
            total / 1e3
        );
    }
}
