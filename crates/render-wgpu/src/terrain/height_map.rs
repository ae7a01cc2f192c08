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
        HeightMap::from_image(super::map_image::load_image(path)?, path)
    }

    /// The map of a decoded image, with errors naming it `path`.
    pub(super) fn from_image(image: DynamicImage, path: &Path) -> Result<HeightMap, MapError> {
        let DynamicImage::ImageLuma16(grey) = image else {
            return Err(MapError::Format {
                path: path.to_owned(),
                found: format!("{:?}", image.color()),
                expected: "a 16-bit grey PNG (value = metres + 11000)",
            });
        };
        let (width, height) = (grey.width() as usize, grey.height() as usize);
        super::map_image::check_aspect(path, width, height)?;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A map of `assets/earth/` in the source tree.
    fn shipped(file: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../assets/earth")
            .join(file)
    }

    /// Known places of the shipped map (10' texels, so peaks and trenches are averaged):
    /// the Challenger Deep area deep, the Himalaya and Tibet high, the open oceans below 0,
    /// the Sahara low land, the Dead Sea rift near sea level, Antarctica's ice high.
    #[test]
    fn shipped_heights_at_known_places() {
        let map = HeightMap::load(&shipped("height.png")).unwrap();
        assert_eq!((map.width, map.height), (2160, 1080));
        let at = |lat: f64, lon: f64| map.sample(lat.to_radians(), lon.to_radians());
        let mariana = at(11.35, 142.2);
        assert!(mariana < -8000.0, "Mariana trench {mariana}");
        let everest = at(27.99, 86.93);
        assert!(everest > 5000.0, "Everest {everest}");
        assert!(at(32.0, 88.0) > 4000.0, "Tibet");
        for (lat, lon) in [(0.0, -150.0), (30.0, -40.0), (-40.0, 80.0), (-60.0, -120.0)] {
            let h = at(lat, lon);
            assert!(h < -2000.0, "ocean at {lat}, {lon}: {h}");
        }
        let sahara = at(23.0, 10.0);
        assert!((0.0..1500.0).contains(&sahara), "Sahara {sahara}");
        assert!(at(-80.0, 30.0) > 2000.0, "East Antarctica");
        // The trench is the deepest region of the map, the Himalaya among its highest.
        assert!(
            map.max_abs_m > 9000.0 && map.max_abs_m < 11000.0,
            "{}",
            map.max_abs_m
        );
        // The direction form agrees with latitude and longitude.
        let d = super::super::geo_grid::direction(27.99f64.to_radians(), 86.93f64.to_radians());
        assert_eq!(map.height_m(d), everest);
    }

    #[test]
    fn missing_and_malformed_files_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("nothing.png");
        let e = HeightMap::load(&missing).unwrap_err();
        assert!(matches!(e, MapError::Missing { .. }));
        let expected = format!("terrain map {} is missing", missing.display());
        assert_eq!(e.to_string(), expected);

        let garbage = dir.path().join("garbage.png");
        std::fs::write(&garbage, b"\x89PNG\r\n\x1a\nnot really").unwrap();
        let e = HeightMap::load(&garbage).unwrap_err();
        assert!(matches!(e, MapError::Read { .. }), "{e}");
        assert!(e.to_string().contains("garbage.png"), "{e}");

        let eight_bit = dir.path().join("eight_bit.png");
        image::GrayImage::new(4, 2).save(&eight_bit).unwrap();
        let e = HeightMap::load(&eight_bit).unwrap_err();
        assert!(matches!(e, MapError::Format { .. }), "{e}");
        assert!(
            e.to_string().contains("eight_bit.png") && e.to_string().contains("16-bit"),
            "{e}"
        );

        let square = dir.path().join("square.png");
        image::ImageBuffer::<image::Luma<u16>, _>::new(4, 4)
            .save(&square)
            .unwrap();
        let e = HeightMap::load(&square).unwrap_err();
        assert!(
            e.to_string().contains("square.png") && e.to_string().contains("twice as wide"),
            "{e}"
        );
    }
}
