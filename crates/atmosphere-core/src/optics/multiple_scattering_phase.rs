//! The multiple-scattering angular distributions A_n of Riley et al. 2004 (section
//! 4.2.1, Eq. 20): a collimated beam's direction after n scatterings, the phase function
//! convolved with itself n times on the sphere; and the forward fractions F_n (section
//! 4.2.2, Eq. 23), the part of A_n in the hemisphere around the beam.
//!
//! Through Legendre coefficients rather than 2D integrals: convolution on the sphere
//! multiplies them, so A_n has coefficients chi_l^n. Each A_n keeps the degrees up to
//! the last whose chi_l^n reaches [`TERM_CUT`]; the terms dropped are each below it,
//! far below the sr^-1 values summed. A_1 is the phase function itself.

use crate::optics::legendre_series::LegendreSeries;

/// Riley et al.'s number of orders, past which they treat light as isotropic.
pub const RILEY_MAX_ORDER: u32 = 26;

/// The smallest chi_l^n an A_n keeps.
pub const TERM_CUT: f64 = 1e-13;

/// A_1..=A_N of one phase function.
#[derive(Clone, Debug)]
pub struct MultipleScatteringPhase {
    orders: Vec<LegendreSeries>,
}

impl MultipleScatteringPhase {
    /// A_1..=A_`max_order` of the phase function `single` (max_order >= 1).
    pub fn new(single: &LegendreSeries, max_order: u32) -> MultipleScatteringPhase {
        MultipleScatteringPhase {
            orders: (1..=max_order.max(1))
                .map(|n| single.power(n, TERM_CUT))
                .collect(),
        }
    }

    /// The highest order held.
    pub fn max_order(&self) -> u32 {
        self.orders.len() as u32
    }

    /// The series of A_n, n in 1..=max_order.
    pub fn series(&self, n: u32) -> &LegendreSeries {
        &self.orders[(n.clamp(1, self.max_order()) - 1) as usize]
    }

    /// A_n at the cosine `nu` of the angle from the beam, sr^-1 (Riley et al. 2004,
    /// Eq. 20).
    pub fn angular_distribution(&self, n: u32, nu: f64) -> f64 {
        self.series(n).eval(nu)
    }

    /// F_n, the integral of A_n over the forward hemisphere (Riley et al. 2004, Eq. 23).
    pub fn forward_fraction(&self, n: u32) -> f64 {
        self.series(n).forward_fraction()
    }
}
