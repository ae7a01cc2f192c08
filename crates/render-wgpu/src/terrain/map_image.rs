//! The Earth's map images: decoding a file or built-in bytes with errors naming it, and
//! the equirectangular shape every map must have.

use std::io::Cursor;
use std::path::Path;

use image::DynamicImage;

use super::map_error::MapError;

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

/// Decodes an image held in memory (a built-in map), with errors naming it `name`.
pub(super) fn decode_image(bytes: &[u8], name: &Path) -> Result<DynamicImage, MapError> {
    image::ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(image::ImageError::IoError)
        .and_then(|reader| reader.decode())
        .map_err(|source| MapError::Read {
            path: name.to_owned(),
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
