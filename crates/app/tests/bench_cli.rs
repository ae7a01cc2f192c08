//! `atmos bench` end to end on tiny frames: the tables name every view of every variant,
//! the baseline's ratio to itself is 1, the file written equals what was printed; bad
//! flags are named. Without an adapter the GPU case fails with the message saying what
//! to install, unless `ATMOS_SKIP_GPU_TESTS=1`, when it records that it skipped.

mod common;

use common::{atmos, atmos_fails_with, skipped_without_adapter, stderr};

#[test]
fn bench_tables_cover_every_view_with_the_baseline_as_unit() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bench.md");
    let args = [
        "bench", "--model", "nishita", "--width", "16", "--height", "9", "--frames", "1", "--out",
    ];
    let mut args = args.to_vec();
    args.push(out.to_str().unwrap());
    let output = atmos(&args);
    if skipped_without_adapter(&output) {
        return;
    }
    let err = stderr(&output);
    assert!(output.status.success(), "{err}");
    let printed = String::from_utf8(output.stdout).unwrap();
    assert_eq!(std::fs::read_to_string(&out).unwrap(), printed);
    for variant in ["nishita samples=16", "nishita"] {
        for view in ["ground", "sunset", "orbit"] {
            let row = printed
                .lines()
                .find(|l| l.starts_with(&format!("| {variant} | {view} |")))
                .unwrap_or_else(|| panic!("no row for {variant} {view}:\n{printed}"));
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            let wall: f64 = cells[5].parse().unwrap();
            assert!(wall > 0.0 && wall.is_finite(), "{row}");
            assert!(
                cells[3].contains("nishita") && cells[3].contains("tone_map"),
                "{row}"
            );
            if variant == "nishita samples=16" {
                assert_eq!(cells[6], "1.00", "{row}");
            } else {
                assert!(cells[6].parse::<f64>().unwrap() > 0.0, "{row}");
            }
        }
    }
    assert!(printed.contains("| nishita | g_l "), "{printed}");
}

#[test]
fn a_variant_is_benched_with_its_settings() {
    let args = [
        "bench",
        "--variant",
        "nishita samples=4",
        "--width",
        "16",
        "--height",
        "9",
        "--frames",
        "1",
    ];
    let output = atmos(&args);
    if skipped_without_adapter(&output) {
        return;
    }
    assert!(output.status.success(), "{}", stderr(&output));
    let printed = String::from_utf8(output.stdout).unwrap();
    for view in ["ground", "sunset", "orbit"] {
        assert!(
            printed.contains(&format!("| nishita samples=4 | {view} |")),
            "{printed}"
        );
    }
    // Only the baseline and the variant: no model's defaults.
    assert!(!printed.contains("| hillaire |"), "{printed}");
}

#[test]
fn bad_bench_flags_are_named() {
    atmos_fails_with(&["bench", "--variant", "nishita samples=0"], "samples=0");
    atmos_fails_with(&["bench", "--variant", "reference"], "reference");
    atmos_fails_with(&["bench", "--frames", "0"], "--frames");
    let output = atmos_fails_with(&["bench", "--model", "nonesuch"], "nonesuch");
    assert_eq!(output.status.code(), Some(2));
    let no_file = [
        "bench",
        "--atmosphere",
        "nowhere.toml",
        "--model",
        "nishita",
    ];
    atmos_fails_with(&no_file, "nowhere.toml");
}
