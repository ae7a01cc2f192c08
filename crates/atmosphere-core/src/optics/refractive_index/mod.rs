//! Complex refractive indices of the materials particles are made of, m = n + i k
//! (k >= 0 absorbs), at a vacuum wavelength.

pub mod ice;
pub mod tabulated;
pub mod water;
