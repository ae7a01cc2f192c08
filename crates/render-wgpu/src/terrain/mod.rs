//! Planet terrain, CPU side: the Earth's maps, the cube sphere, the chunked level of
//! detail and the chunk meshes (docs/terrain.md).
//!
//! Data flows one way: [`HeightMap`] and [`ColourMap`] (from `assets/earth/`) ->
//! [`TerrainSurface`] (radius, exaggeration, sea surface) -> [`lod::select_chunks`] for a
//! camera -> one [`ChunkMesh`] per chosen chunk, positions relative to its f64 origin.

pub mod chunk_key;
pub mod chunk_mesh;
pub mod colour_map;
pub mod colour_mips;
pub mod cube_sphere;
pub mod frustum;
pub mod geo_grid;
pub mod height_field;
pub mod height_map;
pub mod lod;
pub mod map_error;
pub mod pass;
pub mod stitching;
pub mod surface;

use std::path::{Path, PathBuf};

use image::DynamicImage;

pub use chunk_mesh::ChunkMesh;
pub use colour_map::ColourMap;
pub use height_field::HeightField;
pub use height_map::HeightMap;
pub use map_error::MapError;
pub use surface::TerrainSurface;

/// The folder of the shipped Earth maps in the source tree (`assets/earth`).
pub fn earth_assets_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/earth")
}

/// Decodes an image file, with errors naming it.
fn load_image(path: &Path) -> Result<DynamicImage, MapError> {
    if !path.is_file() {
        return Err(MapError::Missing {
            path: path.to_owned(),
        });
    }
    image::ImageReader::open(path)
        .and_then(|reader| reader.with_guessed_format())
        .map_err(|e| MapError::Read {
            path: path.to_owned(),
            source: image::ImageError::IoError(e),
        })?
        .decode()
        .map_err(|source| MapError::Read {
            path: path.to_owned(),
            source,
        })
}

/// Equirectangular maps are twice as wide as tall.
fn check_aspect(path: &Path, width: usize, height: usize) -> Result<(), MapError> {
    if width != 2 * height || height == 0 {
        return Err(MapError::Format {
            path: path.to_owned(),
            found: format!("{width} x {height}"),
            expected: "an equirectangular map twice as wide as tall",
        });
    }
    Ok(())
}
