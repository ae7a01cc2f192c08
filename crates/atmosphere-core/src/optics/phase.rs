//! Phase functions: the angular distribution of scattered light, each normalised so that
//! its integral over the sphere is 1 (units sr^-1). The argument `nu` is the cosine of the
//! scattering angle: 1 is forward scattering.

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

/// The phase functions atmos knows, as written in presets and TOML files.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum PhaseFunction {
    /// Molecules: 3 / (16 pi) (1 + nu^2).
    Rayleigh,
    /// Cornette and Shanks 1992, the Mie approximation of Bruneton 2008 Eq. (4).
    CornetteShanks { g: f64 },
    /// Henyey and Greenstein 1941.
    HenyeyGreenstein { g: f64 },
    /// Nishita's hazy-atmosphere function, Dobashi et al. 2000 Eq. (4):
    /// K (1 + 9 cos^16(theta / 2)), with K = 1 / (8 pi) for unit integral.
    NishitaHazy,
    /// Values at scattering angles (degrees, 0 to 180, increasing), linearly
    /// interpolated in angle and renormalised to unit integral.
    Tabulated {
        angles_deg: Vec<f64>,
        values: Vec<f64>,
    },
}

impl PhaseFunction {
    /// The phase function at the cosine `nu` of the scattering angle, in sr^-1.
    pub fn eval(&self, nu: f64) -> f64 {
        let nu = nu.clamp(-1.0, 1.0);
        match self {
            PhaseFunction::Rayleigh => rayleigh(nu),
            PhaseFunction::CornetteShanks { g } => cornette_shanks(*g, nu),
            PhaseFunction::HenyeyGreenstein { g } => henyey_greenstein(*g, nu),
            PhaseFunction::NishitaHazy => nishita_hazy(nu),
            PhaseFunction::Tabulated { angles_deg, values } => {
                tabulated_raw(angles_deg, values, nu) / tabulated_integral(angles_deg, values)
            }
        }
    }

    /// Why these parameters do not describe a phase function, if they do not.
    pub fn problem(&self) -> Option<String> {
        match self {
            PhaseFunction::CornetteShanks { g } | PhaseFunction::HenyeyGreenstein { g }
                if !(g.is_finite() && g.abs() < 1.0) =>
            {
                Some(format!(
                    "asymmetry g = {g} must lie strictly between -1 and 1"
                ))
            }
            PhaseFunction::Tabulated { angles_deg, values } => {
                if angles_deg.len() < 2 || angles_deg.len() != values.len() {
                    Some("a tabulated phase function needs at least two angles and one value per angle".into())
                } else if angles_deg[0] != 0.0 || angles_deg[angles_deg.len() - 1] != 180.0 {
                    Some("tabulated angles_deg must run from 0 to 180".into())
                } else if angles_deg
                    .windows(2)
                    .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
                {
                    Some("tabulated angles_deg must be strictly increasing".into())
                } else if values.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
                    Some("tabulated values must be finite and >= 0".into())
                } else if tabulated_integral(angles_deg, values) <= 0.0 {
                    Some("tabulated values integrate to zero".into())
                } else {
                    None
                }
            }
            _ => None,
        }
    }
}

/// Rayleigh phase function 3 / (16 pi) (1 + nu^2) (Bruneton 2008 Eq. 2).
pub fn rayleigh(nu: f64) -> f64 {
    3.0 / (16.0 * PI) * (1.0 + nu * nu)
}

/// Cornette-Shanks: 3 / (8 pi) (1 - g^2)(1 + nu^2) / ((2 + g^2)(1 + g^2 - 2 g nu)^(3/2))
/// (Bruneton 2008 Eq. 4).
pub fn cornette_shanks(g: f64, nu: f64) -> f64 {
    let g2 = g * g;
    let denom = (1.0 + g2 - 2.0 * g * nu).max(1e-300);
    3.0 / (8.0 * PI) * (1.0 - g2) * (1.0 + nu * nu) / ((2.0 + g2) * denom * denom.sqrt())
}

/// Henyey-Greenstein: (1 - g^2) / (4 pi (1 + g^2 - 2 g nu)^(3/2)).
pub fn henyey_greenstein(g: f64, nu: f64) -> f64 {
    let g2 = g * g;
    let denom = (1.0 + g2 - 2.0 * g * nu).max(1e-300);
    (1.0 - g2) / (4.0 * PI * denom * denom.sqrt())
}

