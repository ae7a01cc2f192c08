//! A volume's image: per pixel, the radiance it scatters towards the camera at each
//! wavelength and its transmittance, over a background.

/// Row by row from the top left; radiance in W m^-2 sr^-1 nm^-1.
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeImage {
    pub width_px: u32,
    pub height_px: u32,
    pub wavelengths: usize,
    /// `[(y * width + x) * wavelengths + w]`.
    pub radiance: Vec<f64>,
    /// `[y * width + x]`.
    pub transmittance: Vec<f64>,
}

impl VolumeImage {
    /// A black image of transmittance 1.
    pub fn clear(width_px: u32, height_px: u32, wavelengths: usize) -> VolumeImage {
        let pixels = width_px as usize * height_px as usize;
        VolumeImage {
            width_px,
            height_px,
            wavelengths,
            radiance: vec![0.0; pixels * wavelengths],
            transmittance: vec![1.0; pixels],
        }
    }

    /// The radiance of pixel `pixel` (row-major index) at each wavelength.
    pub fn pixel(&self, pixel: usize) -> &[f64] {
        &self.radiance[pixel * self.wavelengths..(pixel + 1) * self.wavelengths]
    }

    /// The radiance seen over a uniform `background` radiance (one per wavelength):
    /// L + T L_background.
    pub fn over_background(&self, background: &[f64]) -> Vec<f64> {
        self.radiance
            .iter()
            .enumerate()
            .map(|(k, l)| {
                let (p, w) = (k / self.wavelengths, k % self.wavelengths);
                l + self.transmittance[p] * background.get(w).copied().unwrap_or(0.0)
            })
            .collect()
    }

    /// The mean absolute radiance difference from `other` over all pixels and
    /// wavelengths, divided by `other`'s mean radiance (0 when both are black).
    pub fn relative_error(&self, other: &VolumeImage) -> f64 {
        let diff: f64 = self
            .radiance
            .iter()
            .zip(&other.radiance)
            .map(|(a, b)| (a - b).abs())
            .sum();
        let mean: f64 = other.radiance.iter().sum();
        if mean > 0.0 { diff / mean } else { diff }
    }
}
