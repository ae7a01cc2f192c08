//! Numerical building blocks: quadrature rules and random sampling.

pub mod gauss_legendre_rule;
pub mod quadrature;
pub mod sampling;
