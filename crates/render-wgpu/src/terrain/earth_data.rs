//! Where the Earth's maps come from: built into the library (the default, so that a
//! copied or installed binary draws the terrain wherever it runs), or a folder holding
//! `height.png` and `colour.jpg` (and, optionally, `land_mask.png`) in the formats of
//! `docs/terrain.md`.

use std::path::{Path, PathBuf};

use super::colour_map::ColourMap;
use super::height_map::HeightMap;
use super::land_mask::LandMask;
use super::map_error::MapError;
use super::map_image::{decode_image, load_image};
use super::refined_heights::{RefinedHeights, RefinementSettings};

/// The height map's file name, in `assets/earth/` and in a folder of maps.
pub const HEIGHT_FILE: &str = "height.png";
/// The colour map's file name, in `assets/earth/` and in a folder of maps.
pub const COLOUR_FILE: &str = "colour.jpg";

/// The land/sea mask's file name, in `assets/earth/` and (optional) in a folder of maps.
pub const LAND_MASK_FILE: &str = "land_mask.png";

/// `assets/earth/land_mask.png`, built in.
const BUILT_IN_LAND_MASK: &[u8] = include_bytes!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/earth/land_mask.png"
));
/// `assets/earth/height.png`, built in.
const BUILT_IN_HEIGHTS: &[u8] = include_bytes!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/earth/height.png"
));
/// `assets/earth/colour.jpg`, built in.
const BUILT_IN_COLOURS: &[u8] = include_bytes!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/earth/colour.jpg"
));

/// The source of the Earth's height and colour maps.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum EarthData {
    /// The maps of `assets/earth/`, built in.
    #[default]
    BuiltIn,
    /// `height.png` and `colour.jpg` in this folder.
    Folder(PathBuf),
}

impl EarthData {
    /// The maps in folder `dir`: an error naming the folder and both paths when the
    /// folder or either file is missing. (A file that does not decode is named when the
    /// maps are loaded.)
    pub fn folder(dir: impl Into<PathBuf>) -> Result<EarthData, MapError> {
        let dir = dir.into();
        let tried = vec![dir.join(HEIGHT_FILE), dir.join(COLOUR_FILE)];
        let problem = if !dir.exists() {
            "no such folder".to_string()
        } else if !dir.is_dir() {
            "not a folder".to_string()
        } else {
            let missing: Vec<String> = tried
                .iter()
                .filter(|p| !p.is_file())
                .filter_map(|p| p.file_name())
                .map(|name| name.to_string_lossy().into_owned())
                .collect();
            match missing.as_slice() {
                [] => return Ok(EarthData::Folder(dir)),
                [one] => format!("{one} is missing"),
                _ => format!("{} are missing", missing.join(" and ")),
            }
        };
        Err(MapError::Folder {
            dir,
            problem,
            tried,
        })
    }

    /// Decodes the height map.
    pub fn heights(&self) -> Result<HeightMap, MapError> {
        let path = self.path_of(HEIGHT_FILE);
        let image = match self {
            EarthData::BuiltIn => decode_image(BUILT_IN_HEIGHTS, &path)?,
            EarthData::Folder(_) => load_image(&path)?,
        };
        HeightMap::from_image(image, &path)
    }

    /// Decodes the colour map.
    pub fn colours(&self) -> Result<ColourMap, MapError> {
        let path = self.path_of(COLOUR_FILE);
        let image = match self {
            EarthData::BuiltIn => decode_image(BUILT_IN_COLOURS, &path)?,
            EarthData::Folder(_) => load_image(&path)?,
        };
        ColourMap::from_image(image, &path)
    }

