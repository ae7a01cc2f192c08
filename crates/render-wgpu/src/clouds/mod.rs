//! Clouds on the GPU: the cloud layer's ray march (`shaders/clouds/`), twin of
//! atmosphere-core's `clouds/layer/` and checked against it pixel by pixel.
//! [`layer_uniform`] holds the pass's parameters, [`layer_inputs`] the cover texture and
//! the multiple-scattering tables, [`layer_pass`] the pass, [`march_variants`] its
//! pipelines per light method; [`frame_clouds`] the layer of a renderer frame and the
//! planner's rule, [`frame_pass`] its march and its composite with the frame's sky model
//! ([`composite_inputs`] what the composite binds, [`cloud_targets`] the images the steps
//! write and read), [`frame_front`] the model's second run in front of the cloud
//! ([`front_targets`] its images at a reduced resolution), [`frame_steps`] the order of
//! the steps after the model's passes; [`sun_map_texture`] and [`sun_map_pass`] the
//! layer's attenuation of the sun over the view's region, which shades the surface, and
//! [`frame_sun_map`] its place in a renderer frame, [`frame_cloud_shafts`] the planner's
//! rule for its shadow in the air and [`air_shadow_pass`] that shadow per pixel, which
//! every model subtracts; [`spheres`] the cloud spheres seen from far away; [`volume`] a
//! voxel cloud by half-angle slicing.

pub mod air_shadow_pass;
pub mod cloud_targets;
pub mod composite_inputs;
pub mod frame_cloud_shafts;
pub mod frame_clouds;
pub mod frame_front;
pub mod frame_pass;
pub mod frame_steps;
pub mod frame_sun_map;
pub mod front_targets;
pub mod layer_inputs;
pub mod layer_pass;
pub mod layer_uniform;
pub mod march_variants;
pub mod spheres;
pub mod sun_map_pass;
pub mod sun_map_texture;
pub mod volume;
