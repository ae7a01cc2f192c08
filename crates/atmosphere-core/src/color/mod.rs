//! From spectral radiance at a few wavelengths to CIE XYZ, luminance and linear sRGB.
//!
//! # Method
//!
//! A model carries radiance `L_i` (W m^-2 sr^-1 nm^-1) only at N wavelengths `lambda_i`
//! (680, 550, 440 nm for the real-time models, dozens for the reference). To convert to
//! colour the full visible spectrum is reconstructed as
//!
//! `S(lambda) = E_sun(lambda) * r(lambda)`,
//!
//! where `E_sun` is the ASTM G-173 extraterrestrial irradiance ([`crate::atmosphere::solar`]) and `r`
//! the piecewise-linear interpolation of the ratios `L_i / E_sun(lambda_i)` through the
//! sampled wavelengths, constant beyond the first and last samples. Sky light is sunlight
//! multiplied by smooth scattering and transmittance factors, so interpolating that factor
//! rather than `L` keeps the sun's spectral lines and, above all, reproduces sunlight (and
//! anything grey under it) exactly whatever the samples: with `r` constant, `S = c E_sun`.
//! This is the idea of Bruneton's `ConvertSpectrumToLinearSrgb` (2017), which interpolates
//! the radiance itself instead.
//!
//! Then `XYZ = 683 lm/W * integral over 360..830 nm of S(lambda) cmf(lambda) d lambda`
//! with the CIE 1931 2-degree functions ([`crate::color::cie1931`]), by the trapezoid rule at the
//! 1 nm steps of the table, so `Y` is the luminance in cd/m^2. Since every step is linear
//! in the `L_i`, [`SpectrumToColor::new`] folds it into a 3 x N matrix once.
//!
//! Linear sRGB uses the IEC 61966-2-1 (D65) matrix on XYZ in cd/m^2, so its scale is
//! absolute: the sRGB of a white with `Y` cd/m^2 is `(Y, Y, Y)`.

pub mod cie1931;
pub mod srgb;

use thiserror::Error;

use crate::atmosphere::solar::astm_g173_irradiance_w_m2_nm;
use crate::color::cie1931::{CMF_MAX_NM, CMF_MIN_NM};

/// Maximum luminous efficacy used to convert W to lm (photopic), lm/W.
pub const MAX_LUMINOUS_EFFICACY_LM_PER_W: f64 = 683.0;

/// XYZ to linear sRGB, IEC 61966-2-1:1999 (D65 white), rows R, G, B.
pub const XYZ_TO_LINEAR_SRGB: [[f64; 3]; 3] = [
    [3.2406, -1.5372, -0.4986],
    [-0.9689, 1.8758, 0.0415],
    [0.0557, -0.2040, 1.0570],
];

/// Why a list of wavelengths cannot be converted to colour.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum ColorError {
    /// No wavelength at all.
    #[error("no wavelengths given")]
    Empty,
    /// A wavelength is NaN or infinite.
    #[error("wavelength #{index} ({value} nm) is not finite")]
    NonFinite { index: usize, value: f64 },
    /// A wavelength lies outside the colour-matching table.
    #[error("wavelength #{index} ({value} nm) is outside {CMF_MIN_NM}..{CMF_MAX_NM} nm")]
    OutOfRange { index: usize, value: f64 },
    /// The same wavelength appears twice.
    #[error("wavelength {value} nm is given more than once")]
    Duplicate { value: f64 },
}

/// The linear map from radiance at fixed wavelengths to CIE XYZ in cd/m^2 (see the
/// module documentation for the method).
#[derive(Clone, Debug)]
pub struct SpectrumToColor {
    /// The wavelengths in the order given to [`SpectrumToColor::new`], nm.
    wavelengths_nm: Vec<f64>,
    /// For each wavelength (same order), the XYZ (cd/m^2) of unit radiance there.
    xyz_weights: Vec<[f64; 3]>,
}

