//! The Earth's map files: where they ship, decoding with errors naming the file, and the
//! equirectangular shape every map must have.

use std::path::{Path, PathBuf};

use image::DynamicImage;

use super::map_error::MapError;

/// The folder of the shipped Earth maps in the source tree (`assets/earth`).
pub fn earth_assets_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/earth")
}

/// Decodes an image file, with errors naming it.
pub(super) fn load_image(path: &Path) -> Result<DynamicImage, MapError> {
    if !path.is_file() {
        return Err(MapError::Missing {
            path: path.to_owned(),
        });
    }
    image::ImageReader::open(path)
        .and_then(|reader| reader.with_guessed_format())
        .map_err(|e| MapError::Read {
            path: path.to_owned(),
            source: image::ImageError::IoError(e),
        })?
        .decode()
        .map_err(|source| MapError::Read {
            path: path.to_owned(),
            source,
        })
}

/// Equirectangular maps are twice as wide as tall.
pub(super) fn check_aspect(path: &Path, width: usize, height: usize) -> Result<(), MapError> {
    if width != 2 * height || height == 0 {
        return Err(MapError::Format {
            path: path.to_owned(),
            found: format!("{width} x {height}"),
            expected: "an equirectangular map twice as wide as tall",
        });
    }
    Ok(())
}
