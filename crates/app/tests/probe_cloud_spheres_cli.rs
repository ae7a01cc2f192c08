//! `atmos probe --clouds --cloud-form`: rays from orbit answered by the cloud spheres
//! (Dobashi et al. 2002 section 5.4) and by the layer's march over the same field, and
//! the blend of the two in the hand-over band.

mod common;

use std::path::Path;

use common::{atmos, atmos_fails_with, stderr};

/// Three rays from 400 km into a deck (sun 40 and 60 degrees from the zenith), and one
/// from 75 km, the middle of the hand-over band.
const RAYS: &str = "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg\n\
                    400000,150,40,90\n400000,160,40,180\n400000,140,60,30\n75000,150,40,90\n";

/// The probe's rows of numbers and the index of `T_cloud`, in `form`.
fn probe(dir: &Path, form: &str) -> (Vec<Vec<f64>>, usize) {
    let csv = dir.join("rays.csv");
    let cover = dir.join("cover.png");
    let args = [
        "probe",
        "--model",
        "hillaire",
        "--input",
        csv.to_str().unwrap(),
        "--clouds",
        "--cloud-cover",
        cover.to_str().unwrap(),
        "--cloud-density",
        "0.002",
        "--cloud-method",
        "octaves",
        "--cloud-form",
        form,
        "--latitude-deg",
        "10",
        "--longitude-deg",
        "20",
        "--sun-azimuth-deg",
        "90",
    ];
    let output = atmos(&args);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8(output.stdout).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let t_cloud = header.iter().position(|h| *h == "T_cloud").unwrap();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (rows, t_cloud)
}

#[test]
fn from_orbit_the_spheres_answer_as_the_layer_and_auto_blends_them() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("rays.csv"), RAYS).unwrap();
    // A uniform cover of 0.8, the hand-over test's deck.
    image::RgbaImage::from_pixel(8, 4, image::Rgba([204, 204, 204, 255]))
        .save(dir.path().join("cover.png"))
        .unwrap();
    let (spheres, t) = probe(dir.path(), "spheres");
    let (layer, _) = probe(dir.path(), "layer");
    let (auto, _) = probe(dir.path(), "auto");
    // L_680, L_550, L_440 follow the four input columns.
    let radiance = 4..7;
    for k in 0..3 {
        // The rays see cloud: a third or less of the light behind comes through.
        assert!(spheres[k][t] < 0.35 && layer[k][t] < 0.35, "ray {k}");
        // The hand-over test's tolerance (tests/cloud_spheres_handover.rs: 3 % with 5
        // spheres); the transmittance within 0.03, since the spheres carry the mean of
        // the detail noise the march reads point by point.
        for w in radiance.clone() {
            let (s, l) = (spheres[k][w], layer[k][w]);
            assert!(
                (s / l - 1.0).abs() < 0.03,
                "ray {k} column {w}: {s} against {l}"
            );
        }
        assert!(
            (spheres[k][t] - layer[k][t]).abs() < 0.03,
            "ray {k} T_cloud"
        );
        // Above the band, auto is the spheres bit for bit.
        assert_eq!(auto[k], spheres[k], "ray {k}");
    }
    // At 75 km the spheres' weight is 1/2: auto is the mean of the two forms.
    for w in radiance.chain([t]) {
        let mean = 0.5 * (spheres[3][w] + layer[3][w]);
        assert!((auto[3][w] - mean).abs() <= 1e-12 * mean, "column {w}");
    }
    assert_ne!(spheres[3][4], layer[3][4]);
}

#[test]
fn the_path_tracer_takes_no_spheres_and_a_bad_form_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("rays.csv");
    std::fs::write(&csv, RAYS).unwrap();
    let with = |model: &'static str, form: &'static str| {
        vec![
            "probe",
            "--model",
            model,
            "--input",
            csv.to_str().unwrap(),
            "--clouds",
            "--cloud-form",
            form,
            "--latitude-deg",
            "10",
            "--longitude-deg",
            "20",
            "--sun-azimuth-deg",
            "90",
        ]
    };
    atmos_fails_with(
        &with("reference", "spheres"),
        "--cloud-form spheres: the path tracer (--model reference) traces the cloud field",
    );
    atmos_fails_with(&with("riley", "volume"), "--cloud-form");
}
