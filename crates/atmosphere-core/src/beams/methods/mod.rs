//! The ways to compute a view ray's radiance in a beams scene, selectable by
//! [`id::BeamMethodId`] like the sky models: `method.rs` the trait and settings,
//! `registry.rs` the factory, one file per method.

pub mod breakpoints;
pub mod id;
pub mod march;
pub mod method;
pub mod planes2000;
pub mod qtable2002;
pub mod reference;
pub mod registry;
