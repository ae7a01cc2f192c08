//! The Earth's height map: `assets/earth/height.png`, 16-bit grey, value = metres + 11000
//! (ETOPO5 averaged onto 10 arc-minute texels; see `assets/CREDITS.md`), sampled
//! bilinearly by latitude and longitude.

use std::f64::consts::PI;
use std::path::Path;

use glam::DVec3;
use image::DynamicImage;

use super::geo_grid::{bilinear_taps, lat_lon};
use super::height_field::HeightField;
use super::map_error::MapError;

/// The offset of the 16-bit encoding: a stored value is metres + `HEIGHT_OFFSET_M`.
pub const HEIGHT_OFFSET_M: f64 = 11_000.0;

/// Heights in metres on an equirectangular grid (layout in `geo_grid.rs`).
#[derive(Clone, Debug)]
pub struct HeightMap {
    pub width: usize,
    pub height: usize,
    /// Row-major, north row first, metres.
    pub metres: Vec<f32>,
    /// The largest `|metres|`.
    pub max_abs_m: f64,
}

impl HeightMap {
    /// Loads a 16-bit grey PNG in the offset encoding. A missing file, a file that does
    /// not decode, or one that is not 16-bit grey with a 2:1 aspect is an error naming it.
    pub fn load(path: &Path) -> Result<HeightMap, MapError> {
        let image = super::load_image(path)?;
        let DynamicImage::ImageLuma16(grey) = image else {
            return Err(MapError::Format {
                path: path.to_owned(),
                found: format!("{:?}", image.color()),
                expected: "a 16-bit grey PNG (value = metres + 11000)",
            });
        };
        let (width, height) = (grey.width() as usize, grey.height() as usize);
        super::check_aspect(path, width, height)?;
        let metres: Vec<f32> = grey
            .into_raw()
            .into_iter()
            .map(|v| (v as f64 - HEIGHT_OFFSET_M) as f32)
            .collect();
        Ok(HeightMap::from_metres(width, height, metres))
    }

    /// A map from heights in metres (row-major, north row first).
    pub fn from_metres(width: usize, height: usize, metres: Vec<f32>) -> HeightMap {
        assert_eq!(metres.len(), width * height, "height map size");
        let max_abs_m = metres.iter().fold(0.0f64, |m, &h| m.max(h.abs() as f64));
        HeightMap {
            width,
            height,
            metres,
            max_abs_m,
        }
    }

    /// The bilinear height at a latitude and longitude (radians), metres.
    pub fn sample(&self, lat_rad: f64, lon_rad: f64) -> f64 {
        bilinear_taps(self.width, self.height, lat_rad, lon_rad)
            .iter()
            .map(|&(k, w)| w * self.metres[k] as f64)
            .sum()
    }
}

impl HeightField for HeightMap {
    fn height_m(&self, direction: DVec3) -> f64 {
        let (lat, lon) = lat_lon(direction);
        self.sample(lat, lon)
    }

    fn max_abs_height_m(&self) -> f64 {
        self.max_abs_m
    }

    fn sample_spacing_rad(&self) -> f64 {
        PI / self.height as f64
    }
}
