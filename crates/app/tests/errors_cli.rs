//! Small errors say what is wrong: an unknown `WGPU_BACKEND`, a scene file without a
//! model; and `atmos stability` ends its table with a summary line.

mod common;

use std::process::Command;

use common::{atmos, atmos_fails_with};

#[test]
fn an_unknown_backend_lists_the_known_ones() {
    let output = Command::new(env!("CARGO_BIN_EXE_atmos"))
        .args([
            "render",
            "--scene",
            "assets/scenes/default.toml",
            "--out",
            "x.png",
        ])
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .env("WGPU_BACKEND", "bogus")
        .output()
        .expect("the atmos binary runs");
    let err = common::stderr(&output);
    assert!(!output.status.success());
    assert!(
        err.contains("WGPU_BACKEND=bogus names no backend (known: vulkan"),
        "{err}"
    );
}

#[test]
fn a_scene_file_without_a_model_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("empty.toml");
    std::fs::write(&scene, "").unwrap();
    let out = dir.path().join("sky.png");
    atmos_fails_with(
        &[
            "render",
            "--scene",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        &format!(
            "scene {}: --model is required (or `model = ...` in a --scene file)",
            scene.display()
        ),
    );
}

#[test]
fn the_stability_table_ends_with_a_summary() {
    let output = atmos(&["stability", "--model", "riley"]);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{}", common::stderr(&output));
    let rows = text.lines().filter(|l| l.starts_with("| riley |")).count();
    let last = text.lines().last().unwrap_or_default();
    assert!(rows > 0);
    assert_eq!(last, format!("{rows} cases: {rows} passed, 0 failed"));
}
