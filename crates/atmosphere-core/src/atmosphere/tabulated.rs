//! Spectral tables shipped in `assets/` as CSV: the CIE 1931 colour-matching functions,
//! the ASTM G-173 solar spectrum and the ozone cross-sections.

/// A table of `N` quantities at increasing wavelengths, parsed from a CSV shipped in
/// `assets/` (shared by [`crate::color::cie1931`], [`crate::atmosphere::solar`] and [`crate::atmosphere::ozone`]).
#[derive(Debug)]
pub(crate) struct Tabulated<const N: usize> {
    wavelengths_nm: Vec<f64>,
    values: Vec<[f64; N]>,
}

impl<const N: usize> Tabulated<N> {
    /// Parses `text` (header line `header`, then `wavelength,v1,..,vN` per line).
    ///
    /// # Panics
    /// If the shipped file is malformed: a build defect, caught by the unit tests.
    pub(crate) fn parse(name: &str, text: &str, header: &str) -> Self {
        let mut lines = text.lines().filter(|l| !l.trim().is_empty());
        assert_eq!(lines.next().map(str::trim), Some(header), "{name}: header");
        let mut table = Self {
            wavelengths_nm: Vec::new(),
            values: Vec::new(),
        };
        for line in lines {
            let fields: Vec<f64> = line
                .split(',')
                .map(|f| {
                    let v: f64 = f.trim().parse().unwrap_or_else(|e| {
                        panic!("{name}: bad number {f:?} in line {line:?}: {e}")
                    });
                    assert!(v.is_finite(), "{name}: non-finite value in {line:?}");
                    v
                })
                .collect();
            assert_eq!(fields.len(), N + 1, "{name}: field count in {line:?}");
            if let Some(&last) = table.wavelengths_nm.last() {
                assert!(
                    fields[0] > last,
                    "{name}: wavelengths not increasing at {line:?}"
                );
            }
            table.wavelengths_nm.push(fields[0]);
            table.values.push(std::array::from_fn(|k| fields[k + 1]));
        }
        assert!(table.wavelengths_nm.len() >= 2, "{name}: fewer than 2 rows");
        table
    }

    pub(crate) fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }

    /// Linear interpolation, the end values outside the table, NaN for NaN.
    pub(crate) fn interpolate_clamped(&self, lambda_nm: f64) -> [f64; N] {
        let nm = &self.wavelengths_nm;
        if lambda_nm.is_nan() {
            return [f64::NAN; N];
        }
        let j = nm.partition_point(|&l| l <= lambda_nm);
        if j == 0 {
            return self.values[0];
        }
        if j == nm.len() {
            return self.values[j - 1];
        }
        let f = (lambda_nm - nm[j - 1]) / (nm[j] - nm[j - 1]);
        let (a, b) = (self.values[j - 1], self.values[j]);
        std::array::from_fn(|k| a[k] + f * (b[k] - a[k]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[should_panic(expected = "header")]
    fn malformed_table_panics() {
        Tabulated::<1>::parse("bad", "nm,v\n1,2\n2,3\n", "wavelength_nm,v");
    }

    #[test]
    fn table_interpolation_and_clamping() {
        let t = Tabulated::<2>::parse("t", "h\n1,10,0\n3,30,2\n", "h");
        assert_eq!(t.interpolate_clamped(2.0), [20.0, 1.0]);
        assert_eq!(t.interpolate_clamped(0.0), [10.0, 0.0]);
        assert_eq!(t.interpolate_clamped(9.0), [30.0, 2.0]);
        assert!(t.interpolate_clamped(f64::NAN)[0].is_nan());
    }
}
