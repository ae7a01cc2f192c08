//! Planet terrain, CPU side: the Earth's maps, the cube sphere, the chunked level of
//! detail and the chunk meshes (docs/terrain.md).
//!
//! Data flows one way: [`HeightMap`], [`LandMask`] and [`ColourMap`] (from [`EarthData`]:
//! built in, or a folder) -> [`RefinedHeights`] (detail below the data's resolution, held
//! to the mask's coastline) -> [`TerrainSurface`] (radius, exaggeration, sea surface) ->
//! [`lod::select_chunks`] for a camera -> one [`ChunkMesh`] per chosen chunk, positions
//! relative to its f64 origin.

pub mod chunk_cache;
pub mod chunk_cover;
pub mod chunk_key;
pub mod chunk_mesh;
pub mod chunk_selector;
pub mod chunk_worker;
pub mod coastline;
pub mod colour_map;
pub mod colour_mips;
pub mod colour_texture;
pub mod cube_sphere;
pub mod detail_morph;
pub mod detail_noise;
pub mod earth_data;
pub mod frustum;
pub mod geo_grid;
pub mod geomorph;
pub mod height_field;
pub mod height_map;
pub mod land_mask;
pub mod lod;
pub mod map_error;
pub mod map_image;
pub mod normal_map;
pub mod normal_texture;
pub mod pass;
pub mod refined_heights;
pub mod relief_amplitude;
pub mod sea_colour;
pub mod stitching;
pub mod surface;
pub mod terrain_pipeline;

pub use chunk_mesh::ChunkMesh;
pub use colour_map::ColourMap;
pub use earth_data::EarthData;
pub use height_field::HeightField;
pub use height_map::HeightMap;
pub use land_mask::LandMask;
pub use map_error::MapError;
pub use refined_heights::RefinedHeights;
pub use surface::TerrainSurface;
