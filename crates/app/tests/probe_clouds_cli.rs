//! `atmos probe --clouds` end to end: the same rays through the cloud layer answered by
//! a model with the layer's march and by the cloud path tracer (`--model reference`).

mod common;

use std::path::{Path, PathBuf};

use common::{atmos, atmos_fails_with, stderr};

const HEADER: &str = "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg";

/// Where the rays stand over the cover, and the sun's azimuth.
const PLACE: [&str; 6] = [
    "--latitude-deg",
    "10",
    "--longitude-deg",
    "20",
    "--sun-azimuth-deg",
    "90",
];

/// A temporary directory with `rays.csv` holding `rays` and `cover.png`, a cover of 1
/// everywhere.
fn inputs(rays: &str) -> (tempfile::TempDir, PathBuf, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("rays.csv");
    std::fs::write(&csv, format!("{HEADER}\n{rays}")).unwrap();
    let cover = dir.path().join("cover.png");
    image::RgbaImage::from_pixel(8, 4, image::Rgba([255, 255, 255, 255]))
        .save(&cover)
        .unwrap();
    (dir, csv, cover)
}

/// The probe's table as header and rows of numbers, after a successful run.
fn probe(model: &str, csv: &Path, extra: &[&str]) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut args = vec!["probe", "--model", model, "--input", csv.to_str().unwrap()];
    args.extend(extra);
    let output = atmos(&args);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8(output.stdout).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

fn column(header: &[String], name: &str) -> usize {
    header.iter().position(|h| h == name).unwrap()
}

#[test]
fn a_thin_cloud_near_the_sun_agrees_with_the_path_tracer_within_its_error() {
    // From the ground, 9 degrees from the sun, through a deck of optical depth 0.25:
    // single scattering through the droplets' forward peak, which the layer's march
    // (riley, offline quality) takes exactly and its back-scatter term xi adds little to.
    let (_dir, csv, cover) = inputs("0,60,60,10\n");
    let cover = cover.to_str().unwrap();
    let mut clouds = vec![
        "--clouds",
        "--cloud-cover",
        cover,
        "--cloud-density",
        "0.0005",
        "--cloud-thickness-m",
        "500",
    ];
    clouds.extend(PLACE);
    let (header, method) = probe("hillaire", &csv, &clouds);
    let mut traced_flags = clouds.to_vec();
    traced_flags.extend(["--target-error", "0.01"]);
    let (traced_header, traced) = probe("reference", &csv, &traced_flags);
    assert_eq!(header.last().unwrap(), "T_cloud");
    assert_eq!(
        &traced_header[traced_header.len() - 2..],
        ["T_cloud", "paths"]
    );
    let t_cloud = method[0][column(&header, "T_cloud")];
    assert!(
        (t_cloud - traced[0][column(&traced_header, "T_cloud")]).abs() < 0.01,
        "the march's and the path tracer's cloud transmittance"
    );
    assert!(
        (0.5..0.95).contains(&t_cloud),
        "a thin cloud: T_cloud {t_cloud}"
    );
    for nm in ["680", "550", "440"] {
        let l = method[0][column(&header, &format!("L_{nm}"))];
        let reference = traced[0][column(&traced_header, &format!("L_{nm}"))];
        let error = traced[0][column(&traced_header, &format!("L_stderr_{nm}"))];
        assert!(
            error > 0.0 && error < 0.03 * reference,
            "{nm} nm: +- {error}"
        );
        assert!(
            (l - reference).abs() < 4.0 * error,
            "{nm} nm: march {l}, path tracer {reference} +- {error}"
        );
    }
}

#[test]
fn below_an_opaque_deck_riley_is_too_dark_and_eddington_follows_the_path_tracer() {
    // Looking up under the default layer (1.5 km thick, 0.04 m^-1, optical depth about
    // 45) at full cover, away from the sun.
    let (_dir, csv, cover) = inputs("0,20,40,180\n");
    let cover = cover.to_str().unwrap();
    let mut clouds = vec!["--clouds", "--cloud-cover", cover];
    clouds.extend(PLACE);
    let (clear_header, clear) = probe("hillaire", &csv, &[]);
    let (header, method) = probe("hillaire", &csv, &clouds);
    let mut eddington_flags = clouds.to_vec();
    eddington_flags.extend(["--cloud-method", "eddington"]);
    let (eddington_header, eddington) = probe("hillaire", &csv, &eddington_flags);
    let mut traced_flags = clouds.to_vec();
    traced_flags.extend(["--target-error", "0.2"]);
    let (traced_header, traced) = probe("reference", &csv, &traced_flags);
    assert!(method[0][column(&header, "T_cloud")] < 1e-3);
    assert!(traced[0][column(&traced_header, "T_cloud")] < 1e-3);
    for nm in ["680", "550", "440"] {
        let sky = clear[0][column(&clear_header, &format!("L_{nm}"))];
        let march = method[0][column(&header, &format!("L_{nm}"))];
        let reference = traced[0][column(&traced_header, &format!("L_{nm}"))];
        let error = traced[0][column(&traced_header, &format!("L_stderr_{nm}"))];
        assert!(
            march > 0.0 && march < sky,
            "{nm} nm: march {march}, clear {sky}"
        );
        // The light that diffuses through a thick cloud, which Riley's walk loses
        // (docs/clouds.md): the path tracer finds many times the march's.
        assert!(
            reference - 3.0 * error > 3.0 * march,
            "{nm} nm: path tracer {reference} +- {error}, march {march}"
        );
        // The delta-Eddington slab keeps it: no brighter than the path tracer (whose
        // ground and air below the deck are lit as under a clear sky), at least half.
        let diffused = eddington[0][column(&eddington_header, &format!("L_{nm}"))];
        assert!(
            diffused > 0.5 * (reference - 3.0 * error) && diffused < reference + 3.0 * error,
            "{nm} nm: path tracer {reference} +- {error}, eddington {diffused}"
        );
    }
}

