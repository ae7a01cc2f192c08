//! Light beams in a local scene: lights through a homogeneous medium (fog, dust, smoke)
//! with occluders casting shadows into the air, after Dobashi, Yamamoto and Nishita 2000
//! and Dobashi et al. 2002 section 4 (docs/beams.md).
//!
//! Conventions, once for the module: the scene frame is glTF's (right-handed, y up),
//! in metres; point and spot lights give their intensity in W sr^-1 nm^-1, parallel
//! lights their irradiance in W m^-2 nm^-1 across the beam; radiance is in
//! W m^-2 sr^-1 nm^-1, at the wavelengths a method is prepared with. Surfaces are
//! black: a ray's radiance is the light its medium scatters toward the camera up to the
//! first surface (Dobashi et al. 2000 Eq. 1, second term).
//!
//! `scene_file.rs` is the TOML as written, `scene.rs` the checked scene with its images
//! and meshes loaded; `methods/` holds the ways to compute a ray's radiance, selectable
//! by [`methods::id::BeamMethodId`] like the sky models.

pub mod bvh;
pub mod camera;
pub mod error;
pub mod gltf_mesh;
pub mod in_scattering;
pub mod light;
pub mod light_frame;
pub mod light_map;
pub mod medium;
pub mod methods;
pub mod occluder;
pub mod occluders;
pub mod plan;
pub mod ray;
pub mod scene;
pub mod scene_file;
pub mod shadow_map;
pub mod triangle;
