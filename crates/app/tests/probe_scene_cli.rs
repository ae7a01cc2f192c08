//! `atmos probe --scene` end to end: the real binary on a shipped beams scene.

mod common;

use std::path::PathBuf;

use common::{atmos, atmos_fails_with, stderr};

fn sphere_scene() -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes/beams/sphere_spotlight.toml")
        .display()
        .to_string()
}

/// Rays from the scene's camera up through the beam and past the sphere, the second
/// stopped by an object 20 m away (before the beam).
const RAYS: &str = "dir_x,dir_y,dir_z,origin_x_m,origin_y_m,origin_z_m,distance_m\n\
                    0,0.18,-1,0,4,28,\n0.2,0.1,-1,0,4,28,\n0,0.18,-1,0,4,28,20\n";

/// The output rows of a probe of `RAYS` with `--model model` and `extra` flags.
fn probe(model: &str, extra: &[&str]) -> Vec<Vec<String>> {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("rays.csv");
    std::fs::write(&input, RAYS).unwrap();
    let scene = sphere_scene();
    let mut args = vec![
        "probe",
        "--scene",
        &scene,
        "--model",
        model,
        "--input",
        input.to_str().unwrap(),
    ];
    args.extend(extra);
    let output = atmos(&args);
    assert!(output.status.success(), "{}", stderr(&output));
    String::from_utf8(output.stdout)
        .unwrap()
        .lines()
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

#[test]
fn probe_of_a_scene_writes_the_input_columns_then_radiance_and_luminance() {
    let rows = probe("reference", &[]);
    assert_eq!(
        rows[0].join(","),
        "dir_x,dir_y,dir_z,origin_x_m,origin_y_m,origin_z_m,distance_m,L_680,L_550,L_440,luminance_cd_m2"
    );
    assert_eq!(rows.len(), 4);
    assert_eq!(rows[1][..7].join(","), "0,0.18,-1,0,4,28,");
    let value = |row: usize, col: usize| rows[row][col].parse::<f64>().unwrap();
    for row in 1..=2 {
        // A white light: the same radiance at every wavelength; luminance is 683 lm/W
        // times the radiance weighted by the colour-matching function y-bar over the
        // visible band, tens of thousands of times the radiance of a flat spectrum.
        assert!(value(row, 7) > 0.0 && value(row, 7) == value(row, 9));
        let ratio = value(row, 10) / value(row, 8);
        assert!((5e4..1e5).contains(&ratio), "{ratio}");
    }
    // The object 20 m away hides the beam.
    assert_eq!(value(3, 8), 0.0);
}

#[test]
fn converged_march_agrees_with_the_reference_on_the_command_line() {
    let reference = probe("reference", &[]);
    let march = probe(
        "march",
        &["--set", "steps=8192", "--set", "shadow_map_px=1024"],
    );
    for row in 1..=2 {
        let (r, m) = (
            reference[row][8].parse::<f64>().unwrap(),
            march[row][8].parse::<f64>().unwrap(),
        );
        assert!(
            (m - r).abs() < 0.005 * r,
            "row {row}: march {m}, reference {r}"
        );
    }
}

#[test]
fn scene_probe_errors_name_the_problem() {
    let scene = sphere_scene();
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("rays.csv");
    std::fs::write(&input, RAYS).unwrap();
    let input = input.to_str().unwrap();
    let base = ["probe", "--scene", &scene, "--input", input];
    atmos_fails_with(
        &[&base[..], &["--model", "nishita"]].concat(),
        "--model nishita is a sky model; with --scene the beam methods are reference, march, planes2000, qtable2002",
    );
    atmos_fails_with(
        &[&base[..], &["--model", "march", "--set", "steps=0"]].concat(),
        "march setting steps=0 is outside 1..=65536",
    );
    atmos_fails_with(
        &[&base[..], &["--model", "qtable2002", "--set", "epsilon=2"]].concat(),
        "qtable2002 setting epsilon=2 is outside 0..=1",
    );
    let output = atmos(&[&base[..], &["--model", "reference", "--orders", "1"]].concat());
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    atmos_fails_with(
        &["probe", "--model", "march", "--input", input],
        "--model march is a beam method: it needs --scene",
    );
    atmos_fails_with(
        &[
            "probe",
            "--scene",
            "/nonexistent/scene.toml",
            "--model",
            "march",
            "--input",
            input,
        ],
        "/nonexistent/scene.toml",
    );
}
