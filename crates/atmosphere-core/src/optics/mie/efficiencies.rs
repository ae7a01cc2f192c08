//! Efficiencies (cross-sections over the geometric cross-section pi r^2) and the
//! asymmetry parameter of a sphere from its coefficients (Bohren and Huffman 1983,
//! Eq. 4.61 and 4.62, and the series for g Q_sca on their p. 120).

use num_complex::Complex64;

use super::coefficients::MieCoefficients;

/// Q_ext, Q_sca, Q_back and g = <cos theta> of one sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Efficiencies {
    pub extinction: f64,
    pub scattering: f64,
    /// 4 pi times the differential cross-section at 180 degrees over pi r^2.
    pub backscattering: f64,
    pub asymmetry: f64,
}

impl Efficiencies {
    pub fn of(c: &MieCoefficients) -> Efficiencies {
        let x = c.size_parameter;
        let (mut ext, mut sca, mut g_sca) = (0.0, 0.0, 0.0);
        let mut back = Complex64::new(0.0, 0.0);
        let terms = c.terms();
        for i in 0..terms {
            let n = (i + 1) as f64;
            let (a, b) = (c.a[i], c.b[i]);
            ext += (2.0 * n + 1.0) * (a + b).re;
            sca += (2.0 * n + 1.0) * (a.norm_sqr() + b.norm_sqr());
            g_sca += (2.0 * n + 1.0) / (n * (n + 1.0)) * (a * b.conj()).re;
            if i + 1 < terms {
                let (a1, b1) = (c.a[i + 1], c.b[i + 1]);
                g_sca += n * (n + 2.0) / (n + 1.0) * (a * a1.conj() + b * b1.conj()).re;
            }
            let sign = if i % 2 == 0 { -1.0 } else { 1.0 };
            back += sign * (2.0 * n + 1.0) * (a - b);
        }
        let x2 = x * x;
        let scattering = 2.0 / x2 * sca;
        Efficiencies {
            extinction: 2.0 / x2 * ext,
            scattering,
            backscattering: back.norm_sqr() / x2,
            asymmetry: 4.0 / x2 * g_sca / scattering,
        }
    }
}
