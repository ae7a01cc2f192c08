//! Settings too large for memory, time or the GPU (issue 18, defect 3 and 4) end in a
//! clear error and exit code 1, quickly: never an abort, a panic, a hang or a silently
//! wrong image. Each run must end within `LIMIT`.

mod common;

use std::io::Read;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::{skipped_without_adapter, stderr};

/// How long a refused command may take.
const LIMIT: Duration = Duration::from_secs(20);

/// Runs `atmos args`, killed after [`LIMIT`] (a failure: it hung).
fn atmos_within_limit(args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_atmos"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the atmos binary runs");
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > LIMIT {
            child.kill().unwrap();
            panic!("{args:?} ran past {LIMIT:?}");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let mut err = Vec::new();
    child.stderr.take().unwrap().read_to_end(&mut err).unwrap();
    Output {
        status: child.wait().unwrap(),
        stdout: Vec::new(),
        stderr: err,
    }
}

/// Asserts that `output` failed with exit code 1 and `expected` in its message.
fn refused(args: &[&str], output: &Output, expected: &str) {
    let err = stderr(output);
    assert_eq!(output.status.code(), Some(1), "{args:?}: {err}");
    assert!(err.contains(expected), "{args:?}: {err}");
}

/// `atmos probe --model model --set ...` on one ray, refused with `expected`.
fn probe_refused(model: &str, sets: &[&str], expected: &str) {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("rays.csv");
    let rays = "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg\n0,60,30,0\n";
    std::fs::write(&input, rays).unwrap();
    let mut args = vec![
        "probe",
        "--model",
        model,
        "--input",
        input.to_str().unwrap(),
    ];
    for set in sets {
        args.extend(["--set", set]);
    }
    refused(&args, &atmos_within_limit(&args), expected);
}

/// `atmos render --model model --set ...` of a tiny frame, refused with `expected`
/// (skipped without a GPU adapter where that is allowed).
fn render_refused(model: &str, sets: &[&str], expected: &str) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sky.png");
    let mut args = vec!["render", "--model", model, "--width", "8", "--height", "6"];
    args.extend([
        "--altitude-m",
        "10",
        "--sun-zenith-deg",
        "45",
        "--view-zenith-deg",
        "80",
    ]);
    for set in sets {
        args.extend(["--set", set]);
    }
    args.extend(["--out", out.to_str().unwrap()]);
    let output = atmos_within_limit(&args);
    if skipped_without_adapter(&output) {
        return;
    }
    refused(&args, &output, expected);
    assert!(!out.exists(), "{args:?} wrote {}", out.display());
}

#[test]
fn the_issues_table_sizes_are_refused_with_the_key_and_its_range() {
    let big = ["table_heights=100000", "table_angles=100000"];
    let nishita = "nishita setting table_heights=100000 is outside 2..=2048";
    probe_refused("nishita", &big, nishita);
    let big_s = ["r=100000", "mu=100000"];
    probe_refused(
        "bruneton",
        &big_s,
        "bruneton setting r=100000 is outside 2..=256",
    );
    let big_view = ["sky_view_width=1000000", "sky_view_height=1000000"];
    let hillaire = "hillaire setting sky_view_width=1000000 is outside 2..=2048";
    probe_refused("hillaire", &big_view, hillaire);
    let samples = "nishita setting samples=1000000000 is outside 1..=4096";
    probe_refused("nishita", &["samples=1000000000"], samples);
}

#[test]
fn tables_over_the_memory_budget_are_refused_with_their_bytes() {
    let s = ["r=256", "mu=1024", "mu_s=256", "nu=64"];
    let expected = "bruneton tables of r=256 x mu=1024 x mu_s=256 x nu=64 at 3 wavelengths \
                    need 154619228160 bytes, over the budget of 1073741824 bytes";
    probe_refused("bruneton", &s, expected);
}

#[test]
fn shared_settings_are_refused_outside_their_ranges() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("rays.csv");
    let rays = "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg\n0,60,30,0\n";
    std::fs::write(&input, rays).unwrap();
    let path = input.to_str().unwrap();
    let args = [
        "probe",
        "--model",
        "reference",
        "--orders",
        "5000",
        "--input",
        path,
    ];
    refused(
        &args,
        &atmos_within_limit(&args),
        "orders 5000 is outside 1..=1000",
    );
}

#[test]
fn gpu_sample_counts_past_what_every_gpu_loops_are_refused() {
    for samples in ["262144", "1000000000"] {
        let set = format!("samples={samples}");
        let expected = format!("nishita setting {set} is outside 1..=4096");
        render_refused("nishita", &[&set], &expected);
    }
    let ambient = "dobashi setting ambient_directions=64 is outside 1..=16";
    render_refused("dobashi", &["ambient_directions=64"], ambient);
    let ground = [
        "ground_zenith_panels=16",
        "ground_azimuths=256",
        "sky_view_samples=100",
    ];
    render_refused(
        "hillaire",
        &ground,
        "= 51200 loop trips in one GPU invocation",
    );
}

#[test]
fn gpu_tables_over_the_budget_are_refused_with_the_settings() {
    let volume = ["ap_width=1024", "ap_height=1024", "ap_slices=256"];
    let expected = "hillaire aerial radiance of 1024 x 1024 x 256 texels \
                    (ap_width x ap_height x ap_slices): 4294967296 bytes, over the GPU \
                    table budget";
    render_refused("hillaire", &volume, expected);
}
