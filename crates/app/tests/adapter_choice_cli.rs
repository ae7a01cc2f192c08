//! The adapter choice end to end: the README's first command (the default scene, made
//! small) with wgpu's GL backend forced, and with no Vulkan driver, never panics. It
//! renders where an adapter can run atmos, and otherwise fails listing the adapters found
//! with why each was refused, naming the packages to install and `WGPU_BACKEND`.

use std::path::Path;
use std::process::{Command, Output};

/// Runs the first command at 64x36 into `dir` with `env` set (`None`: removed).
fn first_command(dir: &Path, env: &[(&str, Option<&str>)]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_atmos"));
    command
        .args(["render", "--scene", "assets/scenes/default.toml"])
        .args(["--width", "64", "--height", "36", "--out"])
        .arg(dir.join("sky.png"))
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    for (key, value) in env {
        match value {
            Some(value) => command.env(key, value),
            None => command.env_remove(key),
        };
    }
    command.output().expect("the atmos binary runs")
}

/// Either a 64x36 sky in `dir`, or the error that says what to do.
fn renders_or_says_what_to_install(dir: &Path, output: &Output) {
    let err = String::from_utf8_lossy(&output.stderr);
    assert_ne!(output.status.code(), Some(101), "panicked: {err}");
    assert!(!err.contains("panicked"), "{err}");
    if output.status.success() {
        assert!(err.contains("64x36 hillaire frame"), "{err}");
        let image = image::open(dir.join("sky.png")).expect("a PNG").to_rgb8();
        assert_eq!(image.dimensions(), (64, 36));
        return;
    }
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(
        err.starts_with("error: no GPU adapter atmos can use (backends tried: "),
        "{err}"
    );
    // Each adapter found is listed with why it was refused, or none was found.
    let adapters: Vec<&str> = err.lines().filter(|l| l.starts_with("  - ")).collect();
    assert!(
        adapters.iter().all(|l| l.contains("): ")) || err.contains("(no adapter found)"),
        "{err}"
    );
    assert!(
        err.contains("apt-get install mesa-vulkan-drivers libvulkan1"),
        "{err}"
    );
    assert!(err.contains("WGPU_BACKEND=vulkan"), "{err}");
    assert!(!dir.join("sky.png").exists());
}

#[test]
fn the_gl_backend_renders_or_is_refused_with_its_reasons() {
    let dir = tempfile::tempdir().unwrap();
    let output = first_command(dir.path(), &[("WGPU_BACKEND", Some("gl"))]);
    renders_or_says_what_to_install(dir.path(), &output);
    let err = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() {
        assert!(err.contains("(backends tried: gl):"), "{err}");
    }
}

#[test]
fn without_a_vulkan_driver_it_renders_on_another_backend_or_says_what_to_install() {
    let dir = tempfile::tempdir().unwrap();
    let output = first_command(
        dir.path(),
        &[
            ("WGPU_BACKEND", None),
            ("WGPU_ADAPTER_NAME", None),
            ("VK_ICD_FILENAMES", Some("/nonexistent/icd.json")),
            ("VK_DRIVER_FILES", Some("/nonexistent/icd.json")),
        ],
    );
    renders_or_says_what_to_install(dir.path(), &output);
}

#[test]
fn in_the_default_environment_it_renders_or_says_what_to_install() {
    let dir = tempfile::tempdir().unwrap();
    let output = first_command(
        dir.path(),
        &[("WGPU_BACKEND", None), ("WGPU_ADAPTER_NAME", None)],
    );
    renders_or_says_what_to_install(dir.path(), &output);
}

#[test]
fn the_viewer_on_the_gl_backend_opens_or_is_refused_with_its_reasons() {
    if std::env::var("ATMOS_SKIP_GPU_TESTS").as_deref() == Ok("1") {
        println!("SKIPPED (ATMOS_SKIP_GPU_TESTS=1): the viewer needs Xvfb");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("view.png");
    let output = Command::new("xvfb-run")
        .args(["-a", env!("CARGO_BIN_EXE_atmos"), "view", "--frames", "1"])
        .arg("--screenshot")
        .arg(&out)
        .current_dir(dir.path())
        .env("WGPU_BACKEND", "gl")
        .output()
        .expect("xvfb-run is missing: apt-get install -y xvfb xauth (or ATMOS_SKIP_GPU_TESTS=1)");
    let err = String::from_utf8_lossy(&output.stderr);
    assert_ne!(output.status.code(), Some(101), "panicked: {err}");
    assert!(!err.contains("panicked"), "{err}");
    if output.status.success() {
        assert!(out.exists(), "{err}");
        return;
    }
    assert!(
        err.contains("cannot open the viewer window: no GPU adapter atmos can use"),
        "{err}"
    );
    assert!(err.contains("mesa-vulkan-drivers libvulkan1"), "{err}");
    // The display is there: rendering headless instead would not help.
    assert!(!err.contains("without a display"), "{err}");
}

#[test]
fn after_the_first_commands_set_up_atmos_prints_only_what_it_wrote() {
    // The set-up of scripts/render.sh (less the installation) on a shell without a
    // runtime directory or a chosen backend, then the built binary.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sky.png");
    let output = Command::new("bash")
        .arg("-c")
        .arg(
            "set -eu; source scripts/gpu_setup.sh; use_lavapipe_without_gpu; \
             give_runtime_dir; exec \"$0\" render --scene assets/scenes/default.toml \
             --width 64 --height 36 --out \"$1\"",
        )
        .arg(env!("CARGO_BIN_EXE_atmos"))
        .arg(&out)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("WGPU_BACKEND")
        .output()
        .expect("bash runs");
    let err = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() && err.contains("mesa-vulkan-drivers libvulkan1") {
        renders_or_says_what_to_install(dir.path(), &output);
        return;
    }
    assert!(output.status.success(), "{err}");
    assert!(output.stdout.is_empty());
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(
        lines[0].ends_with(&format!("; wrote {}", out.display())),
        "{err}"
    );
}