    /// Decodes the land/sea mask: the built-in one, or a folder's `land_mask.png` when it
    /// has one (none otherwise: the coastline is then the height map's).
    pub fn land_mask(&self) -> Result<Option<LandMask>, MapError> {
        let path = self.path_of(LAND_MASK_FILE);
        match self {
            EarthData::BuiltIn => LandMask::decode(BUILT_IN_LAND_MASK, &path).map(Some),
            EarthData::Folder(_) if !path.is_file() => Ok(None),
            EarthData::Folder(_) => {
                let bytes = std::fs::read(&path).map_err(|e| MapError::Read {
                    path: path.clone(),
                    source: image::ImageError::IoError(e),
                })?;
                LandMask::decode(&bytes, &path).map(Some)
            }
        }
    }

    /// The heights the terrain draws: the height map refined below its resolution with
    /// the default settings, held to the land mask's coastline where there is one.
    pub fn refined_heights(&self) -> Result<RefinedHeights, MapError> {
        Ok(RefinedHeights::new(
            self.heights()?,
            self.land_mask()?,
            RefinementSettings::default(),
        ))
    }

    /// How errors name map `file` of this source.
    pub fn path_of(&self, file: &str) -> PathBuf {
        match self {
            EarthData::BuiltIn => Path::new("assets/earth").join(format!("{file} (built in)")),
            EarthData::Folder(dir) => dir.join(file),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_maps_decode() {
        let heights = EarthData::BuiltIn.heights().unwrap();
        assert_eq!((heights.width, heights.height), (2160, 1080));
        let colours = EarthData::BuiltIn.colours().unwrap();
        assert_eq!((colours.width, colours.height), (4096, 2048));
        let mask = EarthData::BuiltIn.land_mask().unwrap().unwrap();
        assert_eq!((mask.width, mask.height), (43200, 21600));
    }

    #[test]
    fn a_folder_lacking_maps_names_every_path() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("nowhere");
        let e = EarthData::folder(&missing).unwrap_err().to_string();
        let expected = format!(
            "terrain data folder {}: no such folder; it needs {} and {}",
            missing.display(),
            missing.join("height.png").display(),
            missing.join("colour.jpg").display()
        );
        assert_eq!(e, expected);

        std::fs::write(dir.path().join("height.png"), b"").unwrap();
        let e = EarthData::folder(dir.path()).unwrap_err().to_string();
        assert!(e.contains(": colour.jpg is missing; it needs"), "{e}");
        let e = EarthData::folder(dir.path().join("height.png"))
            .unwrap_err()
            .to_string();
        assert!(e.contains(": not a folder; it needs"), "{e}");
        let empty = dir.path().join("empty");
        std::fs::create_dir(&empty).unwrap();
        let e = EarthData::folder(&empty).unwrap_err().to_string();
        assert!(e.contains(": height.png and colour.jpg are missing"), "{e}");
    }

    #[test]
    fn a_folder_of_maps_is_read_and_a_bad_map_named() {
        let dir = tempfile::tempdir().unwrap();
        image::ImageBuffer::<image::Luma<u16>, _>::from_pixel(8, 4, image::Luma([11_500]))
            .save(dir.path().join(HEIGHT_FILE))
            .unwrap();
        image::RgbImage::from_pixel(8, 4, image::Rgb([200, 10, 10]))
            .save_with_format(dir.path().join(COLOUR_FILE), image::ImageFormat::Jpeg)
            .unwrap();
        let data = EarthData::folder(dir.path()).unwrap();
        let heights = data.heights().unwrap();
        assert_eq!(
            (heights.width, heights.height, heights.max_abs_m),
            (8, 4, 500.0)
        );
        let colours = data.colours().unwrap();
        assert!(colours.texels[0][0] > 150 && colours.texels[0][2] < 60);
        assert!(data.land_mask().unwrap().is_none());

        std::fs::write(dir.path().join(HEIGHT_FILE), b"not a picture").unwrap();
        let e = data.heights().unwrap_err().to_string();
        let path = dir.path().join(HEIGHT_FILE);
        assert!(
            e.starts_with(&format!("cannot read terrain map {}", path.display())),
            "{e}"
        );
    }
}
