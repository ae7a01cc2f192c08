//! The Lorenz-Mie coefficients a_n and b_n of a homogeneous sphere (Bohren and Huffman
//! 1983, Eq. 4.88), from the logarithmic derivative D_n(mx) = psi_n'(mx) / psi_n(mx) by
//! downward recurrence (Eq. 4.89) from Lentz's continued fraction, and the Riccati-Bessel functions psi_n(x) and
//! xi_n(x) = psi_n(x) - i chi_n(x) by upward recurrence; Wiscombe's (1980) number of
//! terms. Nothing overflows: D_n stays bounded downward, and psi_n, chi_n stay within
//! exp(x^(1/3)) of 1 up to Wiscombe's n.

use num_complex::Complex64;

use super::error::MieError;
use super::limits::{MAX_REFRACTIVE_PART, MAX_SIZE_PARAMETER, MIN_SIZE_PARAMETER};

/// The coefficients a_n and b_n, n = 1..=N, of a sphere of size parameter x and relative
/// refractive index m = n + i k (k >= 0 absorbs).
#[derive(Clone, Debug, PartialEq)]
pub struct MieCoefficients {
    pub size_parameter: f64,
    /// a_1..a_N at index 0..N-1.
    pub a: Vec<Complex64>,
    /// b_1..b_N at index 0..N-1.
    pub b: Vec<Complex64>,
}

/// Wiscombe's (1980, Eq. 13 and after) number of terms: x + 4 x^(1/3) + 1 up to x = 8,
/// x + 4.05 x^(1/3) + 2 up to 4200, x + 4 x^(1/3) + 2 beyond (kept past 2e4).
pub fn wiscombe_terms(x: f64) -> usize {
    let cube_root = x.cbrt();
    let n = if x <= 8.0 {
        x + 4.0 * cube_root + 1.0
    } else if x < 4200.0 {
        x + 4.05 * cube_root + 2.0
    } else {
        x + 4.0 * cube_root + 2.0
    };
    (n as usize).max(1)
}

/// Checks that m and x are in the range the code computes right.
pub fn check_inputs(m: Complex64, x: f64) -> Result<(), MieError> {
    if !(MIN_SIZE_PARAMETER..=MAX_SIZE_PARAMETER).contains(&x) {
        return Err(MieError::SizeParameter(x));
    }
    let real_ok = m.re > 0.0 && m.re <= MAX_REFRACTIVE_PART;
    let imaginary_ok = (0.0..=MAX_REFRACTIVE_PART).contains(&m.im);
    if !real_ok || !imaginary_ok || m == Complex64::new(1.0, 0.0) {
        return Err(MieError::RefractiveIndex { re: m.re, im: m.im });
    }
    Ok(())
}

/// D_n(z) at one n by Lentz's (1976) continued fraction for J_(n-1/2)(z) / J_(n+1/2)(z)
/// (D_n = -n/z + that ratio), evaluated by the modified Lentz method, as Wiscombe (1980)
/// starts the downward recurrence: a plain start (D = 0) is forgotten only slowly when
/// the start lies near |z|, and leaves errors of 1e-5 at x = 100.
fn log_derivative_by_continued_fraction(z: Complex64, n: usize) -> Complex64 {
    let tiny = Complex64::new(1e-300, 0.0);
    let nu = n as f64 + 0.5;
    // a_k = (-1)^(k+1) 2 (nu + k - 1) / z.
    let term = |k: usize| {
        let sign = if k % 2 == 1 { 1.0 } else { -1.0 };
        sign * 2.0 * (nu + k as f64 - 1.0) / z
    };
    let mut ratio = term(1);
    let (mut c, mut d) = (ratio, Complex64::new(0.0, 0.0));
    for k in 2..1_000_000 {
        let a = term(k);
        d = a + d;
        d = if d == Complex64::new(0.0, 0.0) {
            tiny
        } else {
            1.0 / d
        };
        c = a + 1.0 / c;
        if c == Complex64::new(0.0, 0.0) {
            c = tiny;
        }
        let delta = c * d;
        ratio *= delta;
        if (delta - 1.0).norm() < 1e-16 {
            break;
        }
    }
    -(n as f64) / z + ratio
}

/// D_n(z) for n = 0..=terms by downward recurrence D_(n-1) = n/z - 1/(D_n + n/z)
/// (Bohren and Huffman 1983, Eq. 4.89), stable in that direction, from D at
/// max(terms, |z|) + 16 by the continued fraction.
fn log_derivatives(z: Complex64, terms: usize) -> Vec<Complex64> {
    let start = terms.max(z.norm().ceil() as usize) + 16;
    let mut d = vec![Complex64::new(0.0, 0.0); start + 1];
    d[start] = log_derivative_by_continued_fraction(z, start);
    for n in (1..=start).rev() {
        let n_over_z = n as f64 / z;
        d[n - 1] = n_over_z - 1.0 / (d[n] + n_over_z);
    }
    d.truncate(terms + 1);
    d
}

impl MieCoefficients {
    /// a_n and b_n of a sphere of relative refractive index `m` and size parameter `x`.
    pub fn new(m: Complex64, x: f64) -> Result<MieCoefficients, MieError> {
        check_inputs(m, x)?;
        let terms = wiscombe_terms(x);
        let d = log_derivatives(m * x, terms);
        // psi_(n-1), psi_n and chi_(n-1), chi_n from psi_(-1) = cos x, psi_0 = sin x,
        // chi_(-1) = -sin x, chi_0 = cos x (Bohren and Huffman 1983, Eq. 4.71 and 4.72).
        let (mut psi_previous, mut psi) = (x.cos(), x.sin());
        let (mut chi_previous, mut chi) = (-x.sin(), x.cos());
        let mut a = Vec::with_capacity(terms);
        let mut b = Vec::with_capacity(terms);
        for n in 1..=terms {
            let n_f = n as f64;
            let factor = (2.0 * n_f - 1.0) / x;
            let psi_next = factor * psi - psi_previous;
            let chi_next = factor * chi - chi_previous;
            (psi_previous, psi) = (psi, psi_next);
            (chi_previous, chi) = (chi, chi_next);
            let xi = Complex64::new(psi, -chi);
            let xi_previous = Complex64::new(psi_previous, -chi_previous);
            let da = d[n] / m + n_f / x;
            let db = d[n] * m + n_f / x;
            a.push((da * psi - psi_previous) / (da * xi - xi_previous));
            b.push((db * psi - psi_previous) / (db * xi - xi_previous));
        }
        Ok(MieCoefficients {
            size_parameter: x,
            a,
            b,
        })
    }

    /// N, the number of terms.
    pub fn terms(&self) -> usize {
        self.a.len()
    }
}
