//! `atmos view` end to end: the real binary opens its window under Xvfb (`xvfb-run -a`),
//! shows three frames, saves the last one and exits 0; the sky in the PNG is blue-ish.
//! Without Xvfb or a GPU adapter the test fails saying what to install, unless
//! `ATMOS_SKIP_GPU_TESTS=1`, when it records that it skipped and why. Without a display,
//! `atmos view` fails with a hint.

mod common;

use std::process::Command;

use common::skip::record_skip;
use common::{gpu_tests_may_skip, stderr};
use render_wgpu::{GpuContext, GpuError};

/// What the viewer lacks here where `ATMOS_SKIP_GPU_TESTS=1` lets it skip: `xvfb-run`,
/// or a GPU adapter. `None` where it must run (and pass).
fn missing_for_the_viewer() -> Option<String> {
    if !gpu_tests_may_skip() {
        return None;
    }
    if Command::new("xvfb-run").arg("--help").output().is_err() {
        return Some("xvfb-run is not installed (apt-get install xvfb xauth)".into());
    }
    match GpuContext::headless() {
        Err(e @ GpuError::NoAdapter { .. }) => Some(e.to_string()),
        _ => None,
    }
}

#[test]
fn shows_frames_under_xvfb_and_saves_a_blue_sky() {
    if let Some(missing) = missing_for_the_viewer() {
        record_skip(&format!("ATMOS_SKIP_GPU_TESTS=1 and {missing}"));
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let output = Command::new("xvfb-run")
        .args(["-a", env!("CARGO_BIN_EXE_atmos"), "view", "--frames", "3"])
        .arg("--screenshot")
        .arg(&out)
        .current_dir(dir.path())
        .output()
        .expect("xvfb-run is missing: apt-get install -y xvfb xauth (or ATMOS_SKIP_GPU_TESTS=1)");
    let err = stderr(&output);
    assert!(output.status.success(), "atmos view failed: {err}");
    assert!(err.contains("atmos view: saved"), "{err}");
    let image = image::open(&out).expect("a PNG").to_rgb8();
    // The default view (3 km above the Alps near sunset, the horizon a little above the
    // centre): the top rows are blue sky.
    let (width, height) = image.dimensions();
    assert!(width > 100 && height > 100, "{width}x{height}");
    for x in [width / 4, width / 2, 3 * width / 4] {
        let [r, g, b] = image.get_pixel(x, height / 10).0;
        assert!(b > r && b > 60, "sky pixel at {x}: {r} {g} {b}");
    }
}

#[test]
fn without_a_display_says_so_and_suggests_render() {
    let output = Command::new(env!("CARGO_BIN_EXE_atmos"))
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(err.contains("needs a display"), "{err}");
    assert!(err.contains("atmos render --scene"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// A path played from the start (10 km up, the sun 20 deg high, no terrain).
const PATH: &str = r#"version = 1
[[keyframe]]
time_s = 0
latitude_deg = 46.0
longitude_deg = 7.8
altitude_m = 10000
heading_deg = 240
pitch_deg = -5
sun_elevation_deg = 20
sun_azimuth_deg = 250
model = "hillaire"

[[keyframe]]
time_s = 10
heading_deg = 300
"#;

#[test]
fn plays_a_camera_path_under_xvfb() {
    if let Some(missing) = missing_for_the_viewer() {
        record_skip(&format!("ATMOS_SKIP_GPU_TESTS=1 and {missing}"));
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("path.toml");
    std::fs::write(&path, PATH).unwrap();
    let out = dir.path().join("out.png");
    let output = Command::new("xvfb-run")
        .args(["-a", env!("CARGO_BIN_EXE_atmos"), "view", "--frames", "3"])
        .arg("--path")
        .arg(&path)
        .arg("--screenshot")
        .arg(&out)
        .current_dir(dir.path())
        .output()
        .expect("xvfb-run is missing: apt-get install -y xvfb xauth (or ATMOS_SKIP_GPU_TESTS=1)");
    let err = stderr(&output);
    assert!(output.status.success(), "atmos view --path failed: {err}");
    let image = image::open(&out).expect("a PNG").to_rgb8();
    let first = *image.get_pixel(0, 0);
    assert!(
        image.pixels().any(|p| *p != first),
        "the image is one colour"
    );
    // Sky above the horizon (pitch -5 deg, 60 deg field of view): blue at the top.
    let (width, height) = image.dimensions();
    let [r, _, b] = image.get_pixel(width / 2, height / 10).0;
    assert!(b > r, "sky pixel: {r} {b}");
}

#[test]
fn a_bad_path_file_is_named_before_any_window() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(
        &path,
        "version = 1\n[[keyframe]]\ntime_s = 0\nlatitude_deg = 95\n",
    )
    .unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_atmos"))
        .args(["view", "--path"])
        .arg(&path)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(
        err.contains("bad.toml:2:1") && err.contains("latitude_deg"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}
