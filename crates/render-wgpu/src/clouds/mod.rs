//! Clouds on the GPU: the cloud layer's ray march (`shaders/clouds/`), twin of
//! atmosphere-core's `clouds/layer/` and checked against it pixel by pixel.
//! [`layer_uniform`] holds the pass's parameters, [`layer_inputs`] the cover texture
//! and the multiple-scattering tables, [`layer_pass`] the pass.

pub mod layer_inputs;
pub mod layer_pass;
pub mod layer_uniform;
