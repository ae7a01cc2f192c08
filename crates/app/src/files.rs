//! Writing output: files written so that an interrupted run never leaves a half-written
//! one, through symbolic links to the file they name and never over anything but a
//! regular file; and standard output whose reader may go away.

use std::fs;
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};

/// The most symbolic links followed from an output path (Linux's own limit, MAXSYMLINKS).
const MAX_LINKS: usize = 40;

/// Whether `err` comes from writing to a pipe whose reader has gone (`atmos stability |
/// head -1`): the command has nothing left to say, and exits quietly.
pub fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == ErrorKind::BrokenPipe)
    })
}

/// The file an atomic write of `target` goes through before it is renamed into place.
fn partial_path(target: &Path) -> PathBuf {
    let mut partial = target.as_os_str().to_owned();
    partial.push(".partial");
    PathBuf::from(partial)
}

/// What kind of thing `kind` is, for an error that refuses to write over it.
fn kind_name(kind: fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_char_device() {
            return "a character device";
        }
        if kind.is_block_device() {
            return "a block device";
        }
        if kind.is_fifo() {
            return "a named pipe";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    if kind.is_dir() {
        "a folder"
    } else {
        "something other than a regular file"
    }
}

/// The file a write of `path` replaces: `path` itself, or the file its symbolic links
/// lead to, which need not exist yet (a dangling link is written through), but whose
/// folder must. Anything that is not a regular file is refused, as are a process's open
/// files (`/dev/stdout` even when it is redirected to a file, as replacing that file
/// would lose what `>>` appends to) and `-` (standard output is not a file here).
fn write_target(path: &Path) -> anyhow::Result<PathBuf> {
    if path.as_os_str() == "-" {
        bail!(
            "'-' is not a file name here: a command writes standard output when its output \
             flag is left out (probe, bench), and otherwise needs a file"
        );
    }
    // The kernel follows every link, `/proc`'s too (`/dev/stdout` to a pipe or a terminal).
    match fs::metadata(path) {
        Ok(meta) if !meta.is_file() => {
            let what = match fs::read_link(path).and_then(|_| fs::canonicalize(path)) {
                Ok(target) => format!("it links to {}, which", target.display()),
                Err(_) => "it".to_string(),
            };
            bail!(
                "{what} is {}, not a file atmos may replace",
                kind_name(meta.file_type())
            )
        }
        Ok(_) => {}
        Err(e) if e.kind() == ErrorKind::NotFound => {}
        // A loop of links, a folder that may not be searched: the system says which.
        Err(e) => return Err(e.into()),
    }
    let mut target = path.to_owned();
    for _ in 0..=MAX_LINKS {
        let is_link = fs::symlink_metadata(&target).is_ok_and(|m| m.file_type().is_symlink());
        if !is_link {
            let folder = target.parent().filter(|f| !f.as_os_str().is_empty());
            if target != path && folder.is_some_and(|f| !f.is_dir()) {
                bail!(
                    "it links to {}, whose folder does not exist",
                    target.display()
                );
            }
            return Ok(target);
        }
        if target.starts_with("/proc") || target.starts_with("/dev/fd") {
            bail!(
                "it leads to {}, a file a process has open, not a file atmos may replace",
                target.display()
            );
        }
        let next = fs::read_link(&target)
            .with_context(|| format!("cannot read the link {}", target.display()))?;
        target = match target.parent() {
            Some(folder) => folder.join(next),
            None => next,
        };
    }
    bail!("it is a chain of more than {MAX_LINKS} symbolic links (a loop?)")
}

/// Creates the `.partial` file beside `target`, replacing a stale one (never writing
/// through it, should it be a link).
fn create_partial(target: &Path) -> std::io::Result<(PathBuf, fs::File)> {
    let partial = partial_path(target);
    match fs::remove_file(&partial) {
        Err(e) if e.kind() != ErrorKind::NotFound => return Err(e),
        _ => {}
    }
    let file = fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&partial)?;
    Ok((partial, file))
}

/// Checks, before any work, that `path` can be written: it (or the file its links name)
/// is a regular file or absent, and a `.partial` file can be created beside it and is
/// removed again, so a missing or read-only folder or a device is named at once rather
/// than after a long render.
pub fn check_writable(path: &Path) -> anyhow::Result<()> {
    let context = || format!("cannot write {}", path.display());
    let target = write_target(path).with_context(context)?;
    let (partial, _) = create_partial(&target).with_context(context)?;
    fs::remove_file(&partial).with_context(context)
}

