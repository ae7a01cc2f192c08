//! `atmos phase` for rain and ice crystals end to end: the CSV's columns, Q_ext = 2 for
//! crystals, unit integrals, stability at the ends of every range (drop radius 0.1 um to
//! 5 mm, rain rate 200 mm/h, aspect ratios 0.01 and 100, the sun on the horizon and
//! overhead), and every flag a particle does not take or needs named.

mod common;

use std::f64::consts::PI;
use std::path::Path;

use common::{atmos, atmos_fails_with, stderr};

/// The header's Q_ext, Q_sca, g per wavelength, and the rows.
fn read(path: &Path) -> (Vec<[f64; 3]>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut headers = Vec::new();
    let mut rows = Vec::new();
    for line in text.lines() {
        if line.starts_with("# wavelength_nm=") {
            let get = |key: &str| -> f64 {
                line.split_whitespace()
                    .find_map(|kv| kv.strip_prefix(key))
                    .unwrap()
                    .parse()
                    .unwrap()
            };
            headers.push([get("Q_ext="), get("Q_sca="), get("g=")]);
        } else if !line.starts_with('#') && !line.starts_with("angle_deg") {
            rows.push(line.split(',').map(|v| v.parse().unwrap()).collect());
        }
    }
    (headers, rows)
}

/// 2 pi int p f sin(theta) d theta by the trapezoid rule on the rows' angles.
fn sphere_integral(rows: &[Vec<f64>], column: usize, f: impl Fn(f64) -> f64) -> f64 {
    rows.windows(2)
        .map(|w| {
            let (a, b) = (w[0][0].to_radians(), w[1][0].to_radians());
            let g = |r: &Vec<f64>, t: f64| r[column] * f(t) * t.sin();
            0.5 * (b - a) * (g(&w[0], a) + g(&w[1], b))
        })
        .sum::<f64>()
        * 2.0
        * PI
}

fn phase(path: &Path, args: &[&str]) -> (Vec<[f64; 3]>, Vec<Vec<f64>>) {
    let mut all = vec!["phase", "--output", path.to_str().unwrap()];
    all.extend(args);
    let run = atmos(&all);
    assert!(run.status.success(), "{}", stderr(&run));
    read(path)
}

#[test]
fn crystals_have_q_ext_two_unit_integrals_and_their_header_g() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ice.csv");
    let cases: [&[&str]; 5] = [
        &[
            "--particle",
            "ice-column",
            "--radius-um",
            "20",
            "--length-um",
            "40",
        ],
        // Aspect ratios 0.01 and 100.
        &[
            "--particle",
            "ice-plate",
            "--radius-um",
            "100",
            "--length-um",
            "2",
        ],
        &[
            "--particle",
            "ice-column",
            "--radius-um",
            "5",
            "--length-um",
            "1000",
        ],
        // Oriented plates with the sun on the horizon and overhead.
        &[
            "--particle",
            "ice-plate",
            "--radius-um",
            "50",
            "--length-um",
            "10",
            "--horizontal",
            "--sun-elevation-deg",
            "0",
        ],
        &[
            "--particle",
            "ice-plate",
            "--radius-um",
            "50",
            "--length-um",
            "10",
            "--horizontal",
            "--sun-elevation-deg",
            "90",
            "--tilt-deg",
            "0",
        ],
    ];
    for case in cases {
        let mut args = case.to_vec();
        args.extend(["--rays", "20000", "--angles-deg", "0:180:0.05"]);
        let (headers, rows) = phase(&path, &args);
        assert_eq!(headers.len(), 3);
        for (i, [q_ext, q_sca, g]) in headers.into_iter().enumerate() {
            assert_eq!(q_ext, 2.0);
            assert!(q_sca <= 2.0 && q_sca > 1.99, "{case:?}: {q_sca}");
            assert!(rows.iter().all(|r| r[i + 1].is_finite() && r[i + 1] >= 0.0));
            // The CSV reads 0.1 degree bins at 0.05 degree steps, linearly between
            // bin centres: its integrals follow the table's to the interpolation.
            let total = sphere_integral(&rows, i + 1, |_| 1.0);
            assert!((total - 1.0).abs() < 2e-2, "{case:?}: {total}");
            let mean_cosine = sphere_integral(&rows, i + 1, f64::cos);
            assert!(
                (mean_cosine - g).abs() < 2e-2,
                "{case:?}: {mean_cosine} vs {g}"
            );
        }
    }
}

