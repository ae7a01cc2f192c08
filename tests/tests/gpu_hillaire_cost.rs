//! The issue's cost target for the hillaire model: at 1280x720 a ground view renders in
//! at most a quarter of the time of the 16-sample nishita frame. Slow on a software
//! rasteriser (seconds), so ignored by default; run it with
//!
//! ```sh
//! ./scripts/test.sh -p atmos-tests --test gpu_hillaire_cost -- --ignored --nocapture
//! ```
//!
//! Each model renders once first (shader compilation, first table builds), then the
//! frames measured: nishita; hillaire with only the pass (the view unchanged: the
//! target, asserted) and with the per-view tables rebuilt (the sun moved, as in an
//! animation: printed only). Compared: the sum of the plan's GPU times and the
//! wall-clock time of `Renderer::render`, which waits for the GPU (lavapipe's timestamps
//! read too little for table builds, docs/rendering.md).

mod support;

use std::time::Instant;

use atmosphere_core::models::id::ModelId;
use render_wgpu::Renderer;
use render_wgpu::frame::{Frame, LocalView};
use support::{frame, renderer_or_skip};

/// The issue's target: hillaire at most this share of the nishita frame.
const TARGET_SHARE: f64 = 0.25;

fn ground_view(model: ModelId, sun_zenith_deg: f64) -> Frame {
    let view = LocalView {
        altitude_m: 2.0,
        view_zenith_deg: 80.0,
        view_azimuth_deg: 0.0,
        sun_zenith_deg,
        sun_azimuth_deg: 20.0,
    };
    let mut frame = frame(model, view, 70.0, 1280, 720);
    if model == ModelId::Nishita {
        frame.settings.options.set("samples", 16);
    }
    frame
}

/// Renders the ground view of `model` with the sun at `sun_zenith_deg`; prints and
/// returns (sum of GPU times, wall-clock), ms.
fn timed(renderer: &mut Renderer, name: &str, model: ModelId, sun_zenith_deg: f64) -> (f64, f64) {
    let frame = ground_view(model, sun_zenith_deg);
    let start = Instant::now();
    let plan = renderer.render(&frame).unwrap();
    let wall = start.elapsed().as_secs_f64() * 1e3;
    let gpu = plan.total_gpu_ms().unwrap_or(f64::NAN);
    println!("{name}: GPU {gpu:.1} ms, wall {wall:.1} ms; plan: {plan}");
    (gpu, wall)
}

#[test]
#[ignore = "seconds of software rendering at 1280x720; run with --ignored"]
fn a_hillaire_ground_view_costs_at_most_a_quarter_of_nishita_16() {
    let Some(mut renderer) = renderer_or_skip("hillaire cost") else {
        return;
    };
    println!("on {}", renderer.gpu().adapter_summary());
    timed(&mut renderer, "nishita, first", ModelId::Nishita, 50.0);
    let nishita = timed(&mut renderer, "nishita 16", ModelId::Nishita, 50.0);
    timed(&mut renderer, "hillaire, first", ModelId::Hillaire, 60.0);
    let pass_only = timed(
        &mut renderer,
        "hillaire, same view",
        ModelId::Hillaire,
        60.0,
    );
    let per_view = timed(
        &mut renderer,
        "hillaire, sun moved",
        ModelId::Hillaire,
        50.0,
    );
    for (name, (gpu, wall)) in [("same view", pass_only), ("sun moved", per_view)] {
        println!(
            "hillaire ({name}) / nishita 16: GPU {:.3}, wall {:.3}",
            gpu / nishita.0,
            wall / nishita.1
        );
    }
    assert!(
        pass_only.0 <= TARGET_SHARE * nishita.0 && pass_only.1 <= TARGET_SHARE * nishita.1,
        "hillaire {pass_only:?} ms against nishita {nishita:?} ms"
    );
}
