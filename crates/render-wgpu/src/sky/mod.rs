//! The sky on the GPU: every scattering model's tables and per-pixel pass behind one
//! trait ([`model_pass::ModelPass`]), made by the [`registry`]; the transmittance table
//! and the filtered table reads several models share.

pub mod bruneton;
pub mod dobashi;
pub mod hillaire;
pub mod model_pass;
pub mod nishita;
pub mod oneil;
pub mod registry;
pub mod riley;
pub mod table_sampling;
pub mod transmittance;