impl SpectrumToColor {
    /// Precomputes the conversion for radiance given at `wavelengths_nm` (any order,
    /// each within 360..830 nm, no duplicates).
    pub fn new(wavelengths_nm: &[f64]) -> Result<Self, ColorError> {
        if wavelengths_nm.is_empty() {
            return Err(ColorError::Empty);
        }
        for (index, &value) in wavelengths_nm.iter().enumerate() {
            if !value.is_finite() {
                return Err(ColorError::NonFinite { index, value });
            }
            if !(CMF_MIN_NM..=CMF_MAX_NM).contains(&value) {
                return Err(ColorError::OutOfRange { index, value });
            }
        }
        // Sorted sample wavelengths, each with its index in the caller's order.
        let mut sorted: Vec<(f64, usize)> = wavelengths_nm
            .iter()
            .copied()
            .enumerate()
            .map(|(i, l)| (l, i))
            .collect();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        if let Some(w) = sorted.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(ColorError::Duplicate { value: w[0].0 });
        }
        let inv_sun: Vec<f64> = sorted
            .iter()
            .map(|&(l, _)| 1.0 / astm_g173_irradiance_w_m2_nm(l))
            .collect();

        let mut xyz_weights = vec![[0.0; 3]; wavelengths_nm.len()];
        let nodes = cie1931::table_wavelengths_nm();
        for (n, &lambda) in nodes.iter().enumerate() {
            // Trapezoid weight of this node.
            let left = if n > 0 { lambda - nodes[n - 1] } else { 0.0 };
            let right = nodes.get(n + 1).map_or(0.0, |&next| next - lambda);
            let common = MAX_LUMINOUS_EFFICACY_LM_PER_W
                * 0.5
                * (left + right)
                * astm_g173_irradiance_w_m2_nm(lambda);
            let cmf = cie1931::color_matching(lambda);
            // Interpolation weights of the samples at this node (r(lambda) = sum w_j r_j).
            let j = sorted.partition_point(|&(l, _)| l <= lambda);
            let pairs: [(usize, f64); 2] = if j == 0 {
                [(0, 1.0), (0, 0.0)]
            } else if j == sorted.len() {
                [(j - 1, 1.0), (j - 1, 0.0)]
            } else {
                let (a, b) = (sorted[j - 1].0, sorted[j].0);
                let f = (lambda - a) / (b - a);
                [(j - 1, 1.0 - f), (j, f)]
            };
            for (s, w) in pairs {
                let weights = &mut xyz_weights[sorted[s].1];
                for k in 0..3 {
                    weights[k] += common * w * inv_sun[s] * cmf[k];
                }
            }
        }
        Ok(Self {
            wavelengths_nm: wavelengths_nm.to_vec(),
            xyz_weights,
        })
    }

    /// The wavelengths given to [`SpectrumToColor::new`], in that order, nm.
    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }

    /// The 3 x N matrix by columns: for each wavelength (order of `new`), the XYZ in
    /// cd/m^2 of unit radiance (1 W m^-2 sr^-1 nm^-1) there and zero elsewhere.
    pub fn xyz_weights(&self) -> &[[f64; 3]] {
        &self.xyz_weights
    }

    /// As [`SpectrumToColor::xyz_weights`], converted to linear sRGB (e.g. for a shader).
    pub fn linear_srgb_weights(&self) -> Vec<[f64; 3]> {
        self.xyz_weights
            .iter()
            .map(|&w| xyz_to_linear_srgb(w))
            .collect()
    }

    /// CIE XYZ in cd/m^2 of radiance (W m^-2 sr^-1 nm^-1) given at the wavelengths of
    /// `new`, in the same order.
    ///
    /// # Panics
    /// If `radiance.len()` differs from the number of wavelengths.
    pub fn xyz_cd_m2(&self, radiance: &[f64]) -> [f64; 3] {
        assert_eq!(
            radiance.len(),
            self.xyz_weights.len(),
            "radiance has {} values for {} wavelengths",
            radiance.len(),
            self.xyz_weights.len()
        );
        let mut xyz = [0.0; 3];
        for (l, w) in radiance.iter().zip(&self.xyz_weights) {
            for k in 0..3 {
                xyz[k] += l * w[k];
            }
        }
        xyz
    }

    /// Luminance in cd/m^2 (the Y of [`SpectrumToColor::xyz_cd_m2`]).
    ///
    /// # Panics
    /// As [`SpectrumToColor::xyz_cd_m2`].
    pub fn luminance_cd_m2(&self, radiance: &[f64]) -> f64 {
        self.xyz_cd_m2(radiance)[1]
    }

    /// Linear sRGB in cd/m^2 (white of luminance Y maps to (Y, Y, Y)).
    ///
    /// # Panics
    /// As [`SpectrumToColor::xyz_cd_m2`].
    pub fn linear_srgb_cd_m2(&self, radiance: &[f64]) -> [f64; 3] {
        xyz_to_linear_srgb(self.xyz_cd_m2(radiance))
    }
}

