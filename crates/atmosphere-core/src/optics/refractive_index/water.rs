//! Liquid water at 25 C from Hale and Querry 1973, "Optical constants of water in the
//! 200-nm to 200-um wavelength region", Applied Optics 12(3), 555-563, Table I (the
//! rows from 200 nm to 1 um): n linear in wavelength between rows, k linear in log k.

use num_complex::Complex64;
use thiserror::Error;

use crate::optics::refractive_index::tabulated::interpolate;

/// Vacuum wavelength (nm), n, k: Hale and Querry 1973, Table I.
const HALE_QUERRY_1973: [(f64, f64, f64); 33] = [
    (200.0, 1.396, 1.10e-7),
    (225.0, 1.373, 4.90e-8),
    (250.0, 1.362, 3.35e-8),
    (275.0, 1.354, 2.35e-8),
    (300.0, 1.349, 1.60e-8),
    (325.0, 1.346, 1.08e-8),
    (350.0, 1.343, 6.50e-9),
    (375.0, 1.341, 3.50e-9),
    (400.0, 1.339, 1.86e-9),
    (425.0, 1.338, 1.30e-9),
    (450.0, 1.337, 1.02e-9),
    (475.0, 1.336, 9.35e-10),
    (500.0, 1.335, 1.00e-9),
    (525.0, 1.334, 1.32e-9),
    (550.0, 1.333, 1.96e-9),
    (575.0, 1.333, 3.60e-9),
    (600.0, 1.332, 1.09e-8),
    (625.0, 1.332, 1.39e-8),
    (650.0, 1.331, 1.64e-8),
    (675.0, 1.331, 2.23e-8),
    (700.0, 1.331, 3.35e-8),
    (725.0, 1.330, 9.15e-8),
    (750.0, 1.330, 1.56e-7),
    (775.0, 1.330, 1.48e-7),
    (800.0, 1.329, 1.25e-7),
    (825.0, 1.329, 1.82e-7),
    (850.0, 1.329, 2.93e-7),
    (875.0, 1.328, 3.91e-7),
    (900.0, 1.328, 4.86e-7),
    (925.0, 1.328, 1.06e-6),
    (950.0, 1.327, 2.93e-6),
    (975.0, 1.327, 3.48e-6),
    (1000.0, 1.327, 2.89e-6),
];

/// The table's range of vacuum wavelengths, nm.
pub const WATER_WAVELENGTH_RANGE_NM: [f64; 2] = [200.0, 1000.0];

#[derive(Clone, Debug, Error, PartialEq)]
#[error(
    "water's refractive index is tabulated from 200 to 1000 nm (Hale and Querry 1973), not at \
     {0} nm; give --refractive-index for other wavelengths"
)]
pub struct OutsideWaterTable(pub f64);

/// The refractive index of liquid water at this vacuum wavelength.
pub fn water_refractive_index(wavelength_nm: f64) -> Result<Complex64, OutsideWaterTable> {
    let [lo, hi] = WATER_WAVELENGTH_RANGE_NM;
    if !(lo..=hi).contains(&wavelength_nm) {
        return Err(OutsideWaterTable(wavelength_nm));
    }
    Ok(interpolate(&HALE_QUERRY_1973, wavelength_nm))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_rows_are_returned_exactly_and_between_rows_interpolated() {
        let m = water_refractive_index(550.0).unwrap();
        assert_eq!(m, Complex64::new(1.333, 1.96e-9));
        let m = water_refractive_index(200.0).unwrap();
        assert_eq!(m, Complex64::new(1.396, 1.1e-7));
        let m = water_refractive_index(1000.0).unwrap();
        assert_eq!(m, Complex64::new(1.327, 2.89e-6));
        let m = water_refractive_index(662.5).unwrap();
        assert!((m.re - 1.331).abs() < 1e-12);
        assert!((m.im - (1.64e-8f64 * 2.23e-8).sqrt()).abs() < 1e-20);
    }

    #[test]
    fn wavelengths_outside_the_table_are_named() {
        for nm in [199.0, 1001.0, f64::NAN] {
            let e = water_refractive_index(nm).unwrap_err().to_string();
            assert!(e.contains("200 to 1000 nm"), "{e}");
        }
    }
}
