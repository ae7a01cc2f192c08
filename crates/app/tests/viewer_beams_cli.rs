//! `atmos view --beams-scene` end to end: under Xvfb the viewer shows the sphere scene by
//! qtable2002 with the given settings, prints the planner's plan and the steps, and
//! saves a frame whose spot is lit and whose corners are dark; a scene, method or
//! setting it cannot use is named before any window opens.

mod common;

use std::path::PathBuf;
use std::process::Command;

use common::skip::record_skip;
use common::{gpu_tests_may_skip, stderr};
use render_wgpu::{GpuContext, GpuError};

fn sphere_scene() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes/beams/sphere_spotlight.toml")
}

#[test]
fn shows_a_beams_scene_under_xvfb_with_its_plan() {
    if gpu_tests_may_skip() {
        let missing = match GpuContext::headless() {
            Err(e @ GpuError::NoAdapter { .. }) => Some(e.to_string()),
            _ => Command::new("xvfb-run")
                .arg("--help")
                .output()
                .err()
                .map(|_| "xvfb-run is not installed (apt-get install xvfb xauth)".into()),
        };
        if let Some(missing) = missing {
            record_skip(&format!("ATMOS_SKIP_GPU_TESTS=1 and {missing}"));
            return;
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("beams.png");
    let output = Command::new("xvfb-run")
        .args(["-a", env!("CARGO_BIN_EXE_atmos"), "view", "--frames", "2"])
        .arg("--beams-scene")
        .arg(sphere_scene())
        .args(["--beams-method", "qtable2002"])
        .args(["--beams-set", "epsilon=1", "--beams-set", "table_u=64"])
        .args([
            "--beams-set",
            "table_v=64",
            "--beams-set",
            "shadow_map_px=128",
        ])
        .arg("--screenshot")
        .arg(&out)
        .current_dir(dir.path())
        .output()
        .expect("xvfb-run is missing: apt-get install -y xvfb xauth (or ATMOS_SKIP_GPU_TESTS=1)");
    let err = stderr(&output);
    assert!(output.status.success(), "atmos view failed: {err}");
    assert!(err.contains("plan lights[0] drawn"), "{err}");
    assert!(err.contains("sub-planes"), "{err}");
    let image = image::open(&out).expect("a PNG").to_rgb8();
    let (width, height) = image.dimensions();
    assert!(width > 100 && height > 100, "{width}x{height}");
    // The spot shines down through the middle of the view; the corners are dark air.
    let lit = (height / 4..height / 2)
        .map(|y| image.get_pixel(width / 2, y).0[1])
        .max()
        .unwrap();
    let corner = image.get_pixel(2, 2).0[1];
    assert!(lit > 60 && corner < 10, "beam {lit}, corner {corner}");
}

#[test]
fn a_scene_method_or_setting_it_cannot_use_is_named_before_any_window() {
    let cases: [(&[&str], &str); 3] = [
        (&["--beams-scene", "missing.toml"], "missing.toml"),
        (&["--beams-method", "reference"], "not on the GPU"),
        (&["--beams-set", "steps"], "--beams-set"),
    ];
    for (args, expected) in cases {
        let mut command = Command::new(env!("CARGO_BIN_EXE_atmos"));
        command.arg("view");
        if args[0] != "--beams-scene" {
            command.arg("--beams-scene").arg(sphere_scene());
        }
        let output = command
            .args(args)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap();
        let err = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(expected), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}
