//! Mie's share of Delta J by a quadrature over the sphere about each texel's view
//! direction with the exact phase function, in place of the delta-M form: Bruneton and
//! Neyret 2008 (section 4, Algorithm 4.1 line 6) integrate Delta J per texel over the
//! sphere; here the directions crowd towards the view, where a forward-peaked aerosol
//! takes most of its light from. With psi the angle to the view direction v,
//! psi = pi u^2 with u at composite 8-point Gauss-Legendre nodes on [0, 1], and azimuths
//! about v at the midpoints of n equal steps:
//!
//!     J_M(v) = sum over nodes of w_k p_M(cos psi_k) L(omega(psi_k, phi_j)),
//!     w_k = (2 pi u_k) (Gauss weight) sin(psi_k) (2 pi / n).

use std::f64::consts::PI;

use glam::DVec3;

use crate::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};
use crate::optics::phase::PhaseFunction;

/// The directions about a view direction and their weights times the phase function.
#[derive(Clone, Debug, PartialEq)]
pub struct MieQuadrature {
    /// (cos psi, sin psi, weight times p_M(cos psi)) per polar node.
    polar: Vec<(f64, f64, f64)>,
    /// (cos phi, sin phi) per azimuth.
    azimuths: Vec<(f64, f64)>,
}

impl MieQuadrature {
    /// `directions` polar nodes (a multiple of 8) by `directions` azimuths.
    pub fn new(phase: &PhaseFunction, directions: usize) -> MieQuadrature {
        let panels = (directions / 8).max(1);
        let step = 1.0 / panels as f64;
        let azimuth_weight = 2.0 * PI / directions as f64;
        let polar = (0..panels)
            .flat_map(|p| mapped(&GAUSS_LEGENDRE_8, step * p as f64, step * (p + 1) as f64))
            .map(|(u, w)| {
                let psi = PI * u * u;
                let (s, c) = psi.sin_cos();
                (c, s, w * 2.0 * PI * u * s * azimuth_weight * phase.eval(c))
            })
            .collect();
        let azimuths = (0..directions)
            .map(|j| {
                let (s, c) = (azimuth_weight * (j as f64 + 0.5)).sin_cos();
                (c, s)
            })
            .collect();
        MieQuadrature { polar, azimuths }
    }

    /// Sum over the nodes of weight x p_M x `radiance(direction)` about the unit vector
    /// `view`, per channel.
    pub fn integrate(&self, view: DVec3, mut radiance: impl FnMut(DVec3) -> [f64; 3]) -> [f64; 3] {
        let (a, b) = orthonormal_basis(view);
        let mut sum = [0.0; 3];
        for &(cos_psi, sin_psi, weight) in &self.polar {
            for &(cos_phi, sin_phi) in &self.azimuths {
                let direction = view * cos_psi + (a * cos_phi + b * sin_phi) * sin_psi;
                let l = radiance(direction);
                for k in 0..3 {
                    sum[k] += weight * l[k];
                }
            }
        }
        sum
    }
}

/// Two unit vectors that make a right-handed orthonormal basis with the unit vector `n`
/// (Duff et al. 2017, "Building an orthonormal basis, revisited", Listing 3); the GPU
/// builds the same one.
pub fn orthonormal_basis(n: DVec3) -> (DVec3, DVec3) {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weights_integrate_the_phase_function_to_one() {
        for phase in [
            PhaseFunction::HenyeyGreenstein { g: 0.0 },
            PhaseFunction::CornetteShanks { g: 0.76 },
            PhaseFunction::HenyeyGreenstein { g: 0.9 },
        ] {
            let q = MieQuadrature::new(&phase, 16);
            let total = q.integrate(DVec3::Z, |_| [1.0; 3])[0];
            assert!((total - 1.0).abs() < 5e-3, "{phase:?}: {total}");
        }
    }

    #[test]
    fn a_radiance_linear_in_the_direction_gives_its_closed_form() {
        // L(w) = 1 + w.d integrates against p to 1 + g (v.d) for Henyey-Greenstein.
        let g = 0.7;
        let q = MieQuadrature::new(&PhaseFunction::HenyeyGreenstein { g }, 32);
        let view = DVec3::new(0.3, -0.5, 0.8).normalize();
        let d = DVec3::new(-0.2, 0.9, 0.1).normalize();
        let got = q.integrate(view, |w| [1.0 + w.dot(d); 3])[0];
        let want = 1.0 + g * view.dot(d);
        assert!((got - want).abs() < 2e-3, "{got} against {want}");
    }

    #[test]
    fn the_basis_is_orthonormal_for_every_direction() {
        for n in [
            DVec3::Z,
            -DVec3::Z,
            DVec3::X,
            DVec3::new(0.1, -0.7, -0.2).normalize(),
        ] {
            let (a, b) = orthonormal_basis(n);
            for (u, v) in [(a, b), (a, n), (b, n)] {
                assert!(u.dot(v).abs() < 1e-12);
            }
            assert!((a.length() - 1.0).abs() < 1e-12 && (b.length() - 1.0).abs() < 1e-12);
            assert!((a.cross(b) - n).length() < 1e-12, "{n}");
        }
    }
}
