//! Running the real `atmos` binary from the end-to-end tests.

pub mod skip;

use std::process::{Command, Output};

use skip::record_skip;

/// Runs `atmos` with these arguments and waits for it.
pub fn atmos(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_atmos"))
        .args(args)
        .output()
        .expect("the atmos binary runs")
}

/// What the run wrote to stderr.
pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Runs `atmos` with these arguments and asserts that it fails with `expected` in its
/// stderr; returns the run for the caller's further checks (exit code, stdout).
#[allow(dead_code)] // Not every test binary checks failures.
pub fn atmos_fails_with(args: &[&str], expected: &str) -> Output {
    let output = atmos(args);
    let message = stderr(&output);
    assert!(!output.status.success(), "{args:?} succeeded");
    assert!(message.contains(expected), "{args:?}: {message}");
    output
}

/// Whether a GPU run failed for want of an adapter where `ATMOS_SKIP_GPU_TESTS=1` allows
/// that (then the skip is recorded, [`record_skip`]). Any other failure is the caller's
/// to assert.
#[allow(dead_code)] // Not every test binary runs the GPU.
pub fn skipped_without_adapter(output: &Output) -> bool {
    let err = stderr(output);
    let skipped =
        !output.status.success() && err.contains("no GPU adapter") && gpu_tests_may_skip();
    if skipped {
        record_skip(&format!("ATMOS_SKIP_GPU_TESTS=1 and {}", err.trim()));
    }
    skipped
}

/// Whether `ATMOS_SKIP_GPU_TESTS=1` lets GPU tests skip where the machine lacks what they
/// need (they fail otherwise).
#[allow(dead_code)] // Not every test binary runs the GPU.
pub fn gpu_tests_may_skip() -> bool {
    std::env::var("ATMOS_SKIP_GPU_TESTS").as_deref() == Ok("1")
}
