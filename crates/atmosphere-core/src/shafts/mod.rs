//! The terrain's shadow in the air: which points of the atmosphere see the sun past the
//! mountains (light shafts; docs/shafts.md).
//!
//! Conventions: planet-centred positions in metres, unit sun directions; a visibility is
//! a fraction in [0, 1] of the sun's centre seen past the terrain (the Earth's own shadow
//! is the models' business and is not counted here). Two answers to the same question:
//! [`HeightFieldShadow`], exact, marching the relief towards the sun from each point (the
//! reference's), and [`ShadowMap`], the per-frame representation the GPU reads: the
//! altitude of the shadow volume's top over a grid of the view's region.

mod gnomonic_grid;
mod height_field_shadow;
mod relief;
mod shadow_map;
mod sun_visibility;
mod view_span;

pub use gnomonic_grid::{GRID_SIZE_RANGE, GnomonicGrid};
pub use height_field_shadow::HeightFieldShadow;
pub use relief::Relief;
pub use shadow_map::ShadowMap;
pub use sun_visibility::SunVisibility;
pub use view_span::{
    MIN_SHAFT_SAMPLES, SHAFT_SAMPLES, segment_span_m, shadowed_length_m, shaft_samples,
    shaft_span_m,
};