/// CIE XYZ to linear sRGB (IEC 61966-2-1, D65), same scale.
pub fn xyz_to_linear_srgb(xyz: [f64; 3]) -> [f64; 3] {
    XYZ_TO_LINEAR_SRGB.map(|row| row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chromaticity(xyz: [f64; 3]) -> (f64, f64) {
        let s = xyz[0] + xyz[1] + xyz[2];
        (xyz[0] / s, xyz[1] / s)
    }

    fn every_nm(step: usize) -> Vec<f64> {
        (360..=830).step_by(step).map(f64::from).collect()
    }

    #[test]
    fn sun_shaped_spectrum_is_independent_of_the_sampling() {
        let three = [680.0, 550.0, 440.0];
        let many = every_nm(10);
        let sun = |nm: &[f64]| -> Vec<f64> {
            nm.iter()
                .map(|&l| 0.37 * astm_g173_irradiance_w_m2_nm(l))
                .collect()
        };
        let a = SpectrumToColor::new(&three)
            .unwrap()
            .xyz_cd_m2(&sun(&three));
        let b = SpectrumToColor::new(&many).unwrap().xyz_cd_m2(&sun(&many));
        for k in 0..3 {
            assert!((a[k] / b[k] - 1.0).abs() < 1e-9, "{a:?} vs {b:?}");
        }
    }

    #[test]
    fn sun_chromaticity_matches_published_astm_g173_value() {
        let nm = [680.0, 550.0, 440.0];
        let l: Vec<f64> = nm
            .iter()
            .map(|&l| astm_g173_irradiance_w_m2_nm(l))
            .collect();
        let (x, y) = chromaticity(SpectrumToColor::new(&nm).unwrap().xyz_cd_m2(&l));
        assert!(
            (x - 0.3222).abs() < 0.003 && (y - 0.3310).abs() < 0.003,
            "{x} {y}"
        );
    }

    #[test]
    fn equal_energy_is_white_with_the_luminance_of_ybar() {
        // Samples at every table node: S(lambda) = 1 exactly at each integration node.
        let nm = every_nm(1);
        let conv = SpectrumToColor::new(&nm).unwrap();
        let ones = vec![1.0; nm.len()];
        let (x, y) = chromaticity(conv.xyz_cd_m2(&ones));
        assert!(
            (x - 1.0 / 3.0).abs() < 1e-3 && (y - 1.0 / 3.0).abs() < 1e-3,
            "{x} {y}"
        );

        let ybar: Vec<f64> = nm.iter().map(|&l| cie1931::color_matching(l)[1]).collect();
        let integral: f64 = ybar.windows(2).map(|w| 0.5 * (w[0] + w[1])).sum();
        let lum = conv.luminance_cd_m2(&ones);
        assert!((lum / (683.0 * integral) - 1.0).abs() < 1e-12, "{lum}");
        assert!((lum - 683.0 * 106.857).abs() < 0.1 * 683.0, "{lum}");
    }

    #[test]
    fn equal_energy_is_white_with_coarse_samples_too() {
        let nm = every_nm(10);
        let (x, y) = chromaticity(
            SpectrumToColor::new(&nm)
                .unwrap()
                .xyz_cd_m2(&vec![1.0; nm.len()]),
        );
        assert!(
            (x - 1.0 / 3.0).abs() < 2e-3 && (y - 1.0 / 3.0).abs() < 2e-3,
            "{x} {y}"
        );
    }

    #[test]
    fn d65_white_is_srgb_white() {
        let rgb = xyz_to_linear_srgb([0.95047, 1.0, 1.08883]);
        for c in rgb {
            assert!((c - 1.0).abs() < 1e-3, "{rgb:?}");
        }
    }

    #[test]
    fn order_of_wavelengths_does_not_matter() {
        let a = SpectrumToColor::new(&[440.0, 550.0, 680.0]).unwrap();
        let b = SpectrumToColor::new(&[680.0, 440.0, 550.0]).unwrap();
        let xa = a.xyz_cd_m2(&[0.2, 0.5, 0.9]);
        let xb = b.xyz_cd_m2(&[0.9, 0.2, 0.5]);
        for k in 0..3 {
            assert!(
                (xa[k] - xb[k]).abs() <= 1e-12 * xa[k].abs(),
                "{xa:?} {xb:?}"
            );
        }
        // Each wavelength's weight depends on where its radiance goes.
        assert!(a.xyz_cd_m2(&[1.0, 0.0, 0.0])[2] > a.xyz_cd_m2(&[0.0, 0.0, 1.0])[2]);
        let rgb = a.linear_srgb_cd_m2(&[0.2, 0.5, 0.9]);
        assert_eq!(rgb, xyz_to_linear_srgb(xa));
        assert_eq!(a.luminance_cd_m2(&[0.2, 0.5, 0.9]), xa[1]);
    }

    #[test]
    fn single_wavelength_scales_the_sun() {
        let one = SpectrumToColor::new(&[550.0]).unwrap();
        let three = SpectrumToColor::new(&[680.0, 550.0, 440.0]).unwrap();
        let e = |l| astm_g173_irradiance_w_m2_nm(l);
        let a = one.xyz_cd_m2(&[e(550.0)]);
        let b = three.xyz_cd_m2(&[e(680.0), e(550.0), e(440.0)]);
        for k in 0..3 {
            assert!((a[k] / b[k] - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn invalid_wavelengths_are_rejected() {
        assert_eq!(SpectrumToColor::new(&[]).unwrap_err(), ColorError::Empty);
        assert!(matches!(
            SpectrumToColor::new(&[550.0, f64::NAN]),
            Err(ColorError::NonFinite { index: 1, .. })
        ));
        assert!(matches!(
            SpectrumToColor::new(&[f64::INFINITY]),
            Err(ColorError::NonFinite { index: 0, .. })
        ));
        assert_eq!(
            SpectrumToColor::new(&[550.0, 350.0]).unwrap_err(),
            ColorError::OutOfRange {
                index: 1,
                value: 350.0
            }
        );
        assert!(matches!(
            SpectrumToColor::new(&[900.0]),
            Err(ColorError::OutOfRange { index: 0, .. })
        ));
        assert_eq!(
            SpectrumToColor::new(&[440.0, 550.0, 440.0]).unwrap_err(),
            ColorError::Duplicate { value: 440.0 }
        );
    }

    #[test]
    #[should_panic(expected = "radiance has 2 values for 3 wavelengths")]
    fn wrong_radiance_length_panics() {
        let conv = SpectrumToColor::new(&[680.0, 550.0, 440.0]).unwrap();
        conv.xyz_cd_m2(&[1.0, 2.0]);
    }
}
