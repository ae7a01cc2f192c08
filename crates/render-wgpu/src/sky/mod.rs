//! The sky on the GPU: every scattering model's tables and per-pixel pass, its steps typed
//! ([`model_pass::ModelPass`], [`steps`]), behind one object-safe interface for the
//! renderer ([`sky_pass::SkyPass`]), made by the [`registry`]; and what several models
//! share: the pixel pass's layout, the transmittance and columns tables, and the
//! filtered table reads.

pub mod bruneton;
pub mod columns_table;
pub mod dobashi;
pub mod hillaire;
pub mod model_pass;
pub mod nishita;
pub mod oneil;
pub mod pixel_pass;
pub mod registry;
pub mod riley;
pub mod sky_pass;
pub mod steps;
pub mod table_limits;
pub mod table_sampling;
pub mod transmittance;
