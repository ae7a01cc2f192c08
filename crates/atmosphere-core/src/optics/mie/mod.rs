//! Lorenz-Mie scattering by homogeneous spheres (cloud droplets, rain, aerosols), after
//! Bohren and Huffman 1983, chapter 4, and Wiscombe 1980.
//!
//! Conventions, once: the size parameter is x = 2 pi r / lambda with lambda in the
//! surrounding medium; the relative refractive index is m = n + i k with k >= 0 for an
//! absorbing sphere (time dependence exp(-i omega t)); nu or mu is the cosine of the
//! scattering angle (1: forward); phase functions are in sr^-1 with unit integral over
//! the sphere.

pub mod amplitudes;
pub mod coefficients;
pub mod efficiencies;
pub mod error;
pub mod legendre;
pub mod limits;
pub mod marshall_palmer;
pub mod phase_table;
pub mod polydisperse;
pub mod rain;
pub mod size_distribution;
