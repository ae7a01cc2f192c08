//! What goes wrong when a terrain map is loaded: each message names the file.

use std::path::PathBuf;

use thiserror::Error;

/// Errors of loading the Earth's height and colour maps.
#[derive(Debug, Error)]
pub enum MapError {
    #[error("terrain map {path} is missing; run scripts/fetch_earth_data.sh to make it")]
    Missing { path: PathBuf },
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
