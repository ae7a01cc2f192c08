//! Clouds: media of droplets the sky's light scatters through many times. A
//! [`medium::CloudMedium`] describes one (extinction, albedo, phase function, majorant);
//! [`tracking`] follows Monte Carlo paths through it by delta tracking; [`slab`] is the
//! plane-parallel layer and [`slab_transport`] its reflected, transmitted and absorbed
//! fractions with their standard errors, the ground truth the cloud models are checked
//! against.

pub mod cover;
pub mod error;
pub mod estimate;
pub mod layer;
pub mod medium;
pub mod phase;
pub mod reference;
pub mod slab;
pub mod slab_transport;
pub mod spheres;
pub mod tracking;
pub mod volume;
