//! What goes wrong when a beams scene is read, a method prepared or a ray asked about.

use thiserror::Error;

use crate::atmosphere::text_file::TextFileError;
use crate::models::error::ModelError;

/// What goes wrong with a beams scene, a beam method or a ray. Field names are written
/// as in the scene file (`lights[1].cone_deg`).
#[derive(Debug, Error)]
pub enum BeamError {
    #[error(transparent)]
    File(#[from] TextFileError),
    #[error("{file}: {reason}")]
    Toml { file: String, reason: String },
    #[error("{file}: {field}: {reason}")]
    Field {
        file: String,
        field: String,
        reason: String,
    },
    #[error("{file}: {field}: cannot read image {path}: {reason}")]
    Image {
        file: String,
        field: String,
        path: String,
        reason: String,
    },
    #[error("{file}: {field}: cannot read glTF {path}: {reason}")]
    Gltf {
        file: String,
        field: String,
        path: String,
        reason: String,
    },
    #[error(transparent)]
    Settings(#[from] ModelError),
    #[error("invalid ray: {0}")]
    Ray(String),
}
