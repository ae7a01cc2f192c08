//! The Earth's colour map: `assets/earth/colour.jpg` (NASA Blue Marble, 8-bit sRGB; see
//! `assets/CREDITS.md`), sampled bilinearly by latitude and longitude. The GPU will take
//! the same texels as an sRGB texture; this CPU sampler is its specification.

use std::path::Path;

use image::DynamicImage;

use super::geo_grid::bilinear_taps;
use super::map_error::MapError;
use atmosphere_core::color::srgb::srgb_decode;

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
        ColourMap::from_image(super::map_image::load_image(path)?, path)
    }

    /// The map of a decoded image, with errors naming it `path`.
    pub(super) fn from_image(image: DynamicImage, path: &Path) -> Result<ColourMap, MapError> {
        if !image.color().has_color() {
            return Err(MapError::Format {
                path: path.to_owned(),
                found: format!("{:?}", image.color()),
                expected: "a colour (RGB) image",
            });
        }
        let rgb = image.into_rgb8();
        let (width, height) = (rgb.width() as usize, rgb.height() as usize);
        super::map_image::check_aspect(path, width, height)?;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A map of `assets/earth/` in the source tree.
    fn shipped(file: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../assets/earth")
            .join(file)
    }

    /// The shipped Blue Marble: the Sahara sandy (red over blue), the open Pacific dark
    /// blue, Antarctica and Greenland's ice bright.
    #[test]
    fn shipped_colours_at_known_places() {
        let map = ColourMap::load(&shipped("colour.jpg")).unwrap();
        assert_eq!((map.width, map.height), (4096, 2048));
        let at = |lat: f64, lon: f64| map.sample_linear(lat.to_radians(), lon.to_radians());
        let sahara = at(23.0, 10.0);
        assert!(sahara[0] > 1.5 * sahara[2], "Sahara {sahara:?}");
        let pacific = at(0.0, -150.0);
        assert!(
            pacific[2] > 2.0 * pacific[0] && pacific[2] < 0.2,
            "Pacific {pacific:?}"
        );
        for (lat, lon) in [(-85.0, 0.0), (75.0, -40.0)] {
            let ice = at(lat, lon);
            assert!(ice.iter().all(|&c| c > 0.5), "ice at {lat}, {lon}: {ice:?}");
        }
    }

    #[test]
    fn missing_and_grey_files_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let e = ColourMap::load(&dir.path().join("colour.jpg")).unwrap_err();
        assert!(matches!(e, MapError::Missing { .. }));
        assert!(e.to_string().contains("colour.jpg"), "{e}");
        let grey = dir.path().join("grey.png");
        image::GrayImage::new(4, 2).save(&grey).unwrap();
        let e = ColourMap::load(&grey).unwrap_err();
        assert!(
            matches!(e, MapError::Format { .. }) && e.to_string().contains("grey.png"),
            "{e}"
        );
    }
}
