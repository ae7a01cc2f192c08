//! atmosphere-core: the physics of atmos, without a GPU.
//!
//! Data flows one way: an [`atmosphere::Atmosphere`] (parameters) is sampled at the
//! wavelengths a model carries, tables are built from it, and the models answer the
//! radiance and transmittance of view rays. The CPU code here is the specification that
//! every shader matches.

pub mod analysis;
pub mod atmosphere;
pub mod beams;
pub mod clouds;
pub mod color;
pub mod geo;
pub mod hydrometeors;
pub mod models;
pub mod numerics;
pub mod optics;
pub mod reference;
pub mod shafts;
pub mod sun_position;
pub mod table_cache;