#[test]
fn drops_from_a_tenth_of_a_micrometre_to_five_millimetres_stay_finite() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("drops.csv");
    for radius in ["0.1", "5000"] {
        let args = [
            "--particle",
            "water",
            "--radius-um",
            radius,
            "--angles-deg",
            "0:180:1",
        ];
        let (headers, rows) = phase(&path, &args);
        for [q_ext, q_sca, g] in headers {
            assert!(q_ext.is_finite() && q_sca > 0.0 && q_sca <= q_ext && g.abs() < 1.0);
        }
        assert!(rows.iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
    }
}

#[test]
fn a_cloudburst_of_two_hundred_millimetres_an_hour_settles() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rain.csv");
    let args = [
        "--particle",
        "rain",
        "--rain-rate-mm-h",
        "200",
        "--wavelengths",
        "700",
        "--angles-deg",
        "0:180:10",
    ];
    let (headers, rows) = phase(&path, &args);
    let [q_ext, q_sca, g] = headers[0];
    // Drops of 0.1 to 3 mm: Q_ext just above 2, strongly forward.
    assert!(
        q_ext > 2.0 && q_ext < 2.02 && q_sca <= q_ext && g > 0.85,
        "{q_ext} {g}"
    );
    assert!(rows.iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
}

#[test]
fn flags_a_particle_does_not_take_or_needs_are_named() {
    let cases: [(&[&str], &str); 13] = [
        (&["--particle", "rain"], "--rain-rate-mm-h is required"),
        (
            &["--particle", "rain", "--rain-rate-mm-h", "0"],
            "rain rate (mm/h) = 0",
        ),
        (
            &["--particle", "rain", "--rain-rate-mm-h", "301"],
            "[0.1, 300]",
        ),
        (
            &[
                "--particle",
                "rain",
                "--rain-rate-mm-h",
                "5",
                "--radius-um",
                "3",
            ],
            "--radius-um does not apply to --particle rain",
        ),
        (
            &[
                "--particle",
                "water",
                "--radius-um",
                "3",
                "--rain-rate-mm-h",
                "5",
            ],
            "--rain-rate-mm-h does not apply",
        ),
        (
            &["--particle", "ice-column", "--radius-um", "3"],
            "--length-um is required",
        ),
        (
            &[
                "--particle",
                "ice-plate",
                "--radius-um",
                "100",
                "--length-um",
                "1",
            ],
            "aspect ratio",
        ),
        (
            &[
                "--particle",
                "ice-column",
                "--radius-um",
                "3",
                "--length-um",
                "3",
                "--horizontal",
            ],
            "--horizontal does not apply",
        ),
        (
            &[
                "--particle",
                "ice-plate",
                "--radius-um",
                "30",
                "--length-um",
                "3",
                "--horizontal",
            ],
            "--sun-elevation-deg is required",
        ),
        (
            &[
                "--particle",
                "ice-plate",
                "--radius-um",
                "30",
                "--length-um",
                "3",
                "--sun-elevation-deg",
                "10",
            ],
            "--sun-elevation-deg does not apply",
        ),
        (
            &[
                "--particle",
                "ice-plate",
                "--radius-um",
                "30",
                "--length-um",
                "3",
                "--horizontal",
                "--sun-elevation-deg",
                "10",
                "--tilt-deg",
                "40",
            ],
            "tilt spread 40",
        ),
        (
            &[
                "--particle",
                "ice-column",
                "--radius-um",
                "3",
                "--length-um",
                "3",
                "--rays",
                "10",
            ],
            "rays 10",
        ),
        (
            &[
                "--particle",
                "ice-column",
                "--radius-um",
                "3",
                "--length-um",
                "3",
                "--wavelengths",
                "1200",
            ],
            "Warren and Brandt 2008",
        ),
    ];
    for (extra, message) in cases {
        let mut args = vec!["phase"];
        args.extend(extra);
        atmos_fails_with(&args, message);
    }
}
