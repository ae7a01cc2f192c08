//! `atmos report` end to end on a tiny grid: the real binary writes the Markdown, the
//! plot and the reference cache, reuses the cache on a second run, and rejects bad flags
//! by name.

mod common;

use common::{atmos, atmos_fails_with, stderr};

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
    ];
    let first = atmos(&args);
    assert!(first.status.success(), "{}", stderr(&first));
    let readme = std::fs::read_to_string(dir.path().join("README.md")).unwrap();
    for needle in [
        "| riley |",
        "| oneil samples=2 |",
        "| oneil |",
        "ground, civil twilight",
        "![daytime error",
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
    assert_eq!(reference.lines().count(), 2 + 7 * 2);
    assert!(dir.path().join("reference_single.csv").exists());

    let second = atmos(&args);
    assert!(second.status.success(), "{}", stderr(&second));
    assert!(
        stderr(&second).contains("reference radiance from"),
        "{}",
        stderr(&second)
    );
}

#[test]
fn bad_flags_are_named() {
    atmos_fails_with(&["report", "--rays", "0x3"], "'0x3'");
    atmos_fails_with(&["report", "--model", "nosuch"], "nosuch");
}
