//! Perceived colour difference: CIE XYZ to CIELAB (D65 white) and the CIEDE2000 formula
//! (CIE 142-2001, in the form and with the test data of Sharma, Wu and Dalal 2005,
//! "The CIEDE2000 color-difference formula: implementation notes, supplementary test
//! data, and mathematical observations", Eq. 1-23).

/// The D65 white point with Y = 1 (CIE 1931 2 deg observer).
pub const D65_WHITE: [f64; 3] = [0.95047, 1.0, 1.08883];

/// CIELAB of an XYZ colour relative to `white` (same scale as `xyz`).
pub fn xyz_to_lab(xyz: [f64; 3], white: [f64; 3]) -> [f64; 3] {
    const EPSILON: f64 = 216.0 / 24389.0;
    const KAPPA: f64 = 24389.0 / 27.0;
    let f = |t: f64| {
        if t > EPSILON {
            t.cbrt()
        } else {
            (KAPPA * t + 16.0) / 116.0
        }
    };
    let [fx, fy, fz] = [0, 1, 2].map(|i| f(xyz[i] / white[i]));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// Hue angle in degrees in [0, 360); 0 for a neutral colour (Sharma Eq. 4).
fn hue_deg(b: f64, a: f64) -> f64 {
    if a == 0.0 && b == 0.0 {
        0.0
    } else {
        b.atan2(a).to_degrees().rem_euclid(360.0)
    }
}

/// CIEDE2000 difference between two CIELAB colours, with kL = kC = kH = 1.
pub fn ciede2000(lab1: [f64; 3], lab2: [f64; 3]) -> f64 {
    let [l1, a1, b1] = lab1;
    let [l2, a2, b2] = lab2;
    // Eq. 2-5: a' stretched by G, C' and h'.
    let c_mean = 0.5 * ((a1 * a1 + b1 * b1).sqrt() + (a2 * a2 + b2 * b2).sqrt());
    let c7 = c_mean.powi(7);
    let g = 0.5 * (1.0 - (c7 / (c7 + 25f64.powi(7))).sqrt());
    let a1p = (1.0 + g) * a1;
    let a2p = (1.0 + g) * a2;
    let c1p = (a1p * a1p + b1 * b1).sqrt();
    let c2p = (a2p * a2p + b2 * b2).sqrt();
    let h1p = hue_deg(b1, a1p);
    let h2p = hue_deg(b2, a2p);
    // Eq. 8-10: differences.
    let dl = l2 - l1;
    let dc = c2p - c1p;
    let dh_deg = if c1p * c2p == 0.0 {
        0.0
    } else if (h2p - h1p).abs() <= 180.0 {
        h2p - h1p
    } else if h2p - h1p > 180.0 {
        h2p - h1p - 360.0
    } else {
        h2p - h1p + 360.0
    };
    let dh = 2.0 * (c1p * c2p).sqrt() * (0.5 * dh_deg).to_radians().sin();
    // Eq. 12-22: weights.
    let l_mean = 0.5 * (l1 + l2);
    let cp_mean = 0.5 * (c1p + c2p);
    let hp_mean = if c1p * c2p == 0.0 {
        h1p + h2p
    } else if (h1p - h2p).abs() <= 180.0 {
        0.5 * (h1p + h2p)
    } else if h1p + h2p < 360.0 {
        0.5 * (h1p + h2p + 360.0)
    } else {
        0.5 * (h1p + h2p - 360.0)
    };
    let t = 1.0 - 0.17 * (hp_mean - 30.0).to_radians().cos()
        + 0.24 * (2.0 * hp_mean).to_radians().cos()
        + 0.32 * (3.0 * hp_mean + 6.0).to_radians().cos()
        - 0.20 * (4.0 * hp_mean - 63.0).to_radians().cos();
    let d_theta = 30.0 * (-((hp_mean - 275.0) / 25.0).powi(2)).exp();
    let cp7 = cp_mean.powi(7);
    let r_c = 2.0 * (cp7 / (cp7 + 25f64.powi(7))).sqrt();
    let l50 = (l_mean - 50.0).powi(2);
    let s_l = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let s_c = 1.0 + 0.045 * cp_mean;
    let s_h = 1.0 + 0.015 * cp_mean * t;
    let r_t = -(2.0 * d_theta).to_radians().sin() * r_c;
    let (x, y, z) = (dl / s_l, dc / s_c, dh / s_h);
    (x * x + y * y + z * z + r_t * y * z).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pairs of Sharma, Wu and Dalal 2005, Table 1 (pair numbers in the comments).
    #[test]
    fn matches_the_published_test_data() {
        let pairs = [
            // 1
            ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0425),
            // 7
            ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0], 2.3669),
            // 13: hue mean across 0/360
            ([50.0, 2.49, -0.001], [50.0, -2.49, 0.0009], 7.1792),
            // 17
            ([50.0, 2.5, 0.0], [56.0, -27.0, -3.0], 31.9030),
            // 18
            ([50.0, 2.5, 0.0], [58.0, 24.0, 15.0], 19.4535),
            // 19
            ([50.0, 2.5, 0.0], [50.0, 3.1736, 0.5854], 1.0000),
            // 25
            (
                [60.2574, -34.0099, 36.2677],
                [60.4626, -34.1751, 39.4387],
                1.2644,
            ),
            // 34
            ([2.0776, 0.0795, -1.135], [0.9033, -0.0636, -0.5514], 0.9082),
        ];
        for (a, b, expected) in pairs {
            let d = ciede2000(a, b);
            assert!(
                (d - expected).abs() < 1e-4,
                "{a:?} {b:?}: {d} vs {expected}"
            );
            assert!((ciede2000(b, a) - d).abs() < 1e-12, "not symmetric");
        }
        assert_eq!(ciede2000([40.0, 10.0, -5.0], [40.0, 10.0, -5.0]), 0.0);
    }

    #[test]
    fn lab_of_white_and_grey() {
        let white = xyz_to_lab(D65_WHITE, D65_WHITE);
        assert!((white[0] - 100.0).abs() < 1e-9 && white[1].abs() < 1e-9);
        // 18 % grey has L* = 49.5.
        let grey = xyz_to_lab(D65_WHITE.map(|c| 0.18 * c), D65_WHITE);
        assert!((grey[0] - 49.496).abs() < 1e-3, "{grey:?}");
        // The linear part near black: Y = 0.001 -> L* = 0.903.
        let dark = xyz_to_lab(D65_WHITE.map(|c| 0.001 * c), D65_WHITE);
        assert!((dark[0] - 0.9033).abs() < 1e-3, "{dark:?}");
    }
}