/// `cover.png` in `dir`: a deck in stripes along the meridians, one texel of cloud and
/// one of clear sky over 4096 x 2048 (a period of about 19 km at 10 N).
fn striped_cover(dir: &Path) -> PathBuf {
    let cover = dir.join("striped.png");
    image::GrayImage::from_fn(4096, 2048, |x, _| {
        image::Luma([if x % 2 == 0 { 255 } else { 0 }])
    })
    .save(&cover)
    .unwrap();
    cover
}

#[test]
fn under_a_deck_with_gaps_the_air_lies_in_its_shadow_for_the_methods_and_the_path_tracer() {
    // From 1 km, 3 degrees below the horizon towards the sun 30 degrees up: 15 to 20 km
    // of air below a deck at 2 km in stripes, the ray meeting no cloud.
    let (dir, csv, _) = inputs("1000,93,60,0\n");
    let cover = striped_cover(dir.path());
    let mut clouds = vec![
        "--clouds",
        "--cloud-cover",
        cover.to_str().unwrap(),
        "--cloud-base-m",
        "2000",
        "--cloud-thickness-m",
        "1000",
    ];
    clouds.extend(PLACE);
    let with = |more: &[&'static str]| {
        let mut flags = clouds.clone();
        flags.extend(more);
        flags
    };
    let (header, shaded) = probe("hillaire", &csv, &with(&[]));
    let (_, lit) = probe("hillaire", &csv, &with(&["--cloud-shafts", "false"]));
    let (traced_header, traced) = probe("reference", &csv, &with(&["--target-error", "0.05"]));
    let (_, traced_lit) = probe(
        "reference",
        &csv,
        &with(&["--target-error", "0.05", "--cloud-shafts", "false"]),
    );
    assert_eq!(shaded[0][column(&header, "T_cloud")], 1.0);
    assert_eq!(traced[0][column(&traced_header, "paths")], 0.0);
    for nm in ["680", "550", "440"] {
        let l = format!("L_{nm}");
        let (map, direct) = (
            shaded[0][column(&header, &l)],
            traced[0][column(&traced_header, &l)],
        );
        let (plain, plain_traced) = (
            lit[0][column(&header, &l)],
            traced_lit[0][column(&traced_header, &l)],
        );
        println!("{nm} nm: lit {plain:.5}, the map's shadow {map:.5}, the field's {direct:.5}");
        // Without the shadow both answer the model's air alone.
        assert_eq!(plain, plain_traced, "{nm} nm");
        // The stripes' shadow takes a visible share of the air's light...
        assert!(
            map < 0.97 * plain,
            "{nm} nm: {map} against {plain} unshaded"
        );
        // ...and the frames' map (1.6 km cells, 16 steps) gives the field's own within
        // a few per cent of what the shadow takes.
        let loss = plain - direct;
        assert!(
            (map - direct).abs() < 0.1 * loss,
            "{nm} nm: map {map}, field {direct}, unshaded {plain}"
        );
    }
}

#[test]
fn bad_cloud_flags_are_named() {
    let (_dir, csv, _cover) = inputs("0,20,40,180\n");
    let csv = csv.to_str().unwrap();
    let base = ["probe", "--model", "hillaire", "--input", csv];
    let with = |more: &[&'static str]| {
        let mut args = base.to_vec();
        args.extend(more);
        args
    };
    let place = PLACE;
    atmos_fails_with(
        &with(&["--clouds"]),
        "--clouds needs --latitude-deg, --longitude-deg and --sun-azimuth-deg",
    );
    atmos_fails_with(&with(&place), "neither is given");
    let mut dense = vec!["--clouds", "--cloud-density", "2"];
    dense.extend(place);
    atmos_fails_with(&with(&dense), "--cloud-density 2 must lie in [0, 1]");
    let mut method = vec!["--clouds", "--cloud-method", "slices"];
    method.extend(place);
    atmos_fails_with(&with(&method), "--cloud-method");
    let mut traced = vec!["probe", "--model", "reference", "--input", csv, "--clouds"];
    traced.extend(place);
    traced.extend(["--target-error", "0.9"]);
    atmos_fails_with(&traced, "--target-error 0.9 must lie in [1e-4, 0.5]");
    let mut both = vec!["--clouds", "--terrain"];
    both.extend(place);
    atmos_fails_with(&with(&both), "--clouds and --terrain together");
}
