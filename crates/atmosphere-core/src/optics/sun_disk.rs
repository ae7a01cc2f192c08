//! The radiance of the solar disk with limb darkening, at the top of the atmosphere.
//!
//! The disk's brightness falls towards its edge as `I(mu) / I(1) = mu^alpha(lambda)` with
//! `mu` the cosine of the angle between the line of sight and the normal on the solar
//! surface and `alpha(lambda) = -0.023 + 0.292 / lambda_um` (Hestroffer and Magnan 1998,
//! "Wavelength dependency of the Solar limb darkening", A&A 333, 338-342). The centre's
//! radiance is scaled so that the disk integrates to the solar irradiance `E`: over a disk
//! of angular radius `a` (solid angle `Omega = 2 pi (1 - cos a)`) the mean of `mu^alpha`
//! is `2 / (alpha + 2)`, so `I(1) = E / Omega * (alpha + 2) / 2`.
//!
//! The shaders' sun disk (`shaders/common/sun_disk.wgsl`) is the GPU twin.

use std::f64::consts::PI;

/// The limb-darkening exponent `alpha(lambda)` of Hestroffer and Magnan 1998.
pub fn limb_darkening_exponent(lambda_nm: f64) -> f64 {
    -0.023 + 0.292 / (lambda_nm * 1e-3)
}

/// Radiance (W m^-2 sr^-1 nm^-1) at the centre of a disk of angular radius
/// `angular_radius_rad` whose irradiance is `irradiance_w_m2_nm`.
pub fn centre_radiance(irradiance_w_m2_nm: f64, angular_radius_rad: f64, lambda_nm: f64) -> f64 {
    let solid_angle = 2.0 * PI * (1.0 - angular_radius_rad.cos());
    irradiance_w_m2_nm / solid_angle * (limb_darkening_exponent(lambda_nm) + 2.0) / 2.0
}

/// The fraction `mu^alpha` of the centre's radiance seen at angle `angle_rad` from the
/// disk's centre; zero outside the disk.
pub fn limb_darkening(angle_rad: f64, angular_radius_rad: f64, lambda_nm: f64) -> f64 {
    let x = angle_rad / angular_radius_rad;
    if x.is_nan() || x >= 1.0 {
        return 0.0;
    }
    (1.0 - x * x)
        .sqrt()
        .powf(limb_darkening_exponent(lambda_nm))
}

/// Radiance of the disk seen at angle `angle_rad` from its centre, before the
/// atmosphere's transmittance.
pub fn radiance(
    irradiance_w_m2_nm: f64,
    angular_radius_rad: f64,
    lambda_nm: f64,
    angle_rad: f64,
) -> f64 {
    centre_radiance(irradiance_w_m2_nm, angular_radius_rad, lambda_nm)
        * limb_darkening(angle_rad, angular_radius_rad, lambda_nm)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The disk integrates to the irradiance, and the limb is darker in blue than in red.
    #[test]
    fn disk_integrates_to_the_irradiance() {
        let a = 0.004675;
        for lambda in [440.0, 550.0, 680.0] {
            let n = 20_000;
            let mut sum = 0.0;
            for k in 0..n {
                // Rings of equal width in angle, solid angle 2 pi sin(t) dt.
                let t = (k as f64 + 0.5) / n as f64 * a;
                sum += radiance(1.85, a, lambda, t) * 2.0 * PI * t.sin() * (a / n as f64);
            }
            assert!((sum / 1.85 - 1.0).abs() < 1e-3, "{lambda}: {sum}");
        }
        assert!(limb_darkening(0.9 * a, a, 440.0) < limb_darkening(0.9 * a, a, 680.0));
        assert_eq!(limb_darkening(a, a, 550.0), 0.0);
        assert_eq!(limb_darkening(0.0, a, 550.0), 1.0);
    }
}
