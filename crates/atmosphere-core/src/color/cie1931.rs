//! CIE 1931 2-degree standard observer colour-matching functions.
//!
//! Data: `assets/cie1931_2deg_cmf.csv`, 360..830 nm at 1 nm, the CIE 1931 table as
//! distributed by CVRL (cvrl.org) and dumped from the `colour-science` package; see
//! `assets/CREDITS.md`.

use std::sync::LazyLock;

use crate::atmosphere::tabulated::Tabulated;

/// Shortest wavelength of the table, in nm.
pub const CMF_MIN_NM: f64 = 360.0;
/// Longest wavelength of the table, in nm.
pub const CMF_MAX_NM: f64 = 830.0;

static TABLE: LazyLock<Tabulated<3>> = LazyLock::new(|| {
    Tabulated::parse(
        "cie1931_2deg_cmf.csv",
        include_str!("../../../../assets/cie1931_2deg_cmf.csv"),
        "wavelength_nm,xbar,ybar,zbar",
    )
});

/// `[xbar, ybar, zbar]` at `lambda_nm`: linear interpolation of the 1 nm table, zero
/// outside [`CMF_MIN_NM`, `CMF_MAX_NM`] (and for NaN).
pub fn color_matching(lambda_nm: f64) -> [f64; 3] {
    if !(CMF_MIN_NM..=CMF_MAX_NM).contains(&lambda_nm) {
        return [0.0; 3];
    }
    TABLE.interpolate_clamped(lambda_nm)
}

/// The tabulated wavelengths (nm) of the colour-matching functions, in increasing order.
pub fn table_wavelengths_nm() -> &'static [f64] {
    TABLE.wavelengths_nm()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Trapezoid integral over the table of component `k`.
    fn integral(k: usize) -> f64 {
        let nm = table_wavelengths_nm();
        nm.windows(2)
            .map(|w| 0.5 * (w[1] - w[0]) * (color_matching(w[0])[k] + color_matching(w[1])[k]))
            .sum()
    }

    #[test]
    fn table_parses_and_spans_360_to_830() {
        let nm = table_wavelengths_nm();
        assert_eq!(nm.len(), 471);
        assert_eq!(nm[0], CMF_MIN_NM);
        assert_eq!(*nm.last().unwrap(), CMF_MAX_NM);
    }

    #[test]
    fn ybar_peaks_at_555_nm_with_value_one() {
        let nm = table_wavelengths_nm();
        let peak = nm
            .iter()
            .copied()
            .max_by(|a, b| color_matching(*a)[1].total_cmp(&color_matching(*b)[1]))
            .unwrap();
        assert_eq!(peak, 555.0);
        assert!((color_matching(555.0)[1] - 1.0).abs() < 1e-3);
    }

    #[test]
    fn integrals_are_equal_energy_white_and_match_published_ybar_sum() {
        let [x, y, z] = [integral(0), integral(1), integral(2)];
        // Published sum of ybar at 1 nm, 360..830 nm: 106.856895.
        assert!((y - 106.856895).abs() < 1e-3, "integral of ybar {y}");
        for v in [x, z] {
            assert!((v / y - 1.0).abs() < 0.01, "{x} {y} {z}");
        }
    }

    #[test]
    fn zero_outside_and_interpolates_inside() {
        assert_eq!(color_matching(359.9), [0.0; 3]);
        assert_eq!(color_matching(830.1), [0.0; 3]);
        assert_eq!(color_matching(f64::NAN), [0.0; 3]);
        let (a, b, m) = (
            color_matching(550.0),
            color_matching(551.0),
            color_matching(550.5),
        );
        for k in 0..3 {
            assert!((m[k] - 0.5 * (a[k] + b[k])).abs() < 1e-15);
        }
    }
}
