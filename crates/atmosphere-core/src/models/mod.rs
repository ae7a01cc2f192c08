//! Every scattering model of the papers on the CPU, behind one trait
//! ([`sky_model::SkyModel`]); [`registry`] names them and prepares one by its id.

pub mod bruneton;
pub mod dobashi;
pub mod error;
pub mod hillaire;
pub mod id;
pub mod nishita;
pub mod oneil;
pub mod options;
pub mod registry;
pub mod riley;
pub mod sky_model;
pub mod table_update;
