//! A voxel cloud by half-angle slicing on the GPU (docs/clouds.md, "A local volume by
//! half-angle slicing"): [`slicing_uniform`] the passes' parameters,
//! [`slice_polygons`] the slices' proxy geometry, [`slicing_pass`] the alternating eye
//! and light passes.

pub mod slice_polygons;
pub mod slicing_pass;
pub mod slicing_uniform;
