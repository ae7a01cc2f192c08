//! A light map: an image that modulates a light's intensity across its beam (a spot's
//! intensity distribution, a gobo, stained glass), after Dobashi et al. 2000 section
//! 5.1. Texels are decoded from sRGB to linear values in [0, 1]; an RGB texel is a
//! transmission per wavelength by linear interpolation between blue at 440 nm, green at
//! 550 nm and red at 680 nm, held constant beyond them.

use std::path::Path;

/// The wavelengths (nm) at which the blue, green and red channels of a light map are
/// the transmission.
pub const CHANNEL_WAVELENGTHS_NM: [f64; 3] = [440.0, 550.0, 680.0];

/// A decoded light map, linear RGB, rows from the top of the image.
#[derive(Clone, Debug, PartialEq)]
pub struct LightMap {
    pub width: usize,
    pub height: usize,
    /// Linear red, green, blue per texel, row by row from the top.
    pub texels: Vec<[f32; 3]>,
}

impl LightMap {
    /// Reads and decodes the image at `path` (PNG or JPEG); the error is the decoder's.
    pub fn load(path: &Path) -> Result<LightMap, String> {
        let image = image::open(path).map_err(|e| e.to_string())?.to_rgb8();
        let (width, height) = (image.width() as usize, image.height() as usize);
        if width == 0 || height == 0 {
            return Err("the image has no pixels".into());
        }
        let decode = |c: u8| crate::color::srgb::srgb_decode(f64::from(c) / 255.0) as f32;
        let texels = image
            .pixels()
            .map(|p| [decode(p[0]), decode(p[1]), decode(p[2])])
            .collect();
        Ok(LightMap {
            width,
            height,
            texels,
        })
    }

    /// Bilinear filtering at texture coordinates (u across, v down, both in [0, 1];
    /// texel centres at (i + 0.5) / width), clamped to the edge texels; `wrap_u`
    /// wraps u instead (an azimuth).
    pub fn sample(&self, u: f64, v: f64, wrap_u: bool) -> [f64; 3] {
        let (w, h) = (self.width as f64, self.height as f64);
        let x = u * w - 0.5;
        let y = (v * h - 0.5).clamp(0.0, h - 1.0);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let column = |i: f64| -> usize {
            if wrap_u {
                i.rem_euclid(w) as usize
            } else {
                i.clamp(0.0, w - 1.0) as usize
            }
        };
        let (c0, c1) = (column(x0), column(x0 + 1.0));
        let (r0, r1) = (y0 as usize, (y0 as usize + 1).min(self.height - 1));
        let texel = |r: usize, c: usize| self.texels[r * self.width + c];
        let mut out = [0.0; 3];
        for k in 0..3 {
            let top = f64::from(texel(r0, c0)[k]) * (1.0 - fx) + f64::from(texel(r0, c1)[k]) * fx;
            let bottom =
                f64::from(texel(r1, c0)[k]) * (1.0 - fx) + f64::from(texel(r1, c1)[k]) * fx;
            out[k] = top * (1.0 - fy) + bottom * fy;
        }
        out
    }
}

/// The weights of the red, green and blue channels in the transmission at `lambda_nm`.
pub fn channel_weights(lambda_nm: f64) -> [f64; 3] {
    let [blue, green, red] = CHANNEL_WAVELENGTHS_NM;
    if lambda_nm <= blue {
        [0.0, 0.0, 1.0]
    } else if lambda_nm <= green {
        let f = (lambda_nm - blue) / (green - blue);
        [0.0, f, 1.0 - f]
    } else if lambda_nm <= red {
        let f = (lambda_nm - green) / (red - green);
        [f, 1.0 - f, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map() -> LightMap {
        LightMap {
            width: 2,
            height: 1,
            texels: vec![[0.0, 0.0, 0.0], [1.0, 0.5, 0.25]],
        }
    }

    #[test]
    fn bilinear_sample_interpolates_between_texel_centres_and_clamps() {
        let m = map();
        assert_eq!(m.sample(0.25, 0.5, false), [0.0; 3]);
        assert_eq!(m.sample(0.75, 0.5, false), [1.0, 0.5, 0.25]);
        assert_eq!(m.sample(0.5, 0.5, false), [0.5, 0.25, 0.125]);
        assert_eq!(m.sample(1.0, 0.0, false), [1.0, 0.5, 0.25]);
        // Wrapped, u = 1 is halfway between the last texel and the first.
        assert_eq!(m.sample(1.0, 0.5, true), [0.5, 0.25, 0.125]);
    }

    #[test]
    fn channel_weights_sum_to_one_and_pick_the_channel_at_its_wavelength() {
        assert_eq!(channel_weights(680.0), [1.0, 0.0, 0.0]);
        assert_eq!(channel_weights(550.0), [0.0, 1.0, 0.0]);
        assert_eq!(channel_weights(440.0), [0.0, 0.0, 1.0]);
        for nm in [400.0, 500.0, 600.0, 700.0] {
            let w = channel_weights(nm);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        }
    }
}
