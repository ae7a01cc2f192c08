//! The scattering amplitudes S1 and S2 of a sphere at a scattering angle (Bohren and
//! Huffman 1983, Eq. 4.74), with the angular functions pi_n and tau_n by their upward
//! recurrences (Eq. 4.47), and the normalised phase function they give.

use std::f64::consts::PI;

use num_complex::Complex64;

use super::coefficients::MieCoefficients;

/// S1 and S2 at the cosine `mu` of the scattering angle (1: forward).
pub fn amplitudes(c: &MieCoefficients, mu: f64) -> (Complex64, Complex64) {
    let (mut s1, mut s2) = (Complex64::new(0.0, 0.0), Complex64::new(0.0, 0.0));
    // pi_0 = 0, pi_1 = 1.
    let (mut pi_previous, mut pi) = (0.0, 1.0);
    for i in 0..c.terms() {
        let n = (i + 1) as f64;
        let tau = n * mu * pi - (n + 1.0) * pi_previous;
        let factor = (2.0 * n + 1.0) / (n * (n + 1.0));
        s1 += factor * (c.a[i] * pi + c.b[i] * tau);
        s2 += factor * (c.a[i] * tau + c.b[i] * pi);
        let pi_next = ((2.0 * n + 1.0) * mu * pi - (n + 1.0) * pi_previous) / n;
        (pi_previous, pi) = (pi, pi_next);
    }
    (s1, s2)
}

/// (|S1|^2 + |S2|^2) / 2 at `mu`: k^2 times the differential scattering cross-section of
/// unpolarised light.
pub fn unpolarised_intensity(c: &MieCoefficients, mu: f64) -> f64 {
    let (s1, s2) = amplitudes(c, mu);
    0.5 * (s1.norm_sqr() + s2.norm_sqr())
}

/// The phase function of one sphere at `mu`, sr^-1, normalised to 1 over the sphere:
/// (|S1|^2 + |S2|^2) / (2 pi x^2 Q_sca), given its scattering efficiency.
pub fn phase_function(c: &MieCoefficients, scattering_efficiency: f64, mu: f64) -> f64 {
    let x = c.size_parameter;
    unpolarised_intensity(c, mu) / (PI * x * x * scattering_efficiency)
}
