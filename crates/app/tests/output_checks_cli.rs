//! Output paths are checked before any work: a folder a command cannot write to is named
//! at once (bruneton's table build takes seconds on lavapipe; the check comes first), and
//! nothing is left behind.

mod common;

use common::atmos_fails_with;

#[test]
fn a_missing_output_folder_is_named_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("missing/sky.png");
    let out = out.to_str().unwrap();
    let render = ["render", "--model", "bruneton", "--altitude-m", "10"];
    let commands: [&[&str]; 4] = [
        &[&render[..], &["--sun-zenith-deg", "45", "--out", out]].concat(),
        &["bench", "--model", "riley", "--out", out],
        &["contact-sheet", "--model", "riley", "--out", out],
        &[
            "probe", "--model", "riley", "--input", "rays.csv", "--output", out,
        ],
    ];
    for args in commands {
        let output = atmos_fails_with(args, &format!("cannot write {out}"));
        assert!(!String::from_utf8_lossy(&output.stderr).contains("adapter"));
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}
