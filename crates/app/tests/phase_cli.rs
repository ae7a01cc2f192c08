//! `atmos phase` end to end: the CSV it writes has unit-integral phase functions whose
//! mean cosine is the g of its header, and every bad flag is refused with a message
//! naming it.

mod common;

use std::f64::consts::PI;
use std::path::Path;

use common::{atmos, atmos_fails_with, stderr};

/// The header's key=value pairs of each wavelength, the column names and the rows.
struct Csv {
    wavelengths: Vec<Vec<(String, String)>>,
    columns: Vec<String>,
    rows: Vec<Vec<f64>>,
}

fn read_csv(path: &Path) -> Csv {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let mut wavelengths = Vec::new();
    let mut columns = Vec::new();
    for line in lines.by_ref() {
        if let Some(comment) = line.strip_prefix("# wavelength_nm=") {
            let pairs = format!("wavelength_nm={comment}")
                .split_whitespace()
                .map(|kv| {
                    let (k, v) = kv.split_once('=').unwrap();
                    (k.to_string(), v.to_string())
                })
                .collect();
            wavelengths.push(pairs);
        } else if !line.starts_with('#') {
            columns = line.split(',').map(str::to_string).collect();
            break;
        }
    }
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    Csv {
        wavelengths,
        columns,
        rows,
    }
}

fn value(pairs: &[(String, String)], key: &str) -> f64 {
    pairs
        .iter()
        .find(|(k, _)| k == key)
        .unwrap()
        .1
        .parse()
        .unwrap()
}

/// 2 pi times the integral of p(theta) f(theta) sin(theta) d theta over the rows by
/// Simpson's rule (an even number of equal steps).
fn sphere_integral(rows: &[Vec<f64>], column: usize, f: impl Fn(f64) -> f64) -> f64 {
    let h = (rows[1][0] - rows[0][0]).to_radians();
    let last = rows.len() - 1;
    assert_eq!(last % 2, 0);
    let sum: f64 = rows
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let theta = row[0].to_radians();
            let weight = if i == 0 || i == last {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            weight * row[column] * f(theta) * theta.sin()
        })
        .sum();
    2.0 * PI * sum * h / 3.0
}

fn phase_to(path: &Path, extra: &[&str]) {
    let mut args = vec![
        "phase",
        "--particle",
        "water",
        "--output",
        path.to_str().unwrap(),
    ];
    args.extend(extra);
    let run = atmos(&args);
    assert!(run.status.success(), "{}", stderr(&run));
}

#[test]
fn one_radius_is_normalised_and_its_header_g_is_the_mean_cosine() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("phase.csv");
    phase_to(&path, &["--radius-um", "0.5", "--angles-deg", "0:180:0.05"]);
    let csv = read_csv(&path);
    assert_eq!(csv.columns, ["angle_deg", "p_680", "p_550", "p_440"]);
    assert_eq!(csv.rows.len(), 3601);
    assert_eq!(csv.rows[3600][0], 180.0);
    assert_eq!(csv.wavelengths.len(), 3);
    for (i, pairs) in csv.wavelengths.iter().enumerate() {
        let (q_ext, q_sca, g) = (
            value(pairs, "Q_ext"),
            value(pairs, "Q_sca"),
            value(pairs, "g"),
        );
        // Water barely absorbs: Q_ext just above Q_sca; x = 4.6 to 7.1, past the first
        // extinction maximum.
        assert!(q_ext >= q_sca && q_ext - q_sca < 1e-6 && (1.5..4.5).contains(&q_ext));
        let total = sphere_integral(&csv.rows, i + 1, |_| 1.0);
        assert!((total - 1.0).abs() < 1e-6, "column {i}: {total}");
        let mean_cosine = sphere_integral(&csv.rows, i + 1, f64::cos);
        assert!(
            (mean_cosine - g).abs() < 1e-6,
            "column {i}: {mean_cosine} vs {g}"
        );
    }
    assert_eq!(value(&csv.wavelengths[1], "m_re"), 1.333);
}

#[test]
fn a_distribution_and_a_given_refractive_index_are_honoured() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cloud.csv");
    phase_to(
        &path,
        &[
            "--radius-um",
            "2",
            "--distribution",
            "lognormal:0.2",
            "--refractive-index",
            "1.5+0.01i",
            "--wavelengths",
            "550",
            "--angles-deg",
            "0:180:0.02",
        ],
    );
    let csv = read_csv(&path);
    let pairs = &csv.wavelengths[0];
    assert_eq!((value(pairs, "m_re"), value(pairs, "m_im")), (1.5, 0.01));
    assert!(value(pairs, "radii") > 64.0);
    // Absorption: Q_ext clearly above Q_sca.
    assert!(value(pairs, "Q_ext") - value(pairs, "Q_sca") > 0.05);
    let total = sphere_integral(&csv.rows, 1, |_| 1.0);
    assert!((total - 1.0).abs() < 1e-5, "{total}");
    let mean_cosine = sphere_integral(&csv.rows, 1, f64::cos);
    assert!((mean_cosine - value(pairs, "g")).abs() < 1e-5);
}

