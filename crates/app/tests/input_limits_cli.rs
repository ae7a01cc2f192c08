//! Inputs outside what the models and the GPU compute right, and input files that are not
//! text or never end, are refused with exit code 1 and an error naming the field, the
//! range, the file and the line (issue 18, defects 10 and 11).

mod common;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::spectral::Spectral;
use common::atmos;

const HEADER: &str = "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg\n";

/// Runs `atmos` and asserts exit code 1, no panic, and every one of `expected` in stderr.
fn fails_with(args: &[&str], expected: &[&str]) {
    let output = atmos(args);
    let err = common::stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    for part in expected {
        assert!(err.contains(part), "{args:?}: expected '{part}' in: {err}");
    }
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> String {
    let path: PathBuf = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path.display().to_string()
}

/// An Earth whose ground radius is `radius_m`, 60 km thick.
fn planet(radius_m: f64) -> String {
    let mut a = Atmosphere::preset("earth").unwrap();
    a.bottom_radius_m = radius_m;
    a.top_radius_m = radius_m + 60e3;
    a.to_toml()
}

/// `atmos render` of a small frame with these extra flags.
fn render(dir: &Path, extra: &[&str], expected: &[&str]) {
    let out = dir.join("sky.png").display().to_string();
    let mut args = vec![
        "render",
        "--model",
        "nishita",
        "--altitude-m",
        "10",
        "--sun-zenith-deg",
        "30",
        "--width",
        "16",
        "--height",
        "9",
        "--out",
        &out,
    ];
    args.extend(extra);
    fails_with(&args, expected);
}

/// `atmos probe --model MODEL` of the rays in `csv`, with these extra flags.
fn probe(model: &str, csv: &str, extra: &[&str], expected: &[&str]) {
    let mut args = vec!["probe", "--model", model, "--input", csv];
    args.extend(extra);
    fails_with(&args, expected);
}

#[test]
fn a_planet_too_large_for_the_models_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let huge = write(dir.path(), "huge.toml", planet(1e12).as_bytes());
    let rays = write(
        dir.path(),
        "rays.csv",
        format!("{HEADER}0,60,30,90\n").as_bytes(),
    );
    let range = "must be at most 1e10 m";
    render(
        dir.path(),
        &["--atmosphere", &huge],
        &["bottom_radius_m", range],
    );
    let named = format!("--atmosphere {huge}");
    probe(
        "reference",
        &rays,
        &["--atmosphere", &huge],
        &[&named, "bottom_radius_m", range],
    );
    // The reference computes up to 1e10 m, the real-time models and the GPU to 1e8 m.
    let large = write(dir.path(), "large.toml", planet(1e9).as_bytes());
    let real_time = "outside [1e5, 1e8] m, the range of the real-time models and the GPU";
    for model in ["bruneton", "nishita"] {
        probe(
            model,
            &rays,
            &["--atmosphere", &large],
            &["bottom_radius_m", real_time],
        );
    }
    render(
        dir.path(),
        &["--atmosphere", &large],
        &[&format!("--atmosphere {large}"), real_time],
    );
}

#[test]
fn a_sun_past_f32_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mut a = Atmosphere::preset("earth").unwrap();
    a.sun.irradiance_w_m2_nm = Spectral::SolarAstmG173 { scale: 1e300 };
    let bright = write(dir.path(), "bright.toml", a.to_toml().as_bytes());
    let expected = [
        "sun.irradiance_w_m2_nm",
        "at most 1e3 W m^-2 nm^-1 in 360..830 nm",
    ];
    render(dir.path(), &["--atmosphere", &bright], &expected);
    let rays = write(
        dir.path(),
        "rays.csv",
        format!("{HEADER}0,60,30,90\n").as_bytes(),
    );
    probe("nishita", &rays, &["--atmosphere", &bright], &expected);
}

#[test]
fn the_earths_terrain_is_refused_on_mars() {
    let dir = tempfile::tempdir().unwrap();
    render(
        dir.path(),
        &["--terrain", "--atmosphere", "mars"],
        &[
            "--terrain draws the Earth's relief",
            "ground radius of 3389500 m",
        ],
    );
}

#[test]
fn render_and_view_refuse_the_same_longitudes() {
    let dir = tempfile::tempdir().unwrap();
    let place = ["--latitude-deg", "10", "--longitude-deg", "1000"];
    let expected = ["--longitude-deg 1000 must lie in [-180, 180]"];
    render(dir.path(), &place, &expected);
    let mut view = vec!["view"];
    view.extend(place);
    fails_with(&view, &expected);
}

