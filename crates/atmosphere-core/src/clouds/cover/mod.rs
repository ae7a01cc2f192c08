//! Cloud cover over a whole planet: the fraction of each place's sky that cloud covers,
//! 0 to 1, as a function of the planet-fixed direction. Generated from a seed with the
//! structure of real weather ([`generated`]), or read from any equirectangular image,
//! satellite or painted ([`grid`]); either is rasterised to a [`grid::CoverGrid`], which
//! is what the renderer uploads and its CPU twin samples.

pub mod climatology;
pub mod cyclones;
pub mod generated;
pub mod grid;
