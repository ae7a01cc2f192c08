//! The planet's light shafts on the GPU (docs/shafts.md): per frame, the terrain's
//! shadow map for the frame's sun over a grid of the view's region ([`frame_map`]),
//! uploaded with its parameters ([`shadow_texture`], [`uniform`]) for the sky passes
//! that test the sun's visibility at their samples (`shaders/shafts/terrain/`).

pub mod frame_map;
pub mod planner;
pub mod shadow_texture;
pub mod uniform;
