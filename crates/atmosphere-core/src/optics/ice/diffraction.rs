//! Fraunhofer diffraction of a crystal's projected area, taken as a disc of the same
//! area (Macke, Mueller and Raschke 1996, section 2; Takano and Liou 1989): the
//! diffracted power equals the light the area intercepts (half of Q_ext = 2, van de Hulst
//! 1957, section 8.22), spread as the Airy pattern
//! f(theta) = (ka)^2 / (4 pi) [2 J1(v) / v]^2, v = k a sin theta, of unit integral in the
//! small-angle limit; nothing is diffracted backwards (theta > 90 degrees).

use std::f64::consts::PI;

/// J1 by Abramowitz and Stegun 1964, Eq. 9.4.4 (|v| <= 3, error below 1.3e-8 |v|) and
/// 9.4.6 (v > 3, error below 1e-7 relative to the envelope).
pub fn bessel_j1(v: f64) -> f64 {
    let a = v.abs();
    let value = if a <= 3.0 {
        let y = (a / 3.0).powi(2);
        a * (0.5
            + y * (-0.562_499_85
                + y * (0.210_935_73
                    + y * (-0.039_542_89
                        + y * (0.004_433_19 + y * (-0.000_317_61 + y * 0.000_011_09))))))
    } else {
        let y = 3.0 / a;
        let f = 0.797_884_56
            + y * (0.000_001_56
                + y * (0.016_596_67
                    + y * (0.000_171_05
                        + y * (-0.002_495_11 + y * (0.001_136_53 - y * 0.000_200_33)))));
        let theta = a - 2.356_194_49
            + y * (0.124_996_12
                + y * (0.000_056_50
                    + y * (-0.006_378_79
                        + y * (0.000_743_48 + y * (0.000_798_24 - y * 0.000_291_66)))));
        f * theta.cos() / a.sqrt()
    };
    // J1 is odd.
    if v < 0.0 { -value } else { value }
}

/// The Airy pattern of a disc of `ka` = k times its radius at scattering angle `theta`
/// (radians), sr^-1; zero past 90 degrees.
pub fn airy_pattern(ka: f64, theta: f64) -> f64 {
    if theta > 0.5 * PI {
        return 0.0;
    }
    let v = ka * theta.sin();
    let amplitude = if v < 1e-8 {
        1.0
    } else {
        2.0 * bessel_j1(v) / v
    };
    ka * ka / (4.0 * PI) * amplitude * amplitude
}

#[cfg(test)]
mod tests {
    use super::*;

    /// J1(v) = (1 / pi) int_0^pi cos(tau - v sin tau) d tau (Watson 1944, section 2.2),
    /// by the trapezoid rule, exact to rounding for a periodic integrand with enough
    /// points.
    fn j1_by_integral(v: f64) -> f64 {
        let n = 2000;
        let h = PI / n as f64;
        (0..=n)
            .map(|i| {
                let t = h * i as f64;
                let w = if i == 0 || i == n { 0.5 } else { 1.0 };
                w * (t - v * t.sin()).cos()
            })
            .sum::<f64>()
            * h
            / PI
    }

    #[test]
    fn j1_matches_its_integral_and_the_pattern_is_normalised() {
        for v in [0.0, 0.1, 1.0, 2.9, 3.0, 3.1, 3.8317, 7.0, 20.0, 100.0] {
            let (a, b) = (bessel_j1(v), j1_by_integral(v));
            assert!((a - b).abs() < 1e-7, "J1({v}) = {a}, integral {b}");
        }
        assert!((bessel_j1(-2.0) + bessel_j1(2.0)).abs() < 1e-15);
        // Unit integral over small angles for ka = 200.
        let ka = 200.0;
        let n = 200_000;
        let h = 0.5 * PI / n as f64;
        let total: f64 = (1..n)
            .map(|i| {
                let t = h * i as f64;
                airy_pattern(ka, t) * 2.0 * PI * t.sin() * h
            })
            .sum();
        // The Airy ring energy past an angle falls as 2 / (pi v): 3e-3 beyond 90 degrees here.
        assert!((total - 1.0).abs() < 5e-3, "{total}");
    }
}
