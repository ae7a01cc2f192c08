//! What goes wrong when a model is chosen, prepared or asked about a ray.

use thiserror::Error;

use crate::atmosphere::AtmosphereError;
use crate::models::id::ModelId;

/// What goes wrong when a model is chosen, prepared or asked about a ray.
#[derive(Debug, Error)]
pub enum ModelError {
    #[error(transparent)]
    Atmosphere(#[from] AtmosphereError),
    #[error("invalid model settings: {0}")]
    Settings(String),
    #[error("invalid view ray: {0}")]
    Ray(String),
    #[error("the {model} model does not {what}")]
    Unsupported { model: ModelId, what: &'static str },
}
