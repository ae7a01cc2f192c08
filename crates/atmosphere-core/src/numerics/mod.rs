//! Numerical building blocks: quadrature rules, random sampling and deterministic noise.

pub mod cellular_noise;
pub mod gauss_legendre_rule;
pub mod gradient_noise;
pub mod quadrature;
pub mod sampling;
