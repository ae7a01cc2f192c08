//! The tone map from HDR radiance to display pixels, on the CPU: the twin of
//! `shaders/post/tone_map.wgsl` and the source of its uniform.
//!
//! Spectral radiance at the three wavelengths becomes linear sRGB in cd/m^2 through
//! atmosphere-core's [`SpectrumToColor`] (CIE 1931, the sun's spectrum as the shape
//! between samples), is scaled by the exposure `1 / (1.2 * 2^EV100)` (the saturation-based
//! exposure of Lagarde and de Rousiers 2014, "Moving Frostbite to PBR", section 4.4),
//! clipped at zero, and mapped by Narkowicz's fit of the ACES filmic curve (2016, "ACES
//! Filmic Tone Mapping Curve"): a toe, a shoulder that rolls highlights off to white, and
//! one rational function per channel, cheap and widely used. The sRGB transfer function
//! (IEC 61966-2-1) is applied last, by the Rgba8UnormSrgb target on the GPU.

use atmosphere_core::color::srgb::srgb_encode;
use atmosphere_core::color::{ColorError, SpectrumToColor};
use bytemuck::{Pod, Zeroable};

/// The luminance scale of exposure `ev100`: 1 / (1.2 * 2^EV100).
pub fn exposure_scale(ev100: f64) -> f64 {
    1.0 / (1.2 * 2f64.powf(ev100))
}

/// Narkowicz's ACES fit, clamped to [0, 1].
pub fn aces_filmic(x: f64) -> f64 {
    ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
}

/// The tone map of one exposure for radiance at given wavelengths.
#[derive(Clone, Debug)]
pub struct ToneMap {
    /// Rows R, G, B: from radiance (W m^-2 sr^-1 nm^-1) at each wavelength to exposed
    /// linear sRGB.
    pub matrix: [[f64; 3]; 3],
}

impl ToneMap {
    /// The tone map for radiance at `wavelengths_nm` and exposure `ev100`.
    pub fn new(wavelengths_nm: [f64; 3], ev100: f64) -> Result<ToneMap, ColorError> {
        let weights = SpectrumToColor::new(&wavelengths_nm)?.linear_srgb_weights();
        let scale = exposure_scale(ev100);
        Ok(ToneMap {
            matrix: std::array::from_fn(|row| std::array::from_fn(|w| weights[w][row] * scale)),
        })
    }

    /// Display values in [0, 1] (before the sRGB transfer function) of `radiance`.
    pub fn display_linear(&self, radiance: [f64; 3]) -> [f64; 3] {
        self.matrix.map(|row| {
            let v = row[0] * radiance[0] + row[1] * radiance[1] + row[2] * radiance[2];
            aces_filmic(v.max(0.0))
        })
    }

    /// The 8-bit sRGB pixel (alpha 255) of `radiance`, rounded to nearest.
    pub fn pixel(&self, radiance: [f64; 3]) -> [u8; 4] {
        let [r, g, b] = self
            .display_linear(radiance)
            .map(|v| (srgb_encode(v) * 255.0).round() as u8);
        [r, g, b, 255]
    }

    /// The uniform of `shaders/post/tone_map.wgsl`.
    pub fn uniform(&self) -> ToneMapUniform {
        let row = |r: [f64; 3]| [r[0] as f32, r[1] as f32, r[2] as f32, 0.0];
        ToneMapUniform {
            red: row(self.matrix[0]),
            green: row(self.matrix[1]),
            blue: row(self.matrix[2]),
        }
    }
}

/// WGSL `ToneMapParams`, 48 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ToneMapUniform {
    pub red: [f32; 4],
    pub green: [f32; 4],
    pub blue: [f32; 4],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curve_and_exposure() {
        assert_eq!(aces_filmic(0.0), 0.0);
        assert_eq!(aces_filmic(1e6), 1.0);
        assert!(
            (aces_filmic(0.18) - 0.2666).abs() < 1e-3,
            "{}",
            aces_filmic(0.18)
        );
        assert!((srgb_encode(0.5) - 0.7354).abs() < 1e-4);
        // EV100 15 maps 1e4 cd/m^2 to about 0.25.
        assert!((1e4 * exposure_scale(15.0) - 0.254).abs() < 1e-3);
        let black = ToneMap::new([680.0, 550.0, 440.0], 14.0).unwrap();
        assert_eq!(black.pixel([0.0; 3]), [0, 0, 0, 255]);
        assert_eq!(black.pixel([1e9; 3]), [255, 255, 255, 255]);
    }
}
