//! Extraterrestrial solar spectral irradiance (ASTM G-173-03, ETR column).
//!
//! Data: `assets/solar_irradiance_astm_g173_10nm.csv`, 360..830 nm in 10 nm steps, the
//! `kSolarIrradiance` values of Bruneton's 2017 demo (`atmosphere/demo/demo.cc`): the
//! ASTM G-173 values averaged over [lambda, lambda + 10 nm). See `assets/CREDITS.md`.

use std::sync::LazyLock;

use crate::atmosphere::tabulated::Tabulated;

static TABLE: LazyLock<Tabulated<1>> = LazyLock::new(|| {
    Tabulated::parse(
        "solar_irradiance_astm_g173_10nm.csv",
        include_str!("../../../../assets/solar_irradiance_astm_g173_10nm.csv"),
        "wavelength_nm,irradiance_w_m2_nm",
    )
});

/// Solar spectral irradiance at the top of the atmosphere (1 au), W m^-2 nm^-1, at
/// `lambda_nm`: linear interpolation inside 360..830 nm, the end values outside.
pub fn astm_g173_irradiance_w_m2_nm(lambda_nm: f64) -> f64 {
    TABLE.interpolate_clamped(lambda_nm)[0]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn design_values_exactly() {
        for (nm, e) in [(680.0, 1.474), (550.0, 1.8504), (440.0, 1.91198)] {
            assert!((astm_g173_irradiance_w_m2_nm(nm) - e).abs() < 1e-12, "{nm}");
        }
    }

    #[test]
    fn midway_is_the_mean_and_ends_clamp() {
        let mid = astm_g173_irradiance_w_m2_nm(445.0);
        assert!((mid - 0.5 * (1.91198 + 2.03474)).abs() < 1e-12);
        assert_eq!(astm_g173_irradiance_w_m2_nm(300.0), 1.11776);
        assert_eq!(astm_g173_irradiance_w_m2_nm(1000.0), 1.04992);
    }

    #[test]
    fn table_has_48_points() {
        assert_eq!(TABLE.wavelengths_nm().len(), 48);
        assert_eq!(TABLE.wavelengths_nm()[0], 360.0);
        assert_eq!(TABLE.wavelengths_nm()[47], 830.0);
    }
}
