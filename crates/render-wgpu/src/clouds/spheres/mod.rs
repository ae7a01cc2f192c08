//! The cloud spheres on the GPU (Dobashi, Yamamoto and Nishita 2002, section 5.4; twin of
//! atmosphere-core's `clouds/spheres/`): [`sphere_uniform`] the pass's parameters,
//! [`sphere_inputs`] the cloud and attenuation textures and the droplets' phase function
//! as storage buffers, [`sphere_pass`] the pass writing each pixel's radiance and
//! transmittance of the spheres; in renderer frames, [`sphere_cache`] the spheres made
//! for the frame's sun and kept while it stays, and [`frame_spheres`] the pass ended on
//! the frame's surface and blended with the layer across the hand-over, with
//! [`reduced_targets`] its images at a reduced resolution and [`image_formats`] the
//! images' formats.

pub mod frame_spheres;
pub mod image_formats;
pub mod reduced_targets;
pub mod sphere_cache;
pub mod sphere_inputs;
pub mod sphere_pass;
pub mod sphere_uniform;
pub mod sphere_variants;
