//! Output paths end to end: a symbolic link is written through (the link stays, its
//! target gets the contents), and devices, pipes and folders are refused, with exit code
//! 1 and a message naming them, before any work.

mod common;

use std::os::unix::fs::symlink;
use std::path::Path;

use common::{atmos, atmos_fails_with, stderr};

const RAYS: &str = "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg\n\
                    0,0,30,0\n";

/// Runs a fast probe (single scattering of the reference, one ray) from `dir/rays.csv`
/// to `output`; returns the run.
fn probe_to(dir: &Path, output: &Path) -> std::process::Output {
    let input = dir.join("rays.csv");
    std::fs::write(&input, RAYS).unwrap();
    atmos(&[
        "probe",
        "--model",
        "reference",
        "--orders",
        "1",
        "--input",
        input.to_str().unwrap(),
        "--output",
        output.to_str().unwrap(),
    ])
}

/// Probes to `output`, asserts success and that `written` now holds the CSV.
fn probe_writes(dir: &Path, output: &Path, written: &Path) {
    let run = probe_to(dir, output);
    assert!(run.status.success(), "{}", stderr(&run));
    let csv = std::fs::read_to_string(written).unwrap();
    assert!(csv.starts_with("altitude_m,"), "{csv}");
    assert!(!Path::new(&format!("{}.partial", written.display())).exists());
}

fn is_link(path: &Path) -> bool {
    std::fs::symlink_metadata(path)
        .unwrap()
        .file_type()
        .is_symlink()
}

#[test]
fn a_link_stays_a_link_and_its_target_gets_the_output() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("results/latest.csv");
    std::fs::create_dir(dir.path().join("results")).unwrap();
    std::fs::write(&target, "old").unwrap();
    let link = dir.path().join("out.csv");
    symlink("results/latest.csv", &link).unwrap();
    probe_writes(dir.path(), &link, &target);
    assert!(is_link(&link));
}

#[test]
fn a_chain_of_links_and_a_dangling_link_are_written_through() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("real.csv");
    std::fs::write(&target, "old").unwrap();
    symlink(&target, dir.path().join("second")).unwrap();
    symlink("second", dir.path().join("first")).unwrap();
    probe_writes(dir.path(), &dir.path().join("first"), &target);
    assert!(is_link(&dir.path().join("first")) && is_link(&dir.path().join("second")));

    let dangling = dir.path().join("dangling.csv");
    symlink("made.csv", &dangling).unwrap();
    probe_writes(dir.path(), &dangling, &dir.path().join("made.csv"));
    assert!(is_link(&dangling));
}

#[test]
fn a_link_into_a_missing_folder_names_the_link_and_its_target() {
    let dir = tempfile::tempdir().unwrap();
    let link = dir.path().join("out.csv");
    symlink("missing/out.csv", &link).unwrap();
    let run = probe_to(dir.path(), &link);
    assert_eq!(run.status.code(), Some(1));
    let expected = format!(
        "error: cannot write {}: it links to {}, whose folder does not exist",
        link.display(),
        dir.path().join("missing/out.csv").display()
    );
    assert!(stderr(&run).contains(&expected), "{}", stderr(&run));
    assert!(!dir.path().join("missing").exists());
}

/// Devices, pipes and folders are refused by every command that writes, before any work
/// (no GPU adapter is looked for), and nothing is made beside them. Nothing here can
/// replace a device even if the checks broke: `/dev/null` and `/dev/stdout` themselves
/// go only to a probe whose input is missing, the other commands get a link and a folder
/// in a temporary folder (and render and contact-sheet want a file type first, hence
/// the .png names).
#[test]
fn devices_pipes_and_folders_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("folder.png");
    std::fs::create_dir(&folder).unwrap();
    let link_to_null = dir.path().join("null.png");
    symlink("/dev/null", &link_to_null).unwrap();
    let folder = folder.to_str().unwrap();
    let link = link_to_null.to_str().unwrap();
    let cases = [
        ("/dev/null", "it is a character device", 1),
        ("/dev/stdout", "is a named pipe", 1),
        (folder, "it is a folder", 4),
        (
            link,
            "it links to /dev/null, which is a character device",
            4,
        ),
    ];
    for (out, reason, how_many) in cases {
        let commands: [Vec<&str>; 4] = [
            vec![
                "probe",
                "--model",
                "riley",
                "--input",
                "missing.csv",
                "--output",
                out,
            ],
            vec!["bench", "--model", "riley", "--out", out],
            vec![
                "render", "--model", "riley", "--width", "32", "--height", "18", "--out", out,
            ],
            vec!["contact-sheet", "--model", "riley", "--out", out],
        ];
        for args in &commands[..how_many] {
            let args = args.as_slice();
            let run = atmos_fails_with(args, &format!("cannot write {out}: "));
            let err = stderr(&run);
            assert_eq!(run.status.code(), Some(1), "{args:?}: {err}");
            assert!(err.contains(reason), "{args:?}: {err}");
            assert!(!err.contains("adapter"), "{args:?}: {err}");
            assert!(run.stdout.is_empty(), "{args:?}");
        }
    }
    assert!(is_link(&link_to_null));
    assert!(!Path::new("/dev/null.partial").exists());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

#[test]
fn a_dash_is_not_taken_for_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let run = probe_to(dir.path(), Path::new("-"));
    assert_eq!(run.status.code(), Some(1));
    assert!(
        stderr(&run).contains("cannot write -: '-' is not a file name here"),
        "{}",
        stderr(&run)
    );
    assert!(!dir.path().join("-").exists() && !Path::new("-").exists());
}

/// Standard output redirected to a file and named by a link to `/dev/stdout`: replacing
/// that file would lose what `>>` appended to it, so it is refused and the file kept.
/// (Through a link in a temporary folder, so that a broken check replaces only the link.)
#[test]
fn standard_output_redirected_to_a_file_is_not_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("log.txt");
    std::fs::write(&log, "earlier lines\n").unwrap();
    let input = dir.path().join("rays.csv");
    std::fs::write(&input, RAYS).unwrap();
    let to_stdout = dir.path().join("out.csv");
    symlink("/dev/stdout", &to_stdout).unwrap();
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_atmos"))
        .args(["probe", "--model", "reference", "--orders", "1", "--input"])
        .arg(&input)
        .arg("--output")
        .arg(&to_stdout)
        .stdout(std::fs::File::options().append(true).open(&log).unwrap())
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(1));
    let expected = format!(
        "cannot write {}: it leads to /proc/self/fd/1, a file a process has open",
        to_stdout.display()
    );
    assert!(stderr(&run).contains(&expected), "{}", stderr(&run));
    assert_eq!(std::fs::read_to_string(&log).unwrap(), "earlier lines\n");
    assert!(is_link(&to_stdout));
}
