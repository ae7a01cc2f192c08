//! `atmos bench --flight` end to end: a short flight at a tiny size prints the first,
//! median and longest frames with their ratio; a path without terrain and a frame rate
//! out of range are refused, naming the flag, before any GPU work. Without an adapter the
//! GPU case fails with the message saying what to install, unless
//! `ATMOS_SKIP_GPU_TESTS=1`, when it records that it skipped.

mod common;

use common::{atmos, atmos_fails_with, skipped_without_adapter, stderr};

const FLIGHT: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/paths/flight_sea_to_orbit.toml"
);

#[test]
fn a_flight_reports_its_median_and_longest_frame() {
    let args = [
        "bench",
        "--flight",
        FLIGHT,
        "--flight-fps",
        "1",
        "--width",
        "16",
        "--height",
        "9",
    ];
    let output = atmos(&args);
    if skipped_without_adapter(&output) {
        return;
    }
    assert!(output.status.success(), "{}", stderr(&output));
    let printed = String::from_utf8(output.stdout).unwrap();
    assert!(printed.contains("61 frames"), "{printed}");
    let number_after = |label: &str| -> f64 {
        let line = printed.lines().find(|l| l.starts_with(label)).unwrap();
        let rest = line[label.len()..].trim_start();
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    let median = number_after("median frame:");
    let longest = number_after("longest frame:");
    assert!(median > 0.0 && longest >= median, "{printed}");
    let ratio_line = printed
        .lines()
        .find(|l| l.starts_with("longest frame:"))
        .unwrap();
    let ratio: f64 = ratio_line
        .split(", ")
        .last()
        .unwrap()
        .trim_end_matches(" x the median")
        .parse()
        .unwrap();
    // The times are printed to 0.1 ms and the ratio to 0.01: the ratio of the printed
    // times may differ from the printed ratio by their rounding.
    let rounding = 0.005 + longest / median * (0.05 / median + 0.05 / longest);
    assert!(
        (ratio - longest / median).abs() <= rounding,
        "{ratio_line} (median {median} ms)"
    );
}

#[test]
fn a_flight_without_terrain_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no_terrain.toml");
    let text = std::fs::read_to_string(FLIGHT).unwrap();
    std::fs::write(&path, text.replace("terrain = true", "terrain = false")).unwrap();
    let output = atmos_fails_with(
        &["bench", "--flight", path.to_str().unwrap()],
        "no terrain at 0 s",
    );
    assert!(stderr(&output).contains("--flight"));
}

#[test]
fn a_flight_frame_rate_out_of_range_is_refused() {
    let output = atmos_fails_with(&["bench", "--flight", FLIGHT, "--flight-fps", "0"], "0");
    assert!(stderr(&output).contains("--flight-fps"));
}