/// Nishita's hazy function (Dobashi et al. 2000 Eq. 4) with K = 1 / (8 pi): the integral
/// of cos^16(theta/2) over the sphere is 4 pi / 9, so K (4 pi + 9 * 4 pi / 9) = 1.
pub fn nishita_hazy(nu: f64) -> f64 {
    let cos_half_sq = 0.5 * (1.0 + nu); // cos^2(theta/2)
    (1.0 + 9.0 * cos_half_sq.powi(8)) / (8.0 * PI)
}

pub(crate) fn tabulated_raw(angles_deg: &[f64], values: &[f64], nu: f64) -> f64 {
    crate::atmosphere::spectral::interpolate_clamped(angles_deg, values, nu.acos().to_degrees())
}

/// Integral over the sphere of the tabulated values: 2 pi times the integral over theta of
/// p(theta) sin(theta), exact for piecewise-linear p on each interval (Simpson is exact
/// for the product's smooth parts only; we subdivide each interval 16 times).
pub(crate) fn tabulated_integral(angles_deg: &[f64], values: &[f64]) -> f64 {
    let mut sum = 0.0;
    for i in 0..angles_deg.len() - 1 {
        let (a, b) = (angles_deg[i].to_radians(), angles_deg[i + 1].to_radians());
        let (va, vb) = (values[i], values[i + 1]);
        const N: usize = 16;
        let h = (b - a) / N as f64;
        for k in 0..N {
            // Gauss-Legendre with two points on each sub-interval.
            for x in [-0.577_350_269_189_625_8, 0.577_350_269_189_625_8] {
                let t = a + h * (k as f64 + 0.5 + 0.5 * x);
                let v = va + (vb - va) * (t - a) / (b - a);
                sum += 0.5 * h * v * t.sin();
            }
        }
    }
    2.0 * PI * sum
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integral over the sphere by Gauss-Legendre in nu on many panels.
    fn sphere_integral(p: &PhaseFunction) -> f64 {
        let n = 20_000;
        let h = 2.0 / n as f64;
        let mut sum = 0.0;
        for k in 0..n {
            for x in [-0.577_350_269_189_625_8, 0.577_350_269_189_625_8] {
                let nu = -1.0 + h * (k as f64 + 0.5 + 0.5 * x);
                sum += 0.5 * h * p.eval(nu);
            }
        }
        2.0 * PI * sum
    }

    #[test]
    fn every_phase_function_integrates_to_one() {
        let table = PhaseFunction::Tabulated {
            angles_deg: vec![0.0, 10.0, 90.0, 180.0],
            values: vec![5.0, 2.0, 0.5, 1.0],
        };
        for p in [
            PhaseFunction::Rayleigh,
            PhaseFunction::CornetteShanks { g: 0.8 },
            PhaseFunction::CornetteShanks { g: -0.3 },
            PhaseFunction::HenyeyGreenstein { g: 0.76 },
            PhaseFunction::HenyeyGreenstein { g: 0.0 },
            PhaseFunction::NishitaHazy,
            table,
        ] {
            let integral = sphere_integral(&p);
            assert!(
                (integral - 1.0).abs() < 1e-6,
                "{p:?} integrates to {integral}"
            );
        }
    }

    #[test]
    fn henyey_greenstein_mean_cosine_is_g() {
        let g = 0.6;
        let n = 200_000;
        let h = 2.0 / n as f64;
        let mean: f64 = (0..n)
            .map(|k| {
                let nu = -1.0 + h * (k as f64 + 0.5);
                nu * henyey_greenstein(g, nu) * 2.0 * PI * h
            })
            .sum();
        assert!((mean - g).abs() < 1e-4, "{mean}");
    }

    #[test]
    fn known_values() {
        assert!((rayleigh(1.0) - 3.0 / (8.0 * PI)).abs() < 1e-15);
        assert!((henyey_greenstein(0.0, 0.3) - 1.0 / (4.0 * PI)).abs() < 1e-15);
        // Cornette-Shanks with g = 0 is the Rayleigh function.
        assert!((cornette_shanks(0.0, 0.4) - rayleigh(0.4)).abs() < 1e-15);
        // Hazy: forward value 10 K, backward K.
        assert!((nishita_hazy(1.0) / nishita_hazy(-1.0) - 10.0).abs() < 1e-12);
    }

    #[test]
    fn bad_parameters_are_named() {
        assert!(PhaseFunction::CornetteShanks { g: 1.0 }.problem().is_some());
        assert!(
            PhaseFunction::HenyeyGreenstein { g: f64::NAN }
                .problem()
                .is_some()
        );
        let t = PhaseFunction::Tabulated {
            angles_deg: vec![0.0, 90.0],
            values: vec![1.0, 1.0],
        };
        assert!(t.problem().unwrap().contains("0 to 180"));
    }
}
