//! The scattering models of the papers on the CPU, each behind one trait
//! ([`sky_model::SkyModel`]): [`id`] names them, [`registry`] prepares one by its id with
//! its [`settings`] and [`options`], [`model_base`] is the state they all keep and
//! [`table_update`] the bookkeeping of their `update`.

pub mod bruneton;
pub mod dobashi;
pub mod error;
pub mod gpu_loops;
pub mod hillaire;
pub mod id;
pub mod model_base;
pub mod nishita;
pub mod oneil;
pub mod options;
pub mod registry;
pub mod riley;
pub mod settings;
pub mod sky_model;
pub mod table_budget;
pub mod table_update;
