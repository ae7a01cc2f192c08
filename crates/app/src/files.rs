//! Writing output: files written so that an interrupted run never leaves a half-written
//! one, and standard output whose reader may go away.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;

/// Whether `err` comes from writing to a pipe whose reader has gone (`atmos stability |
/// head -1`): the command has nothing left to say, and exits quietly.
pub fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

/// The file an atomic write of `path` goes through before it is renamed into place.
fn partial_path(path: &Path) -> PathBuf {
    let mut partial = path.as_os_str().to_owned();
    partial.push(".partial");
    PathBuf::from(partial)
}

/// Checks, before any work, that `path` can be written: its `.partial` file is created in
/// the output's folder and removed again, so a missing or read-only folder is named at
/// once rather than after a long render.
pub fn check_writable(path: &Path) -> anyhow::Result<()> {
    let partial = partial_path(path);
    fs::File::create(&partial).with_context(|| format!("cannot write {}", path.display()))?;
    fs::remove_file(&partial).with_context(|| format!("cannot write {}", path.display()))
}

/// Writes `contents` to `path` through a `.partial` file renamed into place.
pub fn write_atomically(path: &Path, contents: &[u8]) -> anyhow::Result<()> {
    let partial = partial_path(path);
    let result = fs::File::create(&partial)
        .and_then(|mut f| f.write_all(contents).and_then(|()| f.sync_all()))
        .and_then(|()| fs::rename(&partial, path));
    if result.is_err() {
        // Best effort: the file may never have been created.
        let _ = fs::remove_file(&partial);
    }
    result.with_context(|| format!("cannot write {}", path.display()))
}
