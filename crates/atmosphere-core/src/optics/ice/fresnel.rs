//! Reflection and refraction at a plane boundary (Born and Wolf 1999, section 1.5):
//! Fresnel's reflectance of unpolarised light, the mean of the s and p reflectances
//! (Eq. 1.5.21a), and Snell's refracted direction.

use glam::DVec3;

/// The reflectance of unpolarised light going from index `n1` to `n2` at incidence
/// cosine `cos_i` (> 0); 1 past the critical angle.
pub fn unpolarised_reflectance(n1: f64, n2: f64, cos_i: f64) -> f64 {
    let sin_t2 = (n1 / n2).powi(2) * (1.0 - cos_i * cos_i);
    if sin_t2 >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    let s = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let p = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    0.5 * (s * s + p * p)
}

/// The mirror direction of `d` at a surface of unit normal `n` (either side).
pub fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

/// The refracted direction of `d` into the side `normal` points away from, with
/// `eta` = n1 / n2, or None past the critical angle. `normal` faces the incident side.
pub fn refract(d: DVec3, normal: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -d.dot(normal);
    let sin_t2 = eta * eta * (1.0 - cos_i * cos_i);
    if sin_t2 >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * normal).normalize())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_incidence_brewster_and_total_reflection() {
        // ((n - 1) / (n + 1))^2 at normal incidence, both ways.
        let r = unpolarised_reflectance(1.0, 1.5, 1.0);
        assert!((r - 0.04).abs() < 1e-15);
        assert!((unpolarised_reflectance(1.5, 1.0, 1.0) - 0.04).abs() < 1e-15);
        // At Brewster's angle p vanishes: R = R_s / 2.
        let brewster = 1.5f64.atan();
        let (ci, ct) = (brewster.cos(), (brewster.sin() / 1.5).asin().cos());
        let rs = ((ci - 1.5 * ct) / (ci + 1.5 * ct)).powi(2);
        let r = unpolarised_reflectance(1.0, 1.5, ci);
        assert!((r - 0.5 * rs).abs() < 1e-15);
        // Past the critical angle of ice (49.8 degrees).
        assert_eq!(
            unpolarised_reflectance(1.31, 1.0, 50f64.to_radians().cos()),
            1.0
        );
        let d = DVec3::new(50f64.to_radians().sin(), 0.0, 50f64.to_radians().cos());
        assert!(refract(d, DVec3::NEG_Z, 1.31).is_none());
    }

    #[test]
    fn snell_holds() {
        let i = 30f64.to_radians();
        let d = DVec3::new(i.sin(), 0.0, -i.cos());
        let t = refract(d, DVec3::Z, 1.0 / 1.31).unwrap();
        assert!((t.x - i.sin() / 1.31).abs() < 1e-15 && t.z < 0.0);
        assert!((t.length() - 1.0).abs() < 1e-15);
    }
}
