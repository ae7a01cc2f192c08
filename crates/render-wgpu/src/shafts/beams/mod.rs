//! Light beams of local scenes on the GPU (docs/beams.md, "On the GPU"): lights through
//! a homogeneous medium with occluders casting shadows into the air, after Dobashi,
//! Yamamoto and Nishita 2000. The CPU specification is atmosphere-core's `beams/`.
//!
//! - [`gpu_scene`]: the scene packed for the shaders (lights, light maps, shadow maps,
//!   occluders, phase function), relative to the camera;
//! - [`gpu_methods`]: the methods on the GPU by id, prepared and rendered;
//! - [`limits`]: what the device must hold, checked before anything is made;
//! - [`march_pass`]: the per-pixel ray march with shadow maps
//!   (`shaders/shafts/beams/march.wgsl`), twin of `beams/methods/march.rs`;
//! - [`planes_pass`]: the virtual planes of Dobashi, Yamamoto and Nishita 2000, drawn
//!   as lattice meshes with additive blending (`shaders/shafts/beams/planes.wgsl`,
//!   `ray_end.wgsl`), twin of `beams/methods/planes2000.rs`;
//! - [`qtable_pass`]: the q(u, v) table and sub-planes of Dobashi et al. 2002
//!   (`shaders/shafts/beams/qtable.wgsl`, `q_table.wgsl`), twin of
//!   `beams/methods/qtable2002/`;
//! - [`qtable_walk`]: the q table's planes and sub-planes walked per pixel, the
//!   default way [`qtable_pass`] draws them (`shaders/shafts/beams/qtable_walk.wgsl`);
//! - [`qtable_upsample`]: the q table's walk at reduced resolution brought to the
//!   frame's size, walked exactly where it cannot be interpolated
//!   (`shaders/shafts/beams/qtable_upsample.wgsl`);
//! - [`ray_end_pass`]: where each pixel's ray ends, the planes' depth test;
//! - [`blended_planes`]: the additive render pipeline the plane methods share;
//! - [`planes_frame`]: one frame of a plane method: the scene uploaded, the ray end,
//!   both bind groups, the additive pass and its GPU time;
//! - [`scene_buffers`]: the packed scene uploaded, read by every pass;
//! - [`image`]: the rendered radiance, tone-mapped as a planet frame is, read back.
//!
//! The shadow maps are those the CPU march builds (a ray per texel), uploaded: the
//! parity of GPU and CPU then rests on the march alone.

pub mod blended_planes;
pub mod gpu_methods;
pub mod gpu_scene;
pub mod image;
pub mod limits;
pub mod march_pass;
pub mod planes_frame;
pub mod planes_pass;
pub mod qtable_pass;
pub mod qtable_upsample;
pub mod qtable_walk;
pub mod ray_end_pass;
pub mod scene_buffers;
