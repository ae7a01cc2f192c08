//! `atmos report` end to end on a tiny grid: the real binary writes the Markdown, the
//! plots, the error table and the reference cache, reuses the cache on a second run,
//! measures GPU frame times unless told not to, and rejects bad flags by name.

mod common;

use common::{atmos, atmos_fails_with, skipped_without_adapter, stderr};

#[test]
fn writes_the_report_and_reuses_the_reference() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let args = [
        "report",
        "--out",
        out,
        "--rays",
        "2x1",
        "--reference-error",
        "0.05",
        "--model",
        "riley",
        "--model",
        "oneil",
        "--no-gpu",
    ];
    let first = atmos(&args);
    assert!(first.status.success(), "{}", stderr(&first));
    let readme = std::fs::read_to_string(dir.path().join("README.md")).unwrap();
    for needle in [
        "| riley |",
        "| oneil samples=2 |",
        "| oneil |",
        "ground, civil twilight",
        "ground, nautical twilight",
        "orbit across the terminator (400 km)",
        "GPU frame times were left out (`--no-gpu`)",
        "![Daytime luminance error against frame time (CPU",
    ] {
        assert!(readme.contains(needle), "no '{needle}' in\n{readme}");
    }
    // Riley's daytime error against all orders is tens of percent (docs/models/riley.md):
    // the row holds real numbers.
    let riley = readme.lines().find(|l| l.starts_with("| riley |")).unwrap();
    let daytime_rms: f64 = riley.split('|').nth(2).unwrap().trim().parse().unwrap();
    assert!(daytime_rms > 1.0 && daytime_rms < 100.0, "{riley}");
    let png = std::fs::read(dir.path().join("error_vs_time.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let reference = std::fs::read_to_string(dir.path().join("reference.csv")).unwrap();
    // A title, the header, then per view its fingerprint line and two rays.
    assert_eq!(reference.lines().count(), 2 + 9 * (1 + 2));
    assert!(dir.path().join("reference_single.csv").exists());
    assert!(!dir.path().join("error_vs_gpu_time.png").exists());
    // A header, then one line per setting of the models asked for and view.
    let settings = readme
        .lines()
        .filter(|l| l.starts_with("| riley") || l.starts_with("| oneil"))
        .map(|l| l.split('|').nth(1).unwrap().trim())
        .collect::<std::collections::BTreeSet<_>>()
        .len();
    assert!(settings >= 4, "{settings}");
    let table = std::fs::read_to_string(dir.path().join("errors.csv")).unwrap();
    assert_eq!(table.lines().count(), 1 + settings * 9);
    assert!(table.contains("\noneil,samples=2,nautical,"), "{table}");

    let second = atmos(&args);
    assert!(second.status.success(), "{}", stderr(&second));
    assert!(
        stderr(&second).contains("reference radiance from"),
        "{}",
        stderr(&second)
    );
}

#[test]
fn measures_the_gpu_frame_time_beside_the_baseline() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let args = [
        "report",
        "--out",
        out,
        "--rays",
        "1x1",
        "--reference-error",
        "0.1",
        "--model",
        "riley",
    ];
    let run = atmos(&args);
    if skipped_without_adapter(&run) {
        return;
    }
    assert!(run.status.success(), "{}", stderr(&run));
    let readme = std::fs::read_to_string(dir.path().join("README.md")).unwrap();
    assert!(readme.contains("GPU: a 1280 x 720 frame"), "{readme}");
    // The riley row ends with its GPU frame time and the ratio to the baseline.
    let riley = readme.lines().find(|l| l.starts_with("| riley |")).unwrap();
    let cells: Vec<&str> = riley.split('|').map(str::trim).collect();
    let ms: f64 = cells[cells.len() - 3].parse().unwrap();
    let ratio: f64 = cells[cells.len() - 2].parse().unwrap();
    assert!(ms > 0.0 && ratio > 0.0, "{riley}");
    let png = std::fs::read(dir.path().join("error_vs_gpu_time.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let table = std::fs::read_to_string(dir.path().join("errors.csv")).unwrap();
    let noon = table
        .lines()
        .find(|l| l.starts_with("riley,,noon,"))
        .unwrap();
    assert!(
        noon.split(',').nth(4).unwrap().parse::<f64>().unwrap() > 0.0,
        "{noon}"
    );
}

#[test]
fn bad_flags_are_named() {
    atmos_fails_with(&["report", "--rays", "0x3"], "'0x3'");
    atmos_fails_with(&["report", "--model", "nosuch"], "nosuch");
    atmos_fails_with(
        &["report", "--twilight-max-paths", "10"],
        "--twilight-max-paths",
    );
    atmos_fails_with(&["report", "--section", "cloud"], "cloud");
    atmos_fails_with(
        &["report", "--model", "riley", "--section", "shafts"],
        "nothing to report",
    );
}
