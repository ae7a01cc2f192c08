//! What goes wrong when a terrain map is loaded: each message names the file, or the
//! folder and every path it was looked for at.

use std::path::PathBuf;

use thiserror::Error;

/// Errors of loading the Earth's height and colour maps.
#[derive(Debug, Error)]
pub enum MapError {
    #[error("terrain map {path} is missing")]
    Missing { path: PathBuf },
    #[error("terrain data folder {dir}: {problem}; it needs {}", paths(tried))]
    Folder {
        dir: PathBuf,
        problem: String,
        /// The files looked for, in order.
        tried: Vec<PathBuf>,
    },
    #[error("cannot read terrain map {path}: {source}")]
    Read {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    #[error("terrain map {path} is {found}; expected {expected}")]
    Format {
        path: PathBuf,
        found: String,
        expected: &'static str,
    },
}

/// "a, b and c".
fn paths(list: &[PathBuf]) -> String {
    let names: Vec<String> = list.iter().map(|p| p.display().to_string()).collect();
    match names.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        None => String::new(),
    }
}
