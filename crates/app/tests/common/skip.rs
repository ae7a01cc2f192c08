//! A test that skips at run time records itself, so that a skip is never counted as a
//! pass: it prints `SKIPPED` to stderr and appends `binary::test: reason` to the file
//! named by `ATMOS_SKIPPED_TESTS` (set by `scripts/test.sh`, which lists the lines and
//! counts them out of the passed tests). Shared by the app's end-to-end tests and, by
//! path, the GPU tests of `tests/tests/support`.

use std::io::Write;
use std::path::{Path, PathBuf};

/// The environment variable naming the file skips are appended to.
pub const SKIPPED_TESTS_FILE: &str = "ATMOS_SKIPPED_TESTS";

/// Records that the running test skips for `reason` in the file `ATMOS_SKIPPED_TESTS`
/// names (only on stderr where it is unset).
pub fn record_skip(reason: &str) {
    let file = std::env::var_os(SKIPPED_TESTS_FILE).map(PathBuf::from);
    record_skip_in(file.as_deref(), reason);
}

/// Records that the running test skips for `reason`: `SKIPPED binary::test: reason` on
/// stderr and, where `file` is given, the same line (less `SKIPPED`) appended whole.
pub fn record_skip_in(file: Option<&Path>, reason: &str) {
    let binary = std::env::current_exe()
        .ok()
        .and_then(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .unwrap_or_default();
    // Cargo names test binaries `<file>-<hash>`.
    let binary = binary
        .rsplit_once('-')
        .map_or(binary.as_str(), |(name, _)| name);
    // The test harness runs each test on a thread named after it.
    let thread = std::thread::current();
    let test = thread.name().unwrap_or("unnamed test");
    let reason = reason.replace('\n', " ");
    let line = format!("{binary}::{test}: {reason}");
    eprintln!("SKIPPED {line}");
    if let Some(path) = file {
        let written = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .and_then(|mut f| f.write_all(format!("{line}\n").as_bytes()));
        if let Err(e) = written {
            panic!("cannot record the skip in {}: {e}", path.display());
        }
    }
}
