//! Light in the atmosphere: ray geometry on the sphere, optical columns and
//! transmittance, phase functions, the view ray's segment inside the atmosphere, the
//! sun's disk, the lighting of surfaces and the sea's reflection; particles: Lorenz-Mie spheres, refractive
//! indices, Legendre series of phase functions and their multiple-scattering powers.

pub mod column;
pub mod geometry;
pub mod ice;
pub mod legendre_series;
pub mod mie;
pub mod multiple_scattering_phase;
pub mod phase;
pub mod phase_sampling;
pub mod prepared_phase;
pub mod refractive_index;
pub mod sea_surface;
pub mod sun_disk;
pub mod surface_lighting;
pub mod transmittance_table;
pub mod view_segment;
