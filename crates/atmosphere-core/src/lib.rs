//! atmosphere-core: the physics of atmos, without a GPU.
//!
//! Data flows one way: an [`atmosphere::Atmosphere`] (parameters) is sampled at the
//! wavelengths a model carries, tables are built from it, and the models answer the
//! radiance and transmittance of view rays. The CPU code here is the specification that
//! every shader matches.

pub mod atmosphere;
pub mod bruneton;
pub mod cie1931;
pub mod color;
pub mod color_difference;
pub mod column;
pub mod density;
pub mod dobashi;
pub mod error_statistics;
pub mod geometry;
pub mod hillaire;
pub mod model;
pub mod model_options;
pub mod nishita;
pub mod oneil;
pub mod ozone;
pub mod phase;
pub mod phase_sampling;
pub mod presets;
pub mod quadrature;
pub mod reference;
pub mod riley;
pub mod sampling;
pub mod solar;
pub mod spectral;
pub mod stability;
pub mod sun_disk;
pub mod sun_position;
pub mod surface_lighting;
pub mod table_inputs;
pub mod transmittance_table;
pub mod view_segment;
