//! Rain shafts and cirrus layers in renderer frames, on the GPU: the single-scattering
//! march of each pixel through the volumes and its composite over the model's pixels
//! (`shaders/precipitation/`), twin of atmosphere-core's `hydrometeors/render.rs` and
//! checked against it pixel by pixel. [`volume_uniform`] packs the volumes and their
//! phase tables, [`volumes_pass`] is the pass, [`in_view`] the planner's rule,
//! [`screen_rect`] the pixels the pass runs over.

pub mod in_view;
pub mod screen_rect;
#[cfg(test)]
mod test_scene;
pub mod volume_uniform;
pub mod volumes_pass;
