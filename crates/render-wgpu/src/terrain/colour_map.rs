//! The Earth's colour map: `assets/earth/colour.jpg` (NASA Blue Marble, 8-bit sRGB; see
//! `assets/CREDITS.md`), sampled bilinearly by latitude and longitude. The GPU will take
//! the same texels as an sRGB texture; this CPU sampler is its specification.

use std::path::Path;

use super::geo_grid::bilinear_taps;
use super::map_error::MapError;
use crate::tone_map::srgb_decode;

/// 8-bit sRGB texels on an equirectangular grid (layout in `geo_grid.rs`).
#[derive(Clone, Debug)]
pub struct ColourMap {
    pub width: usize,
    pub height: usize,
    /// Row-major, north row first.
    pub texels: Vec<[u8; 3]>,
}

impl ColourMap {
    /// Loads a colour image (JPEG or PNG) with a 2:1 aspect. A missing file, a file that
    /// does not decode, or a grey one is an error naming it.
    pub fn load(path: &Path) -> Result<ColourMap, MapError> {
        let image = super::load_image(path)?;
        if !image.color().has_color() {
            return Err(MapError::Format {
                path: path.to_owned(),
                found: format!("{:?}", image.color()),
                expected: "a colour (RGB) image",
            });
        }
        let rgb = image.into_rgb8();
        let (width, height) = (rgb.width() as usize, rgb.height() as usize);
        super::check_aspect(path, width, height)?;
        let texels = rgb.pixels().map(|p| p.0).collect();
        Ok(ColourMap {
            width,
            height,
            texels,
        })
    }

    /// The bilinear linear-sRGB colour at a latitude and longitude (radians): each texel
    /// is decoded from sRGB, then the four are interpolated, as a GPU's sRGB texture
    /// filters.
    pub fn sample_linear(&self, lat_rad: f64, lon_rad: f64) -> [f64; 3] {
        let mut rgb = [0.0; 3];
        for (k, w) in bilinear_taps(self.width, self.height, lat_rad, lon_rad) {
            for c in 0..3 {
                rgb[c] += w * srgb_decode(self.texels[k][c] as f64 / 255.0);
            }
        }
        rgb
    }
}
