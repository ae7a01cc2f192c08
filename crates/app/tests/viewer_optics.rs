//! The viewer's "Rain and ice" settings on a headless renderer, without a window: with
//! the rain shaft on the frame runs the volumes pass, off it does not; a bad setting is
//! an error naming it, after which the renderer holds no volume. Needs a GPU adapter
//! (lavapipe will do) unless `ATMOS_SKIP_GPU_TESTS=1`.

mod common;

use atmos::viewer::optics_settings::OpticsSettings;
use atmos::viewer::optics_state::OpticsState;
use atmos::viewer::settings::ViewerSettings;
use common::gpu_tests_may_skip;
use common::skip::record_skip;
use render_wgpu::frame::plan::FramePlan;
use render_wgpu::{GpuContext, Renderer};

fn ran_volumes(plan: &FramePlan) -> bool {
    plan.steps.iter().any(|s| s.name == "volumes")
}

#[test]
fn the_rain_shaft_runs_the_volumes_pass_and_bad_settings_are_named() {
    let gpu = match GpuContext::headless() {
        Ok(gpu) => gpu,
        Err(e) if gpu_tests_may_skip() => {
            record_skip(&format!("ATMOS_SKIP_GPU_TESTS=1 and {e}"));
            return;
        }
        Err(e) => panic!("{e}"),
    };
    let mut renderer = Renderer::new(gpu).unwrap();
    let viewer = ViewerSettings {
        terrain: false,
        ..ViewerSettings::default()
    };
    let frame = viewer.frame(64, 36).unwrap();
    let mut state = OpticsState::default();
    let rain = OpticsSettings {
        rain: true,
        rain_distance_m: 2_000.0,
        ..OpticsSettings::default()
    };
    assert!(state.apply(&mut renderer, &frame, &rain).unwrap());
    assert!(ran_volumes(&renderer.render(&frame).unwrap()));
    // Unchanged settings keep the volumes: they are not made again.
    assert!(!state.apply(&mut renderer, &frame, &rain).unwrap());
    assert!(ran_volumes(&renderer.render(&frame).unwrap()));
    state
        .apply(&mut renderer, &frame, &OpticsSettings::default())
        .unwrap();
    assert!(!ran_volumes(&renderer.render(&frame).unwrap()));
    let bad = OpticsSettings {
        rain_rate_mm_h: 0.0,
        ..rain.clone()
    };
    let e = state.apply(&mut renderer, &frame, &bad).unwrap_err();
    assert!(
        format!("{e:#}").contains("rain rate (mm/h) = 0 is outside [0.1, 300]"),
        "{e:#}"
    );
    assert!(!ran_volumes(&renderer.render(&frame).unwrap()));
}
