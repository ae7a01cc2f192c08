//! Ice Ih from Warren and Brandt 2008 ("Optical constants of ice from the ultraviolet to
//! the microwave: A revised compilation", Journal of Geophysical Research 113, D14220),
//! their table of m = n + i k, the rows from 0.30 to 1.00 um: n linear in wavelength
//! between rows, k linear in log k. Below 0.39 um their k is an upper limit, not a
//! measurement (their section 3).

use num_complex::Complex64;
use thiserror::Error;

use crate::optics::refractive_index::tabulated::interpolate;

/// Vacuum wavelength (nm), n, k: Warren and Brandt 2008.
const WARREN_BRANDT_2008: [(f64, f64, f64); 64] = [
    (300.0, 1.3339, 2e-11),
    (350.0, 1.3249, 2e-11),
    (390.0, 1.3203, 2e-11),
    (400.0, 1.3194, 2.365e-11),
    (410.0, 1.3185, 2.669e-11),
    (420.0, 1.3177, 3.135e-11),
    (430.0, 1.3170, 4.14e-11),
    (440.0, 1.3163, 6.268e-11),
    (450.0, 1.3157, 9.239e-11),
    (460.0, 1.3151, 1.325e-10),
    (470.0, 1.3145, 1.956e-10),
    (480.0, 1.3140, 2.861e-10),
    (490.0, 1.3135, 4.172e-10),
    (500.0, 1.3130, 5.889e-10),
    (510.0, 1.3126, 8.036e-10),
    (520.0, 1.3121, 1.076e-09),
    (530.0, 1.3117, 1.409e-09),
    (540.0, 1.3114, 1.813e-09),
    (550.0, 1.3110, 2.289e-09),
    (560.0, 1.3106, 2.839e-09),
    (570.0, 1.3103, 3.461e-09),
    (580.0, 1.3100, 4.159e-09),
    (590.0, 1.3097, 4.93e-09),
    (600.0, 1.3094, 5.73e-09),
    (610.0, 1.3091, 6.89e-09),
    (620.0, 1.3088, 8.58e-09),
    (630.0, 1.3085, 1.04e-08),
    (640.0, 1.3083, 1.22e-08),
    (650.0, 1.3080, 1.43e-08),
    (660.0, 1.3078, 1.66e-08),
    (670.0, 1.3076, 1.89e-08),
    (680.0, 1.3073, 2.09e-08),
    (690.0, 1.3071, 2.4e-08),
    (700.0, 1.3069, 2.9e-08),
    (710.0, 1.3067, 3.44e-08),
    (720.0, 1.3065, 4.03e-08),
    (730.0, 1.3062, 4.3e-08),
    (740.0, 1.3060, 4.92e-08),
    (750.0, 1.3059, 5.87e-08),
    (760.0, 1.3057, 7.08e-08),
    (770.0, 1.3055, 8.58e-08),
    (780.0, 1.3053, 1.02e-07),
    (790.0, 1.3051, 1.18e-07),
    (800.0, 1.3049, 1.34e-07),
    (810.0, 1.3047, 1.4e-07),
    (820.0, 1.3046, 1.43e-07),
    (830.0, 1.3044, 1.45e-07),
    (840.0, 1.3042, 1.51e-07),
    (850.0, 1.3040, 1.83e-07),
    (860.0, 1.3039, 2.15e-07),
    (870.0, 1.3037, 2.65e-07),
    (880.0, 1.3035, 3.35e-07),
    (890.0, 1.3033, 3.92e-07),
    (900.0, 1.3032, 4.2e-07),
    (910.0, 1.3030, 4.44e-07),
    (920.0, 1.3028, 4.74e-07),
    (930.0, 1.3027, 5.11e-07),
    (940.0, 1.3025, 5.53e-07),
    (950.0, 1.3023, 6.02e-07),
    (960.0, 1.3022, 7.55e-07),
    (970.0, 1.3020, 9.26e-07),
    (980.0, 1.3019, 1.12e-06),
    (990.0, 1.3017, 1.33e-06),
    (1000.0, 1.3015, 1.62e-06),
];

/// The table's range of vacuum wavelengths, nm.
pub const ICE_WAVELENGTH_RANGE_NM: [f64; 2] = [300.0, 1000.0];

#[derive(Clone, Debug, Error, PartialEq)]
#[error(
    "ice's refractive index is tabulated from 300 to 1000 nm (Warren and Brandt 2008), not at \
     {0} nm"
)]
pub struct OutsideIceTable(pub f64);

/// The refractive index of ice Ih at this vacuum wavelength.
pub fn ice_refractive_index(wavelength_nm: f64) -> Result<Complex64, OutsideIceTable> {
    let [lo, hi] = ICE_WAVELENGTH_RANGE_NM;
    if !(lo..=hi).contains(&wavelength_nm) {
        return Err(OutsideIceTable(wavelength_nm));
    }
    Ok(interpolate(&WARREN_BRANDT_2008, wavelength_nm))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_returned_exactly_and_the_ends_are_kept() {
        let m = ice_refractive_index(550.0).unwrap();
        assert!((m.re - 1.3110).abs() < 1e-12 && (m.im - 2.289e-9).abs() < 1e-21);
        let m = ice_refractive_index(400.0).unwrap();
        assert!((m.re - 1.3194).abs() < 1e-12 && (m.im - 2.365e-11).abs() < 1e-23);
        assert!(ice_refractive_index(1000.0).is_ok() && ice_refractive_index(300.0).is_ok());
        for bad in [299.0, 1001.0, f64::NAN] {
            assert!(ice_refractive_index(bad).is_err());
        }
        // Between rows: n between its neighbours, k their geometric mean at the middle.
        let m = ice_refractive_index(545.0).unwrap();
        assert!((m.re - 1.3112).abs() < 1e-12);
        assert!((m.im - (1.813e-9f64 * 2.289e-9).sqrt()).abs() < 1e-20);
    }
}
