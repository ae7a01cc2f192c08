//! Running the real `atmos` binary from the end-to-end tests.

use std::process::{Command, Output};

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
