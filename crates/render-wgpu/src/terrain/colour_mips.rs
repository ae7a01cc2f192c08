//! The colour map's mip chain for the GPU: each level halves the one above by averaging
//! 2 x 2 texels in linear light (decoded from sRGB, averaged, encoded again), as a GPU's
//! sRGB texture filters, so that the planet seen from far away keeps its mean colour and
//! does not shimmer. An equirectangular map twice as wide as tall stays so down to 2 x 1.

use super::colour_map::ColourMap;
use atmosphere_core::color::srgb::{srgb_decode, srgb_encode};

/// One level: `width x height` RGBA8 sRGB texels, row-major, alpha 255.
#[derive(Clone, Debug, PartialEq)]
pub struct MipLevel {
    pub width: usize,
    pub height: usize,
    pub texels: Vec<[u8; 4]>,
}

/// The full chain, level 0 the map itself, down to a level one texel tall.
pub fn colour_mips(map: &ColourMap) -> Vec<MipLevel> {
    let decode: Vec<f32> = (0..=255u8)
        .map(|v| srgb_decode(v as f64 / 255.0) as f32)
        .collect();
    let mut levels = vec![MipLevel {
        width: map.width,
        height: map.height,
        texels: map.texels.iter().map(|&[r, g, b]| [r, g, b, 255]).collect(),
    }];
    while let Some(above) = levels.last().filter(|l| l.height > 1 && l.width > 1) {
        let (width, height) = (above.width / 2, above.height / 2);
        let mut texels = Vec::with_capacity(width * height);
        for j in 0..height {
            for i in 0..width {
                let mut texel = [255u8; 4];
                for (c, out) in texel.iter_mut().take(3).enumerate() {
                    let sum: f32 = [(0, 0), (1, 0), (0, 1), (1, 1)]
                        .iter()
                        .map(|(di, dj)| {
                            decode
                                [above.texels[(2 * j + dj) * above.width + 2 * i + di][c] as usize]
                        })
                        .sum();
                    *out = (srgb_encode(f64::from(sum) / 4.0) * 255.0).round() as u8;
                }
                texels.push(texel);
            }
        }
        levels.push(MipLevel {
            width,
            height,
            texels,
        });
    }
    levels
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_halve_and_average_in_linear_light() {
        // Black and white columns: the next level is mid-grey in light (sRGB 188), not
        // the sRGB average 128.
        let texels = (0..8 * 4)
            .map(|k| {
                if k % 2 == 0 {
                    [0, 0, 0]
                } else {
                    [255, 255, 255]
                }
            })
            .collect();
        let map = ColourMap {
            width: 8,
            height: 4,
            texels,
        };
        let mips = colour_mips(&map);
        let sizes: Vec<_> = mips.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(8, 4), (4, 2), (2, 1)]);
        assert!(mips[1].texels.iter().all(|t| *t == [188, 188, 188, 255]));
        assert!(mips[2].texels.iter().all(|t| *t == [188, 188, 188, 255]));
    }
}
