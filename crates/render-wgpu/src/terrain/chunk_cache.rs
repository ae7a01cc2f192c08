//! The terrain pass's chunk meshes on the GPU, by key: uploaded when built, kept while
//! drawn, dropped after [`KEEP_FRAMES`] frames unused. The six root chunks stay: they
//! cover the planet while finer meshes are being built (`chunk_cover.rs`).

use std::collections::HashMap;

use bytemuck::{Pod, Zeroable};
use glam::DVec3;
use wgpu::util::DeviceExt;

use crate::gpu::context::GpuContext;
use crate::terrain::chunk_key::ChunkKey;
use crate::terrain::chunk_mesh::ChunkMesh;
use crate::terrain::normal_texture::NormalTextures;

/// Chunks unused for this many frames leave the cache.
pub const KEEP_FRAMES: u64 = 240;

/// A chunk's vertex on the GPU: position relative to the origin, the normal, the height
/// field's height (below 0: water), and the morph target (relative to the vertex), its
/// height and its normal (`geomorph.rs`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub height: f32,
    pub morph_offset: [f32; 3],
    pub target_height: f32,
    pub target_normal: [f32; 3],
}

/// A chunk's mesh on the GPU.
#[derive(Debug)]
pub struct GpuChunk {
    pub vertices: wgpu::Buffer,
    /// The chunk's normal map (`normal_map.rs`) and its parent's over it
    /// (`detail_morph.rs`), the terrain shader's group 1.
    pub normal_map: wgpu::BindGroup,
    pub origin_m: DVec3,
    /// Bounding sphere of the mesh's vertices (centre, radius), m.
    pub bounds: (DVec3, f64),
    /// The largest distance of a vertex from the planet's centre, m: no point of the
    /// chunk's flat triangles, morphed or not, lies farther (the distance is convex).
    pub max_radius_m: f64,
    /// The last frame that drew the chunk.
    pub last_used: u64,
    /// Whether a vertex lies in the sea (its height below 0).
    pub has_water: bool,
}

/// The meshes on the GPU; see the module documentation.
#[derive(Debug, Default)]
pub struct ChunkCache {
    chunks: HashMap<ChunkKey, GpuChunk>,
}

impl ChunkCache {
    pub fn contains(&self, key: ChunkKey) -> bool {
        self.chunks.contains_key(&key)
    }

    pub fn get(&self, key: ChunkKey) -> Option<&GpuChunk> {
        self.chunks.get(&key)
    }

    pub fn len(&self) -> usize {
        self.chunks.len()
    }

    pub fn is_empty(&self) -> bool {
        self.chunks.is_empty()
    }

    pub fn clear(&mut self) {
        self.chunks.clear();
    }

    /// Marks `key` drawn in `frame`.
    pub fn touch(&mut self, key: ChunkKey, frame: u64) {
        if let Some(chunk) = self.chunks.get_mut(&key) {
            chunk.last_used = frame;
        }
    }

    /// Drops the chunks unused for [`KEEP_FRAMES`] frames before `frame`, but the roots.
    pub fn evict(&mut self, frame: u64) {
        self.chunks
            .retain(|k, c| k.level == 0 || frame - c.last_used < KEEP_FRAMES);
    }

    /// Uploads `mesh` and its normal map, used in `frame`.
    pub fn insert(
        &mut self,
        gpu: &GpuContext,
        normal_textures: &NormalTextures,
        mesh: &ChunkMesh,
        frame: u64,
    ) {
        let vertices: Vec<Vertex> = (0..mesh.positions.len())
            .map(|k| Vertex {
                position: mesh.positions[k],
                normal: mesh.normals[k],
                height: mesh.heights_m[k],
                morph_offset: mesh.morph_offsets[k],
                target_height: mesh.morph_heights_m[k],
                target_normal: mesh.morph_normals[k],
            })
            .collect();
        let buffer = buffer_with(gpu, "terrain chunk", &vertices, wgpu::BufferUsages::VERTEX);
        // The targets are midpoints of vertices: the vertices' sphere and largest radius
        // bound the morphed triangles too.
        let (_, radius) = mesh.bounding_sphere();
        let max_radius_m = (0..mesh.positions.len() as u32)
            .map(|k| mesh.world_position_m(k).length())
            .fold(0.0, f64::max);
        self.chunks.insert(
            mesh.key,
            GpuChunk {
                vertices: buffer,
                normal_map: normal_textures.upload(gpu, &mesh.normal_map, &mesh.parent_map),
                origin_m: mesh.origin_m,
                bounds: (mesh.origin_m, radius),
                max_radius_m,
                last_used: frame,
                has_water: mesh.heights_m.iter().any(|&h| h < 0.0),
            },
        );
    }
}

/// A buffer holding `data`.
pub fn buffer_with<T: Pod>(
    gpu: &GpuContext,
    label: &str,
    data: &[T],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(data),
            usage,
        })
}
