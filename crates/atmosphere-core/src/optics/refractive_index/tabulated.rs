//! A refractive index between the rows of a published table of (wavelength nm, n, k):
//! n linear in the wavelength, k linear in its logarithm (k spans decades between
//! neighbouring rows); a row's own wavelength gives the row exactly.

use num_complex::Complex64;

/// The index of `table` (rows in increasing wavelength) at `wavelength_nm`, which the
/// caller has checked lies within the table's first and last wavelengths.
pub fn interpolate(table: &[(f64, f64, f64)], wavelength_nm: f64) -> Complex64 {
    if let Some(&(_, n, k)) = table.iter().find(|row| row.0 == wavelength_nm) {
        return Complex64::new(n, k);
    }
    let i = table
        .windows(2)
        .position(|w| wavelength_nm <= w[1].0)
        .unwrap_or(table.len() - 2);
    let ((l0, n0, k0), (l1, n1, k1)) = (table[i], table[i + 1]);
    let t = (wavelength_nm - l0) / (l1 - l0);
    let n = n0 + t * (n1 - n0);
    let k = (k0.ln() + t * (k1.ln() - k0.ln())).exp();
    Complex64::new(n, k)
}