#[test]
fn stdout_without_output() {
    let run = atmos(&[
        "phase",
        "--particle",
        "water",
        "--radius-um",
        "1",
        "--wavelengths",
        "550",
        "--angles-deg",
        "0:180:90",
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = String::from_utf8(run.stdout).unwrap();
    assert!(
        text.contains("\nangle_deg,p_550\n0,") && text.contains("\n180,"),
        "{text}"
    );
}

#[test]
fn bad_flags_are_named() {
    let base = ["phase", "--particle", "water"];
    let cases: [(&[&str], &str); 12] = [
        (&["--radius-um", "0"], "outside (0, 10000] um"),
        (&["--radius-um", "-3"], "outside (0, 10000] um"),
        (&["--radius-um", "20000"], "outside (0, 10000] um"),
        (
            &["--radius-um", "1", "--distribution", "lognormal:3"],
            "lognormal sigma",
        ),
        (
            &["--radius-um", "1", "--distribution", "weibull:3"],
            "not lognormal:SIGMA",
        ),
        (&["--radius-um", "1", "--angles-deg", "0:190:1"], "[0, 180]"),
        (
            &["--radius-um", "1", "--angles-deg", "0:180:0"],
            "STEP must be above 0",
        ),
        (
            &["--radius-um", "1", "--angles-deg", "0:180:1e-6"],
            "at most 2000000",
        ),
        (
            &["--radius-um", "1", "--refractive-index", "1.3x"],
            "not a refractive index",
        ),
        (
            &["--radius-um", "1", "--wavelengths", "1500"],
            "200 to 1000 nm",
        ),
        (
            &[
                "--radius-um",
                "1",
                "--wavelengths",
                "-5",
                "--refractive-index",
                "1.3",
            ],
            "not a positive wavelength",
        ),
        (
            &[
                "--radius-um",
                "9000",
                "--wavelengths",
                "50",
                "--refractive-index",
                "1.3",
            ],
            "size parameter",
        ),
    ];
    for (extra, message) in cases {
        let args: Vec<&str> = base.iter().chain(extra).copied().collect();
        atmos_fails_with(&args, message);
    }
}

#[test]
fn work_past_the_budget_is_refused_before_it_starts() {
    atmos_fails_with(
        &[
            "phase",
            "--particle",
            "water",
            "--radius-um",
            "5000",
            "--distribution",
            "lognormal:1",
            "--angles-deg",
            "0:180:0.001",
        ],
        "term evaluations",
    );
}

#[test]
fn an_output_folder_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    atmos_fails_with(
        &[
            "phase",
            "--particle",
            "water",
            "--radius-um",
            "1",
            "--output",
            dir.path().to_str().unwrap(),
        ],
        "is a folder",
    );
}

mod parsers {
    use atmos::phase::flags::{
        MAX_ANGLES, parse_angles, parse_distribution, parse_radius_um, parse_refractive_index,
    };
    use proptest::prelude::*;

    /// Text made of the characters these flags are written with, and numbers that break
    /// careless handling.
    fn flag_text() -> impl Strategy<Value = String> {
        prop_oneof![
            "[-+0-9.eEij:,a-z]{0,24}",
            prop::sample::select(vec![
                "nan",
                "inf",
                "-inf",
                "1e309",
                "-0",
                "0:180:1e-300",
                "0:nan:1",
                "lognormal:nan",
                "modified-gamma:inf,1",
                "1e308+1e308i",
                "+i",
                "-i",
                "e-5i",
            ])
            .prop_map(str::to_string),
        ]
    }

    proptest! {
        /// No phase flag parser panics; what they accept lies in the documented ranges.
        #[test]
        fn phase_flag_parsers_never_panic(text in flag_text()) {
            if let Ok(r) = parse_radius_um(&text) {
                prop_assert!(r > 0.0 && r <= 10_000.0);
            }
            if let Ok(a) = parse_angles(&text) {
                prop_assert!(a.count >= 1 && a.count <= MAX_ANGLES);
                prop_assert!(a.angles_deg().all(|x| (0.0..=180.0 + 1e-9).contains(&x)));
            }
            if let Ok(m) = parse_refractive_index(&text) {
                prop_assert!(m.re > 0.0 && m.re <= 10.0 && (0.0..=10.0).contains(&m.im));
            }
            let _ = parse_distribution(&text);
        }
    }
}
