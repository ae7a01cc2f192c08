//! `atmos bench --beams-scene` end to end on tiny frames: a row per beam variant with its
//! GPU and wall times and their ratios to the interleaved baseline frames; beam methods
//! not on the GPU and beam variants without a scene are refused. Without an adapter the
//! GPU case fails with the message saying what to install, unless
//! `ATMOS_SKIP_GPU_TESTS=1`, when it records that it skipped.

mod common;

use common::{atmos, atmos_fails_with, skipped_without_adapter, stderr};

const SPHERE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/scenes/beams/sphere_spotlight.toml"
);

#[test]
fn beam_variants_are_timed_against_the_baseline_in_the_same_run() {
    let output = atmos(&[
        "bench",
        "--beams-scene",
        SPHERE,
        "--beams-variant",
        "march steps=8 shadow_map_px=64",
        "--beams-variant",
        "march steps=64 shadow_map_px=64",
        "--beams-variant",
        "planes2000 planes=16 lattice=4 shadow_map_px=64",
        "--beams-variant",
        "qtable2002 table_u=16 table_v=16 shadow_map_px=64",
        "--width",
        "16",
        "--height",
        "9",
        "--frames",
        "1",
    ]);
    if skipped_without_adapter(&output) {
        return;
    }
    assert!(output.status.success(), "{}", stderr(&output));
    let printed = String::from_utf8(output.stdout).unwrap();
    // Only the baseline among the planet models: neither --model nor --variant asked.
    assert!(
        printed.contains("| nishita samples=16 | ground |"),
        "{printed}"
    );
    assert!(!printed.contains("| hillaire |"), "{printed}");
    for variant in [
        "march steps=8 shadow_map_px=64",
        "march steps=64 shadow_map_px=64",
        "planes2000 planes=16 lattice=4 shadow_map_px=64",
        "qtable2002 table_u=16 table_v=16 shadow_map_px=64",
    ] {
        let row = printed
            .lines()
            .find(|l| l.starts_with(&format!("| {variant} |")))
            .unwrap_or_else(|| panic!("no row for {variant}:\n{printed}"));
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let wall: f64 = cells[3].parse().unwrap();
        let base_wall: f64 = cells[5].parse().unwrap();
        let wall_ratio: f64 = cells[7].parse().unwrap();
        assert!(wall > 0.0 && base_wall > 0.0, "{row}");
        // The times are printed to 0.1 ms, the ratio from the unrounded medians.
        let (low, high) = (
            (wall - 0.05) / (base_wall + 0.05),
            (wall + 0.05) / (base_wall - 0.05),
        );
        assert!(
            wall_ratio >= low - 0.005 && wall_ratio <= high + 0.005,
            "{row}"
        );
    }
}

#[test]
fn beam_variants_need_a_scene_and_a_method_on_the_gpu() {
    atmos_fails_with(
        &[
            "bench",
            "--beams-scene",
            SPHERE,
            "--beams-variant",
            "reference",
        ],
        "--beams-variant reference: not on the GPU",
    );
    atmos_fails_with(
        &[
            "bench",
            "--beams-scene",
            SPHERE,
            "--beams-variant",
            "nishita",
        ],
        "a beams scene takes a beam method",
    );
    atmos_fails_with(&["bench", "--beams-variant", "march"], "--beams-scene");
}
