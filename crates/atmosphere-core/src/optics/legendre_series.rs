//! A phase function as a Legendre series on the cosine nu of the scattering angle,
//! p(nu) = sum_l (2l + 1) / (4 pi) chi_l P_l(nu), with chi_0 = 1 (unit integral over the
//! sphere) and chi_1 = g. On the sphere, the convolution of two phase functions
//! multiplies their coefficients (the addition theorem of spherical harmonics), which is
//! how `multiple_scattering_phase.rs` forms Riley et al.'s (2004) A_n.

use std::f64::consts::PI;

/// Coefficients chi_0..=chi_L of a phase function, chi_0 = 1.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendreSeries {
    coefficients: Vec<f64>,
}

/// Calls `each(l, P_l(x))` for l = 0..=degree, by the upward recurrence (stable on
/// [-1, 1]).
fn for_each_legendre(x: f64, degree: usize, mut each: impl FnMut(usize, f64)) {
    let (mut previous, mut current) = (1.0, x);
    each(0, 1.0);
    if degree >= 1 {
        each(1, x);
    }
    for l in 1..degree {
        let l_f = l as f64;
        let next = ((2.0 * l_f + 1.0) * x * current - l_f * previous) / (l_f + 1.0);
        (previous, current) = (current, next);
        each(l + 1, current);
    }
}

impl LegendreSeries {
    /// The series of a phase function known at the nodes of a Gauss-Legendre rule in nu
    /// (`values[k]` at `rule[k].0`): chi_l = 2 pi sum_k w_k p(nu_k) P_l(nu_k), exact when
    /// p P_l is a polynomial the rule integrates, divided by chi_0 so the series has unit
    /// integral.
    pub fn from_gauss_rule(rule: &[(f64, f64)], values: &[f64], degree: usize) -> LegendreSeries {
        let mut chi = vec![0.0; degree + 1];
        for (&(nu, w), &p) in rule.iter().zip(values) {
            let weight = 2.0 * PI * w * p;
            for_each_legendre(nu, degree, |l, p_l| chi[l] += weight * p_l);
        }
        let norm = chi[0];
        chi.iter_mut().for_each(|c| *c /= norm);
        LegendreSeries { coefficients: chi }
    }

    /// The series of Henyey and Greenstein's (1941) phase function of asymmetry `g` in
    /// (-1, 1), to `degree`: chi_l = g^l exactly.
    pub fn henyey_greenstein(g: f64, degree: usize) -> LegendreSeries {
        LegendreSeries::from_coefficients((0..=degree).map(|l| g.powi(l as i32)).collect())
    }

    /// A series from its coefficients (chi_0 is taken as 1).
    pub fn from_coefficients(mut coefficients: Vec<f64>) -> LegendreSeries {
        if coefficients.is_empty() {
            coefficients.push(1.0);
        }
        coefficients[0] = 1.0;
        LegendreSeries { coefficients }
    }

    /// chi_0..=chi_L.
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// L, the highest degree.
    pub fn degree(&self) -> usize {
        self.coefficients.len() - 1
    }

    /// g = chi_1, the mean cosine of the scattering angle.
    pub fn asymmetry(&self) -> f64 {
        self.coefficients.get(1).copied().unwrap_or(0.0)
    }

    /// The phase function at `nu`, sr^-1.
    pub fn eval(&self, nu: f64) -> f64 {
        let mut sum = 0.0;
        for_each_legendre(nu.clamp(-1.0, 1.0), self.degree(), |l, p_l| {
            sum += (2 * l + 1) as f64 * self.coefficients[l] * p_l;
        });
        sum / (4.0 * PI)
    }

    /// The fraction scattered into the forward hemisphere, 2 pi times the integral of
    /// p over nu in [0, 1]: 1/2 + 1/2 sum over odd l of chi_l (P_(l-1)(0) - P_(l+1)(0)),
    /// from (2l + 1) P_l = P_(l+1)' - P_(l-1)'.
    pub fn forward_fraction(&self) -> f64 {
        // P_l(0) for even l: P_(l+2)(0) = -(l + 1) / (l + 2) P_l(0).
        let mut p_even = 1.0;
        let mut sum = 0.5;
        for l in (1..=self.degree()).step_by(2) {
            let below = p_even;
            p_even *= -(l as f64) / (l as f64 + 1.0);
            sum += 0.5 * self.coefficients[l] * (below - p_even);
        }
        sum
    }

    /// The series of the phase function convolved with itself n times (n >= 1):
    /// coefficients chi_l^n, cut after the last degree whose chi_l^n reaches `cut`
    /// (|chi_l| <= 1, so the terms cut are each below it).
    pub fn power(&self, n: u32, cut: f64) -> LegendreSeries {
        let powered: Vec<f64> = self.coefficients.iter().map(|c| c.powi(n as i32)).collect();
        let keep = powered.iter().rposition(|c| c.abs() >= cut).unwrap_or(0);
        LegendreSeries::from_coefficients(powered[..=keep].to_vec())
    }
}
