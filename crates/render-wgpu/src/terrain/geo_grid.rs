//! Equirectangular grids addressed by latitude and longitude (the layout of
//! `assets/earth/*`, see `assets/CREDITS.md`) and the planet-fixed frame's directions:
//! atmosphere-core's, which the cloud cover shares.

pub use atmosphere_core::geo::equirectangular::{bilinear_taps, direction, lat_lon};
