//! The Mie phase function in the delta-M form the order step integrates exactly.

use std::f64::consts::PI;

use crate::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};
use crate::optics::phase::PhaseFunction;

/// The delta-M form of the Mie phase function with three Legendre terms (Wiscombe 1977):
/// p(nu) ~ f delta(1 - nu) / (2 pi) + (1 - f) / (4 pi) (1 + 3 chi1 P1(nu) + 5 chi2 P2(nu)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeltaM {
    pub forward_fraction: f64,
    pub chi1: f64,
    pub chi2: f64,
}

impl DeltaM {
    /// Legendre moments of `phase` by quadrature in the scattering angle (fine near the
    /// forward peak), then truncation.
    pub fn new(phase: &PhaseFunction) -> DeltaM {
        let n = 20_000;
        let h = PI / n as f64;
        let mut chi = [0.0; 4];
        for k in 0..n {
            for (t, w) in mapped(&GAUSS_LEGENDRE_8, h * k as f64, h * (k + 1) as f64) {
                let x = t.cos();
                let p = phase.eval(x) * 2.0 * PI * t.sin() * w;
                let p2 = 0.5 * (3.0 * x * x - 1.0);
                let p3 = 0.5 * (5.0 * x * x * x - 3.0 * x);
                chi[0] += p;
                chi[1] += p * x;
                chi[2] += p * p2;
                chi[3] += p * p3;
            }
        }
        let f = (chi[3] / chi[0]).clamp(0.0, 0.999);
        DeltaM {
            forward_fraction: f,
            chi1: (chi[1] / chi[0] - f) / (1.0 - f),
            chi2: (chi[2] / chi[0] - f) / (1.0 - f),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delta_m_of_henyey_greenstein_has_its_known_moments() {
        let g: f64 = 0.8;
        let dm = DeltaM::new(&PhaseFunction::HenyeyGreenstein { g });
        let f = g.powi(3);
        assert!((dm.forward_fraction - f).abs() < 1e-4, "{dm:?}");
        assert!((dm.chi1 - (g - f) / (1.0 - f)).abs() < 1e-4, "{dm:?}");
        assert!((dm.chi2 - (g * g - f) / (1.0 - f)).abs() < 1e-4, "{dm:?}");
    }
}
