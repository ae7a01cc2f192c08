//! The viewer's "Rain and ice" settings on a headless renderer, without a window: the
//! tables are built off the calling thread (the state reports the build pending and the
//! frame renders without the volumes meanwhile), then the volumes pass runs; turning
//! the volumes off removes it; a change while a build runs supersedes it; the droplet
//! deck and the small drops run the pass too; a bad setting is an error naming it, after
//! which the renderer holds no volume. Needs a GPU adapter (lavapipe will do) unless
//! `ATMOS_SKIP_GPU_TESTS=1`.

mod common;

use std::time::{Duration, Instant};

use atmos::viewer::optics_settings::OpticsSettings;
use atmos::viewer::optics_state::OpticsState;
use atmos::viewer::settings::ViewerSettings;
use common::gpu_tests_may_skip;
use common::skip::record_skip;
use render_wgpu::frame::plan::FramePlan;
use render_wgpu::{Frame, GpuContext, Renderer};

/// Longest wait for a build: the deck's and small drops' tables take a minute or more
/// of CPU on a busy 2-core machine when the cache is cold.
const BUILD_TIMEOUT: Duration = Duration::from_secs(1200);

fn ran_volumes(plan: &FramePlan) -> bool {
    plan.steps.iter().any(|s| s.name == "volumes")
}

/// A renderer and a small frame of the default view without terrain, or `None` when the
/// GPU tests may be skipped and there is no adapter.
fn renderer_and_frame() -> Option<(Renderer, Frame)> {
    let gpu = match GpuContext::headless() {
        Ok(gpu) => gpu,
        Err(e) if gpu_tests_may_skip() => {
            record_skip(&format!("ATMOS_SKIP_GPU_TESTS=1 and {e}"));
            return None;
        }
        Err(e) => panic!("{e}"),
    };
    let renderer = Renderer::new(gpu).unwrap();
    let viewer = ViewerSettings {
        terrain: false,
        ..ViewerSettings::default()
    };
    Some((renderer, viewer.frame(64, 36).unwrap()))
}

/// Applies `settings` each "frame" until their build has been swapped in; returns
/// whether some call replaced the renderer's volumes.
fn settle(
    state: &mut OpticsState,
    renderer: &mut Renderer,
    frame: &Frame,
    settings: &OpticsSettings,
) -> bool {
    let start = Instant::now();
    let mut replaced = state.apply(renderer, frame, settings).unwrap();
    while state.building() {
        assert!(start.elapsed() < BUILD_TIMEOUT, "the build did not finish");
        std::thread::sleep(Duration::from_millis(50));
        replaced |= state.apply(renderer, frame, settings).unwrap();
    }
    replaced
}

#[test]
fn the_rain_shaft_is_built_off_the_thread_then_runs_the_volumes_pass() {
    let Some((mut renderer, frame)) = renderer_and_frame() else {
        return;
    };
    let mut state = OpticsState::default();
    let rain = OpticsSettings {
        rain: true,
        rain_distance_m: 2_000.0,
        ..OpticsSettings::default()
    };
    // The call returns with the build pending on the worker (its result is only taken
    // by a later call), and the frame renders meanwhile, without the volumes.
    assert!(!state.apply(&mut renderer, &frame, &rain).unwrap());
    assert!(state.building());
    assert!(!ran_volumes(&renderer.render(&frame).unwrap()));
    assert!(settle(&mut state, &mut renderer, &frame, &rain));
    assert!(ran_volumes(&renderer.render(&frame).unwrap()));
    // Unchanged settings keep the volumes: they are not made again.
    assert!(!state.apply(&mut renderer, &frame, &rain).unwrap());
    assert!(!state.building());
    // A change draws the volumes made before while its own build runs; a second change
    // supersedes the first: the volumes end made for the last.
    let heavier = OpticsSettings {
        rain_rate_mm_h: 10.0,
        ..rain.clone()
    };
    let heaviest = OpticsSettings {
        rain_rate_mm_h: 20.0,
        ..rain.clone()
    };
    assert!(!state.apply(&mut renderer, &frame, &heavier).unwrap());
    assert!(state.building());
    assert!(ran_volumes(&renderer.render(&frame).unwrap()));
    assert!(settle(&mut state, &mut renderer, &frame, &heaviest));
    assert!(!state.apply(&mut renderer, &frame, &heaviest).unwrap());
    assert!(!state.building());
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
    assert!(!state.building());
    assert!(!ran_volumes(&renderer.render(&frame).unwrap()));
}

#[test]
fn the_droplet_deck_and_small_drops_run_the_volumes_pass_and_bad_values_are_named() {
    let Some((mut renderer, frame)) = renderer_and_frame() else {
        return;
    };
    let mut state = OpticsState::default();
    // Small droplets and small drops, so that their tables build quickly.
    let deck = OpticsSettings {
        deck: true,
        deck_droplet_radius_um: 3.0,
        ..OpticsSettings::default()
    };
    assert!(settle(&mut state, &mut renderer, &frame, &deck));
    assert!(ran_volumes(&renderer.render(&frame).unwrap()));
    let small_drops = OpticsSettings {
        rain: true,
        rain_small_drops: true,
        rain_small_drop_radius_um: 50.0,
        ..deck.clone()
    };
    assert!(settle(&mut state, &mut renderer, &frame, &small_drops));
    assert!(ran_volumes(&renderer.render(&frame).unwrap()));
    for (bad, named) in [
        (
            OpticsSettings {
                deck_optical_depth: 20.0,
                ..deck.clone()
            },
            "--deck: deck optical depth 20",
        ),
        (
            OpticsSettings {
                deck_droplet_radius_um: 1.0,
                ..deck.clone()
            },
            "--deck: deck droplet radius (um) 1",
        ),
        (
            OpticsSettings {
                rain_small_drop_radius_um: 1000.0,
                ..small_drops.clone()
            },
            "--rain: small drop radius (um) 1000",
        ),
    ] {
        let e = format!(
            "{:#}",
            state.apply(&mut renderer, &frame, &bad).unwrap_err()
        );
        assert!(e.contains(named), "{e}");
        assert!(!state.building());
        assert!(!ran_volumes(&renderer.render(&frame).unwrap()));
    }
}
