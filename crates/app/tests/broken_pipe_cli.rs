//! A reader that stops early (`atmos stability | head -1`) ends the command quietly: exit
//! status 0, no panic, no error on stderr.

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};

#[test]
fn a_reader_that_stops_early_ends_the_command_quietly() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_atmos"))
        .args(["stability", "--model", "oneil"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the atmos binary runs");
    let mut first = String::new();
    // The table's rows follow the sweep, after the reader has gone.
    BufReader::new(child.stdout.take().expect("piped"))
        .read_line(&mut first)
        .expect("the header line");
    let output = child.wait_with_output().expect("atmos ends");
    let err = String::from_utf8_lossy(&output.stderr);
    assert!(first.starts_with("| model | case |"), "{first}");
    assert!(output.status.success(), "{:?}: {err}", output.status);
    assert!(!err.contains("panicked") && !err.contains("error"), "{err}");
}
