//! `--out DIR`: checked before any work. A missing folder is created; a file, or a
//! folder where a frame cannot be written, is refused at once.

use std::path::Path;

use anyhow::{Context, bail};

use crate::files::check_writable;

/// Makes `dir` if it is missing and checks that `probe` (a frame's file in it) can be
/// written there.
pub fn prepare(dir: &Path, probe: &Path) -> anyhow::Result<()> {
    match std::fs::metadata(dir) {
        Ok(meta) if meta.is_dir() => {}
        Ok(_) => bail!(
            "--out {}: it is a file, not a folder (record writes one file per frame into a folder)",
            dir.display()
        ),
        Err(_) => std::fs::create_dir_all(dir)
            .with_context(|| format!("--out {}: cannot create the folder", dir.display()))?,
    }
    check_writable(probe).with_context(|| format!("--out {}", dir.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_folder_is_made_and_a_file_refused() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("a/b");
        prepare(&out, &out.join("frame_000000.png")).unwrap();
        assert!(out.is_dir());
        let file = dir.path().join("file");
        std::fs::write(&file, "x").unwrap();
        let e = format!("{:#}", prepare(&file, &file.join("f.png")).unwrap_err());
        assert!(
            e.ends_with(
                "it is a file, not a folder (record writes one file per frame into a folder)"
            ),
            "{e}"
        );
    }
}
