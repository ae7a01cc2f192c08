//! Terrain chunks chosen and meshes built off the render thread
//! (`render_wgpu::terrain::chunk_selector`, `chunk_worker`, `chunk_cover`; docs/terrain.md,
//! "No popping"): a frame that does not wait returns with the choice still being made
//! and draws the six faces meanwhile, then the chosen chunks, with a coarse cover where
//! their meshes are still being built, never a hole; once the workers are done, its
//! surface buffer equals, bit for bit, that of a renderer that waited for every chunk.
//!
//! Needs a GPU adapter (lavapipe will do); see `support/mod.rs`.

mod support;

use std::time::{Duration, Instant};

use atmosphere_core::models::id::ModelId;
use render_wgpu::frame::{LocalView, TerrainOptions, location_rotation};
use support::{frame, renderer_or_skip};

/// Looking down from 5.5 km over the Pennine Alps (about 3 km above the ground), so
/// every pixel sees the ground.
fn alps_frame(wait_for_chunks: bool) -> render_wgpu::Frame {
    let local = LocalView {
        altitude_m: 5_500.0,
        view_zenith_deg: 140.0,
        view_azimuth_deg: 30.0,
        sun_zenith_deg: 50.0,
        sun_azimuth_deg: 200.0,
    };
    let mut f = frame(ModelId::Nishita, local, 60.0, 64, 36);
    let place = location_rotation(46.0, 7.8);
    f.camera_position_m = place * f.camera_position_m;
    f.orientation = place * f.orientation;
    f.sun_direction = place * f.sun_direction;
    f.terrain = Some(TerrainOptions {
        wait_for_chunks,
        ..TerrainOptions::default()
    });
    f
}

#[test]
fn a_frame_that_does_not_wait_covers_then_converges_to_the_waiting_image() {
    let Some(mut waiting) = renderer_or_skip("terrain streaming") else {
        return;
    };
    let mut streaming = renderer_or_skip("terrain streaming").unwrap();
    waiting.render(&alps_frame(true)).unwrap();
    let expected = waiting.read_surface().unwrap();
    let done = waiting.terrain_progress().unwrap();
    assert_eq!((done.covered, done.building), (0, 0), "{done:?}");
    assert!(expected.iter().all(|t| t.distance_m > 0.0));

    let f = alps_frame(false);
    streaming.render(&f).unwrap();
    let first = streaming.terrain_progress().unwrap();
    // The choice is being made off the render thread: the frame drew the six faces.
    assert!(first.selecting, "{first:?}");
    assert_eq!((first.chosen, first.covered), (6, 0), "{first:?}");
    let roots = streaming.read_surface().unwrap();
    assert!(
        roots.iter().all(|t| t.distance_m > 0.0),
        "a hole in the six faces"
    );
    assert_ne!(
        roots, expected,
        "the faces should be coarser than the choice"
    );

    let start = Instant::now();
    let mut frames = 1;
    let mut covered_frames = 0;
    loop {
        std::thread::sleep(Duration::from_millis(20));
        streaming.render(&f).unwrap();
        frames += 1;
        let p = streaming.terrain_progress().unwrap();
        if !p.selecting && p.covered > 0 {
            // The choice arrived before its meshes: the chosen chunks built in the frame
            // are the roots alone, every other one is covered.
            assert_eq!(p.chosen, done.chosen, "{p:?}");
            covered_frames += 1;
            assert!(
                streaming
                    .read_surface()
                    .unwrap()
                    .iter()
                    .all(|t| t.distance_m > 0.0),
                "a hole in the cover"
            );
        }
        if !p.selecting && p.covered == 0 && p.building == 0 {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(300), "stalled: {p:?}");
    }
    assert!(covered_frames > 0, "no frame drew a cover");
    println!(
        "converged after {frames} frames ({covered_frames} with covers), {:?}",
        start.elapsed()
    );
    assert_eq!(streaming.read_surface().unwrap(), expected);
}