#[test]
fn zeniths_are_not_wrapped() {
    let dir = tempfile::tempdir().unwrap();
    for zenith in ["-5", "1000"] {
        let expected = format!("--view-zenith-deg {zenith} must lie in [0, 180] degrees");
        render(dir.path(), &["--view-zenith-deg", zenith], &[&expected]);
        let rays = write(
            dir.path(),
            "rays.csv",
            format!("{HEADER}0,60,30,90\n0,{zenith},30,90\n").as_bytes(),
        );
        let expected = format!("line 3, column view_zenith_deg: {zenith} must be in [0, 180]");
        probe("nishita", &rays, &[], &[&rays, &expected]);
    }
}

#[test]
fn a_byte_not_utf8_is_named_by_file_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let csv = [HEADER.as_bytes(), b"# caf\xe9\n0,60,30,90\n"].concat();
    let rays = write(dir.path(), "rays.csv", &csv);
    let expected = format!("{rays} line 2, column 6: not UTF-8 text (byte 0xe9)");
    probe("nishita", &rays, &[], &[&expected]);

    let earth = Atmosphere::preset("earth").unwrap().to_toml();
    let toml = [b"# \xff\n", earth.as_bytes()].concat();
    let atmosphere = write(dir.path(), "air.toml", &toml);
    let expected = format!("{atmosphere} line 1, column 3: not UTF-8 text (byte 0xff)");
    render(dir.path(), &["--atmosphere", &atmosphere], &[&expected]);

    let scene = write(dir.path(), "scene.toml", b"model = \"nishita\"\n\n# \xc3\n");
    let expected = format!("--scene: {scene} line 3, column 3: not UTF-8 text (byte 0xc3)");
    render(dir.path(), &["--scene", &scene], &[&expected]);
}

#[test]
fn endless_and_oversized_files_end_quickly_with_their_bound() {
    let dir = tempfile::tempdir().unwrap();
    let start = Instant::now();
    probe(
        "nishita",
        "/dev/zero",
        &[],
        &["/dev/zero line 1 is longer than 4096 bytes, the longest line allowed"],
    );
    render(
        dir.path(),
        &["--scene", "/dev/zero"],
        &["/dev/zero line 1 is longer than 65536 bytes"],
    );
    render(
        dir.path(),
        &["--atmosphere", "/dev/zero"],
        &["/dev/zero line 1 is longer than 65536 bytes"],
    );
    assert!(
        start.elapsed() < Duration::from_secs(10),
        "{:?}",
        start.elapsed()
    );
    let big = "# padding\n".repeat(110_000);
    let scene = write(dir.path(), "big.toml", big.as_bytes());
    render(
        dir.path(),
        &["--scene", &scene],
        &[&format!("{scene} is larger than 1048576 bytes")],
    );
}

#[test]
fn a_camera_too_far_for_the_geometry_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    // Looking straight down from 1e200 m, rays missed the planet: radiance 0, T = 1.
    let rays = write(
        dir.path(),
        "far.csv",
        format!("{HEADER}1e200,180,30,0\n").as_bytes(),
    );
    let expected = format!("{rays} line 2, column altitude_m: 1e200 must be at most 1e10 m");
    probe("nishita", &rays, &[], &[&expected]);
    let out = dir.path().join("sky.png").display().to_string();
    let args = [
        "render",
        "--model",
        "nishita",
        "--altitude-m",
        "1e11",
        "--sun-zenith-deg",
        "30",
        "--out",
        &out,
    ];
    fails_with(&args, &["--altitude-m 1e11 must be at most 1e10 m"]);
}

#[test]
fn a_sun_disk_past_the_hdr_image_is_warned_of() {
    let dir = tempfile::tempdir().unwrap();
    let mut a = Atmosphere::preset("earth").unwrap();
    a.sun.angular_radius_rad = 1e-3;
    let small = write(dir.path(), "small_sun.toml", a.to_toml().as_bytes());
    let out = dir.path().join("sky.png").display().to_string();
    let args = [
        "render",
        "--model",
        "nishita",
        "--altitude-m",
        "10",
        "--sun-zenith-deg",
        "30",
        "--width",
        "16",
        "--height",
        "9",
        "--atmosphere",
        &small,
        "--out",
        &out,
    ];
    // Warned of before the GPU is needed, so with or without an adapter.
    let err = common::stderr(&atmos(&args));
    assert!(
        err.contains("warning: the sun's disk (") && err.contains("it is drawn clipped"),
        "{err}"
    );
}
