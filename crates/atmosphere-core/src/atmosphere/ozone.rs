//! Ozone absorption cross-section (Serdyuchenko et al. 2014).
//!
//! Data: `assets/ozone_cross_section_10nm.csv`, 360..830 nm in 10 nm steps, the
//! `kOzoneCrossSection` values of Bruneton's 2017 demo (`atmosphere/demo/demo.cc`),
//! averaged over [lambda, lambda + 10 nm); the demo's comment gives the temperature as
//! 233 K. See `assets/CREDITS.md`.

use std::sync::LazyLock;

use crate::atmosphere::tabulated::Tabulated;

static TABLE: LazyLock<Tabulated<1>> = LazyLock::new(|| {
    Tabulated::parse(
        "ozone_cross_section_10nm.csv",
        include_str!("../../../../assets/ozone_cross_section_10nm.csv"),
        "wavelength_nm,cross_section_m2",
    )
});

/// Absorption cross-section of one ozone molecule, m^2, at `lambda_nm`: linear
/// interpolation inside 360..830 nm, the end values outside.
pub fn serdyuchenko_cross_section_m2(lambda_nm: f64) -> f64 {
    TABLE.interpolate_clamped(lambda_nm)[0]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Peak number density of the "earth" preset (300 DU over a 15 km tent), m^-3.
    const PEAK_DENSITY_PER_M3: f64 = 5.374e18;

    #[test]
    fn design_absorption_coefficients() {
        for (nm, k) in [(680.0, 6.4972e-7), (550.0, 1.8809e-6), (440.0, 8.5017e-8)] {
            let got = PEAK_DENSITY_PER_M3 * serdyuchenko_cross_section_m2(nm);
            assert!((got / k - 1.0).abs() < 1e-4, "{nm} nm: {got} vs {k}");
        }
    }

    #[test]
    fn clamps_and_interpolates() {
        assert_eq!(serdyuchenko_cross_section_m2(200.0), 1.18e-27);
        assert_eq!(serdyuchenko_cross_section_m2(900.0), 7.105e-27);
        let mid = serdyuchenko_cross_section_m2(555.0);
        assert!((mid / (0.5 * (3.5e-25 + 4.266e-25)) - 1.0).abs() < 1e-12);
        assert_eq!(TABLE.wavelengths_nm().len(), 48);
    }
}