/// Writes `contents` to `path` through a `.partial` file renamed into place; a link
/// stays a link, its target gets the contents (and keeps its permissions).
pub fn write_atomically(path: &Path, contents: &[u8]) -> anyhow::Result<()> {
    let context = || format!("cannot write {}", path.display());
    let target = write_target(path).with_context(context)?;
    let (partial, mut file) = create_partial(&target).with_context(context)?;
    let result = file
        .write_all(contents)
        .and_then(|()| match fs::metadata(&target) {
            Ok(existing) => file.set_permissions(existing.permissions()),
            Err(e) if e.kind() == ErrorKind::NotFound => Ok(()),
            Err(e) => Err(e),
        })
        .and_then(|()| file.sync_all())
        .and_then(|()| fs::rename(&partial, &target));
    if result.is_err() {
        // Best effort: the rename may have failed after the file was written.
        let _ = fs::remove_file(&partial);
    }
    result.with_context(context)
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::os::unix::fs::symlink;

    fn error_of(result: anyhow::Result<()>) -> String {
        format!("{:#}", result.unwrap_err())
    }

    #[test]
    fn a_plain_file_is_replaced_and_no_partial_is_left() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.csv");
        fs::write(&path, "old").unwrap();
        check_writable(&path).unwrap();
        write_atomically(&path, b"new").unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "new");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_link_stays_a_link_and_its_target_gets_the_contents() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("data/real.csv");
        fs::create_dir(dir.path().join("data")).unwrap();
        fs::write(&target, "old").unwrap();
        let link = dir.path().join("link.csv");
        symlink("data/real.csv", &link).unwrap();
        check_writable(&link).unwrap();
        write_atomically(&link, b"new").unwrap();
        assert!(
            fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(fs::read_to_string(&target).unwrap(), "new");
        // The partial file went beside the target and was renamed onto it.
        assert_eq!(fs::read_dir(dir.path().join("data")).unwrap().count(), 1);
    }

    #[test]
    fn a_chain_of_links_is_followed_to_its_end() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("real.csv");
        fs::write(&target, "old").unwrap();
        symlink(&target, dir.path().join("b")).unwrap();
        symlink("b", dir.path().join("a")).unwrap();
        write_atomically(&dir.path().join("a"), b"new").unwrap();
        assert_eq!(fs::read_to_string(&target).unwrap(), "new");
        for name in ["a", "b"] {
            let meta = fs::symlink_metadata(dir.path().join(name)).unwrap();
            assert!(meta.file_type().is_symlink(), "{name}");
        }
    }

    #[test]
    fn a_dangling_link_creates_its_target() {
        let dir = tempfile::tempdir().unwrap();
        let link = dir.path().join("link.csv");
        symlink("made.csv", &link).unwrap();
        check_writable(&link).unwrap();
        write_atomically(&link, b"new").unwrap();
        assert_eq!(
            fs::read_to_string(dir.path().join("made.csv")).unwrap(),
            "new"
        );
        assert!(
            fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
    }

    #[test]
    fn a_link_into_a_missing_folder_names_both() {
        let dir = tempfile::tempdir().unwrap();
        let link = dir.path().join("link.csv");
        symlink("missing/made.csv", &link).unwrap();
        let e = error_of(check_writable(&link));
        let expected = format!(
            "cannot write {}: it links to {}, whose folder does not exist",
            link.display(),
            dir.path().join("missing/made.csv").display()
        );
        assert_eq!(e, expected);
        assert!(error_of(write_atomically(&link, b"x")).contains("folder does not exist"));
    }

    #[test]
    fn a_loop_of_links_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        symlink("b", dir.path().join("a")).unwrap();
        symlink("a", dir.path().join("b")).unwrap();
        let e = error_of(write_atomically(&dir.path().join("a"), b"x"));
        assert!(e.contains("Too many levels of symbolic links"), "{e}");
    }

    /// Nothing here can replace a device even if the checks broke: only the check (which
    /// at worst makes and removes `/dev/null.partial`) sees `/dev/null` itself, and the
    /// writes go to links and pipes in a temporary folder.
    #[test]
    fn devices_folders_and_pipes_are_refused_untouched() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(
            error_of(check_writable(Path::new("/dev/null"))),
            "cannot write /dev/null: it is a character device, not a file atmos may replace"
        );
        let e = error_of(write_atomically(dir.path(), b"x"));
        assert!(
            e.ends_with("it is a folder, not a file atmos may replace"),
            "{e}"
        );
        // A link to a device names both, at the check and at the write.
        let link = dir.path().join("null");
        symlink("/dev/null", &link).unwrap();
        let expected = format!(
            "cannot write {}: it links to /dev/null, which is a character device, \
             not a file atmos may replace",
            link.display()
        );
        assert_eq!(error_of(check_writable(&link)), expected);
        assert_eq!(error_of(write_atomically(&link, b"x")), expected);
        assert!(
            fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        let fifo = dir.path().join("fifo");
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(made.success());
        for e in [check_writable(&fifo), write_atomically(&fifo, b"x")] {
            let e = error_of(e);
            assert!(
                e.ends_with("it is a named pipe, not a file atmos may replace"),
                "{e}"
            );
        }
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 2);
        assert!(!Path::new("/dev/null.partial").exists());
    }

    #[test]
    fn a_dash_is_not_a_file() {
        let e = error_of(check_writable(Path::new("-")));
        assert!(e.contains("'-' is not a file name here"), "{e}");
    }

    #[test]
    fn replacing_keeps_the_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("private.csv");
        fs::write(&path, "old").unwrap();
        fs::set_permissions(&path, fs::Permissions::from_mode(0o600)).unwrap();
        write_atomically(&path, b"new").unwrap();
        let mode = fs::metadata(&path).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o600);
    }

    #[test]
    fn a_stale_partial_link_is_not_written_through() {
        let dir = tempfile::tempdir().unwrap();
        let victim = dir.path().join("victim");
        fs::write(&victim, "keep").unwrap();
        symlink(&victim, dir.path().join("out.csv.partial")).unwrap();
        write_atomically(&dir.path().join("out.csv"), b"new").unwrap();
        assert_eq!(fs::read_to_string(&victim).unwrap(), "keep");
        assert_eq!(
            fs::read_to_string(dir.path().join("out.csv")).unwrap(),
            "new"
        );
    }
}
