//! Tables that take seconds to minutes to build (the rain's and ice's spectral phase
//! functions, the cloud droplets' Lorenz-Mie series) kept on disk between runs. A table
//! is rows of f64, stored under a name made of its kind and a hash of its key: the key is
//! the text of every parameter that changes the table, and the file holds the key itself,
//! so that two keys with one hash are told apart. [`FORMAT_VERSION`] goes into every
//! key: it changes whenever the file's layout or a table's method changes.
//!
//! The file: the line `atmos table cache v<FORMAT_VERSION>`, the key's line, a line
//! `rows <n> <length>...`, a line `fnv1a <16 hex digits>` (the hash of the data), then the
//! data as little-endian f64, row after row, so that a table read back is the table built
//! bit for bit. Written to a temporary file in the same folder and renamed into place, so
//! that an interrupted run never leaves half a file. A file that cannot be read, or whose
//! key, layout or hash does not match, is built again with a warning; a cache that
//! cannot be written is a warning too: the table built is returned either way.

use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The version of the files' layout and of the methods of the tables they hold.
pub const FORMAT_VERSION: u32 = 1;

/// Where tables are kept, or nowhere.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TableCache {
    dir: Option<PathBuf>,
}

/// A stable 64-bit hash (FNV-1a).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &b| {
        (hash ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// The first line of every file.
fn title() -> String {
    format!("atmos table cache v{FORMAT_VERSION}")
}

/// `rows` as the file's bytes under `key`.
fn encode(key: &str, rows: &[Vec<f64>]) -> Vec<u8> {
    let data: Vec<u8> = rows
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let lengths: Vec<String> = rows.iter().map(|r| r.len().to_string()).collect();
    let mut bytes = format!(
        "{}\n{key}\nrows {} {}\nfnv1a {:016x}\n",
        title(),
        rows.len(),
        lengths.join(" "),
        fnv1a(&data)
    )
    .into_bytes();
    bytes.extend(data);
    bytes
}

/// The rows a file's `bytes` hold under `key`, or what is wrong with them.
fn decode(key: &str, bytes: &[u8]) -> Result<Vec<Vec<f64>>, String> {
    let mut rest = bytes;
    let mut line = || -> Result<String, String> {
        let end = rest
            .iter()
            .position(|&b| b == b'\n')
            .ok_or("the header is cut short")?;
        let text = std::str::from_utf8(&rest[..end])
            .map_err(|_| "the header is not text".to_string())?
            .to_string();
        rest = &rest[end + 1..];
        Ok(text)
    };
    if line()? != title() {
        return Err(format!("not a file of format v{FORMAT_VERSION}"));
    }
    if line()? != key {
        return Err("it holds a table of other parameters".into());
    }
    let layout = line()?;
    let words: Vec<&str> = layout.split(' ').collect();
    let numbers = words
        .get(1..)
        .filter(|_| words[0] == "rows")
        .ok_or("no row layout")?
        .iter()
        .map(|w| {
            w.parse::<usize>()
                .map_err(|_| format!("row layout '{layout}'"))
        })
        .collect::<Result<Vec<usize>, String>>()?;
    let (&count, lengths) = numbers.split_first().ok_or("no row count")?;
    if lengths.len() != count {
        return Err(format!("row layout '{layout}'"));
    }
    let hash = line()?;
    let data = rest;
    let total: usize = lengths.iter().sum();
    if data.len() != 8 * total {
        return Err(format!(
            "{} bytes of data where the layout needs {}",
            data.len(),
            8 * total
        ));
    }
    if hash != format!("fnv1a {:016x}", fnv1a(data)) {
        return Err("the data does not match its hash".into());
    }
    let mut values = data
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("8-byte chunks")));
    Ok(lengths
        .iter()
        .map(|&n| values.by_ref().take(n).collect())
        .collect())
}

impl TableCache {
    /// No cache: every table is built.
    pub fn off() -> TableCache {
        TableCache { dir: None }
    }

    /// Tables kept in the folder `dir` (made when a table is first written).
    pub fn at(dir: impl Into<PathBuf>) -> TableCache {
        TableCache {
            dir: Some(dir.into()),
        }
    }

    /// The folder, when on.
    pub fn dir(&self) -> Option<&Path> {
        self.dir.as_deref()
    }

    /// The file of the table of `kind` (a short name, part of the file's name) under
    /// `key`, when on.
    pub fn path(&self, kind: &str, key: &str) -> Option<PathBuf> {
        let full = format!("v{FORMAT_VERSION} {kind} {key}");
        self.dir
            .as_ref()
            .map(|d| d.join(format!("{kind}-{:016x}.table", fnv1a(full.as_bytes()))))
    }

    /// The table of `kind` under `key` (every parameter that changes it, as text) from
    /// the cache, else built by `build` and written to the cache.
    pub fn load_or_build<E>(
        &self,
        kind: &str,
        key: &str,
        build: impl FnOnce() -> Result<Vec<Vec<f64>>, E>,
    ) -> Result<Vec<Vec<f64>>, E> {
        let Some(path) = self.path(kind, key) else {
            return build();
        };
        // One line per key: the file's header is line by line.
        let key = format!("{kind} {}", key.replace('\n', " "));
        match fs::read(&path) {
            Ok(bytes) => match decode(&key, &bytes) {
                Ok(rows) => return Ok(rows),
                Err(why) => eprintln!(
                    "warning: table cache {}: {why}; building the table again",
                    path.display()
                ),
            },
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => eprintln!(
                "warning: table cache {}: {e}; building the table again",
                path.display()
            ),
        }
        let rows = build()?;
        if let Err(e) = write_atomically(&path, &encode(&key, &rows)) {
            eprintln!("warning: table cache {}: not written ({e})", path.display());
        }
        Ok(rows)
    }
}

/// Writes `bytes` to `path` through a temporary file beside it, renamed into place; the
/// temporary file's name is the process's and the write's own, so that concurrent
/// writers of one table never share it.
fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    static WRITES: AtomicU64 = AtomicU64::new(0);
    if let Some(dir) = path.parent() {
        fs::create_dir_all(dir)?;
    }
    let mut partial = path.as_os_str().to_owned();
    let write = WRITES.fetch_add(1, Ordering::Relaxed);
    partial.push(format!(".{}-{write}.partial", std::process::id()));
    let partial = PathBuf::from(partial);
    fs::write(&partial, bytes)?;
    fs::rename(&partial, path).inspect_err(|_| {
        let _ = fs::remove_file(&partial);
    })
}
