//! `atmos probe` end to end: the real binary, real files.

use std::path::{Path, PathBuf};
mod common;

use std::process::Output;

use common::{atmos, atmos_fails_with, stderr};

const HEADER: &str = "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg,distance_m";

/// Ground at noon looking up; 10 km looking at the horizon; an object 5 km away.
const RAYS: &str = "0,0,30,0,\n10000,90,45,90,\n0,90,60,90,5000\n";

/// A temporary directory holding `rays.csv` with this text.
fn input(text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rays.csv");
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

fn probe(input: &Path, extra: &[&str]) -> Output {
    let input = input.to_str().unwrap();
    let mut args = vec![
        "probe",
        "--model",
        "reference",
        "--orders",
        "1",
        "--input",
        input,
    ];
    args.extend(extra);
    atmos(&args)
}

/// The stderr of a probe run that must fail with exit code 1 (an error in the run, not
/// in the flags) and write nothing to stdout.
fn probe_error(input: &Path, extra: &[&str]) -> String {
    let output = probe(input, extra);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert!(output.stdout.is_empty());
    stderr(&output)
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn probe_writes_csv_to_stdout() {
    let (_dir, path) = input(&format!("{HEADER}\n{RAYS}"));
    let output = probe(&path, &[]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8(output.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        format!(
            "{HEADER},L_680,L_550,L_440,T_680,T_550,T_440,E_sun_680,E_sun_550,E_sun_440,\
             luminance_cd_m2,r,g,b,L_stderr_680,L_stderr_550,L_stderr_440"
        )
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 3);
    for (row, given) in rows.iter().zip(RAYS.lines()) {
        assert_eq!(row.len(), 21);
        assert_eq!(
            row[..5].join(","),
            given,
            "input columns come back as given"
        );
        let numbers: Vec<f64> = row[5..].iter().map(|x| x.parse().unwrap()).collect();
        assert!(numbers.iter().all(|x| x.is_finite()), "{row:?}");
        let (radiance, transmittance) = (&numbers[0..3], &numbers[3..6]);
        assert!(radiance.iter().all(|&l| l > 0.0), "daylight: {row:?}");
        assert!(
            transmittance.iter().all(|&t| t > 0.0 && t <= 1.0),
            "{row:?}"
        );
        assert!(numbers[9] > 0.0, "luminance: {row:?}");
    }
    // The irradiance at the top of the atmosphere is the ASTM G-173 one.
    let e_sun_550: f64 = rows[0][5 + 7].parse().unwrap();
    assert!((e_sun_550 - 1.8504).abs() < 1e-3, "{e_sun_550}");
}

#[test]
fn probe_names_columns_as_the_wavelengths_were_written() {
    let (_dir, path) = input(&format!("{HEADER}\n0,0,30,0,\n"));
    let output = probe(&path, &["--wavelengths", "700,532.5"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8(output.stdout).unwrap();
    let header = text.lines().next().unwrap();
    assert!(
        header.ends_with(
            "L_700,L_532.5,T_700,T_532.5,E_sun_700,E_sun_532.5,\
             luminance_cd_m2,r,g,b,L_stderr_700,L_stderr_532.5"
        ),
        "{header}"
    );
}

#[test]
fn probe_output_file_is_written_whole() {
    let (dir, path) = input(&format!("{HEADER}\n{RAYS}"));
    let out = dir.path().join("out.csv");
    let output = probe(&path, &["--output", out.to_str().unwrap()]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(output.stdout.is_empty());
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(text.lines().count(), 4);
    assert_eq!(files_in(dir.path()), ["out.csv", "rays.csv"]);
}

#[test]
fn malformed_line_is_named_and_leaves_no_output() {
    let (dir, path) = input(&format!("{HEADER}\n0,0,30,0,\n0,0,abc,0,\n"));
    let out = dir.path().join("out.csv");
    let output = probe(&path, &["--output", out.to_str().unwrap()]);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("rays.csv line 3, column sun_zenith_deg: 'abc' is not a number"),
        "{message}"
    );
    assert_eq!(files_in(dir.path()), ["rays.csv"]);
}

#[test]
fn rejected_rays_are_named() {
    let cases = [
        ("-10,0,30,0,", "altitude_m -10 is below the ground"),
        ("0,80,30,0,inf", "distance_m must be finite, got inf"),
    ];
    for (ray, expected) in cases {
        let (_dir, path) = input(&format!("{HEADER}\n0,0,30,0,\n{ray}\n"));
        let message = probe_error(&path, &[]);
        assert!(
            message.contains("rays.csv line 3: ") && message.contains(expected),
            "{message}"
        );
    }
}

#[test]
fn a_setting_is_named_by_its_key() {
    let (_dir, path) = input(&format!("{HEADER}\n{RAYS}"));
    let settings = ["--model", "nishita", "--set", "samples=0"];
    let args = [&["probe", "--input", path.to_str().unwrap()], &settings[..]].concat();
    atmos_fails_with(&args, "nishita setting samples=0 is outside 1..=4096");
}

#[test]
fn bad_flags_get_clear_messages() {
    let (_dir, path) = input(&format!("{HEADER}\n{RAYS}"));
    let input = path.to_str().unwrap();
    let cases: [(&[&str], &str); 5] = [
        (&["--model", "nope"], "'nope'"),
        (
            &["--atmosphere", "no-such-preset"],
            "unknown atmosphere preset 'no-such-preset'",
        ),
        (&["--wavelengths", "680,abc"], "'abc' is not a wavelength"),
        (&["--orders", "0"], "--orders"),
        (
            &["--wavelengths", "550,550"],
            "550 nm is given more than once",
        ),
    ];
    for (flags, expected) in cases {
        let mut args = vec!["probe", "--input", input];
        if !flags.contains(&"--model") {
            args.extend(["--model", "reference"]);
        }
        args.extend(flags);
        let output = atmos_fails_with(&args, expected);
        assert!(output.stdout.is_empty(), "{flags:?}");
    }
}

#[test]
fn missing_input_file_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("nowhere.csv");
    let message = probe_error(&missing, &[]);
    assert!(
        message.starts_with("error: cannot read ") && message.contains("nowhere.csv"),
        "{message}"
    );
}

#[test]
fn usage_errors_exit_with_2() {
    let output = atmos(&["probe", "--model", "reference"]);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("--input"));
}
