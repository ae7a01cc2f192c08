//! `atmos bench --terrain-scene` end to end: the default scene at a tiny size prints the
//! terrain pass's and the hillaire pass's medians and their ratio; a scene without
//! terrain is refused, naming the flag, before any GPU work. Without an adapter the GPU
//! case fails with the message saying what to install, unless `ATMOS_SKIP_GPU_TESTS=1`,
//! when it records that it skipped.

mod common;

use common::{atmos, atmos_fails_with, skipped_without_adapter, stderr};

const DEFAULT_SCENE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/scenes/default.toml"
);

#[test]
fn the_default_scene_reports_the_terrain_pass_against_the_sky_pass() {
    let args = [
        "bench",
        "--terrain-scene",
        DEFAULT_SCENE,
        "--width",
        "32",
        "--height",
        "18",
        "--frames",
        "3",
    ];
    let output = atmos(&args);
    if skipped_without_adapter(&output) {
        return;
    }
    assert!(output.status.success(), "{}", stderr(&output));
    let printed = String::from_utf8(output.stdout).unwrap();
    assert!(
        printed.contains("| terrain pass, GPU ms | hillaire pass, GPU ms |"),
        "{printed}"
    );
    let row = printed.lines().last().unwrap();
    let cells: Vec<f64> = row
        .trim_matches('|')
        .split('|')
        .map(|c| c.trim().parse().unwrap())
        .collect();
    let [terrain, sky, ratio, _, _] = cells[..] else {
        panic!("{row}")
    };
    assert!(terrain > 0.0 && sky > 0.0, "{row}");
    // The times are printed to 0.1 ms, the ratio of the unrounded medians to 0.01: it
    // lies between the ratios of the times' rounding intervals' ends.
    let lowest = (terrain - 0.05) / (sky + 0.05) - 0.005;
    let highest = (terrain + 0.05) / (sky - 0.05).max(f64::MIN_POSITIVE) + 0.005;
    assert!((lowest..=highest).contains(&ratio), "{row}");
}

#[test]
fn a_scene_without_terrain_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no_terrain.toml");
    let text = std::fs::read_to_string(DEFAULT_SCENE).unwrap();
    std::fs::write(&path, text.replace("terrain = true", "terrain = false")).unwrap();
    let output = atmos_fails_with(
        &["bench", "--terrain-scene", path.to_str().unwrap()],
        "no terrain",
    );
    assert!(stderr(&output).contains("--terrain-scene"));
}
