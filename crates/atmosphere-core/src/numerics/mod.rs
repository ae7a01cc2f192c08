//! Numerical building blocks: quadrature rules and random sampling.

pub mod quadrature;
pub mod sampling;
