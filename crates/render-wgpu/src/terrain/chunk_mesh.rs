//! A chunk's mesh: vertex positions relative to a per-chunk origin, normals from the
//! relief at the chunk's resolution, and the stitched triangles.
//!
//! Normals: the cross product of the central differences between a vertex's neighbours
//! along u and along v on the chunk's grid, extended by one cell beyond the chunk's
//! edges, so each chunk's normals are those of the relief sampled at its own cell size
//! (a coarse chunk far away is shaded by the relief it draws, not by metre-scale detail
//! it cannot show). Neighbouring chunks of the same level agree at shared vertices; a
//! vertex shared with a coarser chunk gets each chunk's own normal.
//!
//! Each vertex also carries its morph target's normal (`geomorph.rs`): the parent's
//! normal where the vertex's position morphs to, from central differences two cells
//! apart (the parent's cells), so the grid reaches two cells beyond the chunk.
//!
//! Camera-relative rendering: positions are computed in f64, planet-centred, then stored
//! as f32 offsets from the chunk's origin (its centre's point on the reference sphere).
//! Each frame the renderer uploads `origin - camera` (computed in f64, then rounded to
//! f32) per chunk, so a vertex reaches the GPU as a sum of two values that are small near
//! the camera: no jitter a metre above the ground, where planet-centred f32 coordinates
//! (spacing 0.5 m at 6,360 km) would shake. A chunk's f32 offsets are within `6e-8` of its
//! size of the f64 positions; shared edge vertices are equal in f64 (see `stitching.rs`,
//! `chunk_key.rs` and the test below) and may differ in their last f32 bits between two
//! chunks, which is far below a pixel.

use glam::DVec3;

use super::chunk_key::ChunkKey;
use super::cube_sphere::direction;
use super::detail_morph::ParentNormalMap;
use super::geomorph::{
    MorphEnds, MorphRole, morph_normal, morph_role, normal_factor, normal_pair, target_pair,
    vertex_factor,
};
use super::height_field::HeightField;
use super::lod::SelectedChunk;
use super::normal_map::NormalMap;
use super::stitching::stitched_indices;
use super::surface::TerrainSurface;

/// The CPU-side mesh of one chunk, ready for upload.
#[derive(Clone, Debug)]
pub struct ChunkMesh {
    pub key: ChunkKey,
    /// Cells along a side; the mesh has `(cells + 1)^2` vertices, vertex (i, j) at index
    /// `j (cells + 1) + i`.
    pub cells: u32,
    /// The chunk's origin, planet-centred, metres.
    pub origin_m: DVec3,
    /// Vertex positions relative to `origin_m`, metres.
    pub positions: Vec<[f32; 3]>,
    /// Outward unit normals.
    pub normals: Vec<[f32; 3]>,
    /// The height field's height at each vertex, metres (below 0 in the sea, where the
    /// drawn surface is the sea's): the terrain shader's land or water.
    pub heights_m: Vec<f32>,
    /// Each vertex's morph target relative to the vertex, metres (small, so the shader's
    /// f32 morph is nearly exact): the parent's surface below it, or for an even vertex of
    /// an edge the coarser neighbour's (`geomorph.rs`).
    pub morph_offsets: Vec<[f32; 3]>,
    /// The height field's height at each morph target, metres.
    pub morph_heights_m: Vec<f32>,
    /// Each vertex's morph target's unit normal: the parent's normal there, interpolated
    /// as the parent's triangles interpolate it (`geomorph.rs`).
    pub morph_normals: Vec<[f32; 3]>,
    /// Counter-clockwise triangles (seen from outside), stitched to coarser neighbours.
    pub indices: Vec<u32>,
    /// The relief's normals finer than the mesh (`normal_map.rs`).
    pub normal_map: NormalMap,
    /// The parent's normal map over the chunk, the map's morph target
    /// (`detail_morph.rs`).
    pub parent_map: ParentNormalMap,
}

/// Cells by which a mesh's grid reaches beyond the chunk: one parent cell, for the
/// parent's normals at the morph targets.
const MARGIN: i64 = 2;

/// Point (i, j) of a chunk's grid extended by [`MARGIN`] cells on every side (`side`
/// points along a row, (-MARGIN, -MARGIN) first).
fn grid_point<T: Copy>(grid: &[T], side: i64, i: i64, j: i64) -> T {
    grid[((j + MARGIN) * side + i + MARGIN) as usize]
}

/// The unit direction of vertex (i, j) of a chunk with `cells` cells along a side.
pub fn vertex_direction(key: ChunkKey, cells: u32, i: u32, j: u32) -> DVec3 {
    let (u, v) = key.vertex_uv(cells, i as i64, j as i64);
    direction(key.face, u, v)
}

impl ChunkMesh {
    /// Builds the mesh of a selected chunk on `surface`.
    pub fn build<H: HeightField>(
        surface: &TerrainSurface<H>,
        chunk: &SelectedChunk,
        cells: u32,
    ) -> ChunkMesh {
        let key = chunk.key;
        let origin_m = vertex_direction(key, cells, cells / 2, cells / 2) * surface.radius_m;
        // Points on the grid beyond the chunk on every side, for the normals.
        let side = cells as i64 + 1 + 2 * MARGIN;
        let reach = -MARGIN..=cells as i64 + MARGIN;
        let (grid, grid_heights): (Vec<DVec3>, Vec<f64>) = reach
            .clone()
            .flat_map(|j| reach.clone().map(move |i| (i, j)))
            .map(|(i, j)| {
                let (u, v) = key.vertex_uv(cells, i, j);
                let d = direction(key.face, u, v);
                let h = surface.heights.height_m(d);
                (d * (surface.radius_m + surface.elevation_of_height(h)), h)
            })
            .unzip();
        let count = ((cells + 1) * (cells + 1)) as usize;
        let mut positions = Vec::with_capacity(count);
        let mut normals = Vec::with_capacity(count);
        let mut heights_m = Vec::with_capacity(count);
        let mut morph_offsets = Vec::with_capacity(count);
        let mut morph_heights_m = Vec::with_capacity(count);
        let mut morph_normals = Vec::with_capacity(count);
        let at = |(i, j): (i64, i64)| grid_point(&grid, side, i, j);
        // The parent's normal at its vertex (i, j) of this grid (both even).
        let parent_normal = |(i, j): (i64, i64)| {
            (at((i + 2, j)) - at((i - 2, j)))
                .cross(at((i, j + 2)) - at((i, j - 2)))
                .normalize()
        };
        for j in 0..=cells {
            for i in 0..=cells {
                let (i, j) = (i as i64, j as i64);
                positions.push(
                    (grid_point(&grid, side, i, j) - origin_m)
                        .as_vec3()
                        .to_array(),
                );
                heights_m.push(grid_point(&grid_heights, side, i, j) as f32);
                let along_u = grid_point(&grid, side, i + 1, j) - grid_point(&grid, side, i - 1, j);
                let along_v = grid_point(&grid, side, i, j + 1) - grid_point(&grid, side, i, j - 1);
                normals.push(along_u.cross(along_v).normalize().as_vec3().to_array());
                let [a, b] =
                    target_pair(key, cells, i as u32, j as u32).map(|(i, j)| (i as i64, j as i64));
                let target =
                    (grid_point(&grid, side, a.0, a.1) + grid_point(&grid, side, b.0, b.1)) * 0.5;
                let own = grid_point(&grid, side, i, j);
                morph_offsets.push((target - own).as_vec3().to_array());
                let height = 0.5
                    * (grid_point(&grid_heights, side, a.0, a.1)
                        + grid_point(&grid_heights, side, b.0, b.1));
                morph_heights_m.push(height as f32);
                let [a, b] =
                    normal_pair(key, cells, i as u32, j as u32).map(|(i, j)| (i as i64, j as i64));
                let target_normal = (parent_normal(a) + parent_normal(b)).normalize();
                morph_normals.push(target_normal.as_vec3().to_array());
            }
        }
        ChunkMesh {
            key,
            cells,
            origin_m,
            positions,
            normals,
            heights_m,
            morph_offsets,
            morph_heights_m,
            morph_normals,
            indices: stitched_indices(cells, chunk.coarser),
            normal_map: NormalMap::build_sharing(surface, key, cells, |i, j| {
                grid_point(&grid, side, i, j)
            }),
            parent_map: ParentNormalMap::build(key, cells, |i, j| grid_point(&grid, side, i, j)),
        }
    }

    /// A sphere holding every vertex, hence every triangle (centre, radius), metres:
    /// centred on the origin, reaching the farthest vertex (plus a millimetre for the f32
    /// offsets).
    pub fn bounding_sphere(&self) -> (DVec3, f64) {
        let reach = self
            .positions
            .iter()
            .map(|&p| glam::Vec3::from_array(p).as_dvec3().length())
            .fold(0.0, f64::max);
        (self.origin_m, reach + 1e-3)
    }

    /// A vertex's planet-centred position as the GPU sees it (origin plus f32 offset).
    pub fn world_position_m(&self, index: u32) -> DVec3 {
        self.origin_m + glam::Vec3::from_array(self.positions[index as usize]).as_dvec3()
    }

    /// A vertex's morph factor for a camera at `camera_m`, drawn with the coarser edges
    /// `coarser` and the morph ends `ends` (`geomorph.rs`; the vertex shader's twin).
    pub fn morph_factor(
        &self,
        index: u32,
        coarser: [bool; 4],
        camera_m: DVec3,
        ends: MorphEnds,
    ) -> f64 {
        let (role, distance_m) = self.role_and_distance(index, coarser, camera_m);
        vertex_factor(role, distance_m, ends)
    }

    /// A vertex's part in the morph (`geomorph.rs`) with the coarser edges `coarser`, and
    /// its distance from a camera at `camera_m`.
    fn role_and_distance(
        &self,
        index: u32,
        coarser: [bool; 4],
        camera_m: DVec3,
    ) -> (MorphRole, f64) {
        let (i, j) = (index % (self.cells + 1), index / (self.cells + 1));
        (
            morph_role(self.cells, coarser, i, j),
            (self.world_position_m(index) - camera_m).length(),
        )
    }

    /// A vertex's planet-centred position as the vertex shader morphs it by `factor`
    /// ([`ChunkMesh::morph_factor`]), in f64 from the f32 offsets.
    pub fn morphed_position_m(&self, index: u32, factor: f64) -> DVec3 {
        let offset = glam::Vec3::from_array(self.morph_offsets[index as usize]).as_dvec3();
        self.world_position_m(index) + offset * factor
    }

    /// The morph factor of a vertex's normal ([`normal_factor`]; the vertex shader's
    /// twin), as [`ChunkMesh::morph_factor`].
    pub fn normal_morph_factor(
        &self,
        index: u32,
        coarser: [bool; 4],
        camera_m: DVec3,
        ends: MorphEnds,
    ) -> f64 {
        let (role, distance_m) = self.role_and_distance(index, coarser, camera_m);
        normal_factor(role, distance_m, ends)
    }

    /// A vertex's unit normal as the vertex shader morphs it by `factor`
    /// ([`ChunkMesh::normal_morph_factor`]), in f64 from the f32 normals
    /// ([`morph_normal`]).
    pub fn morphed_normal(&self, index: u32, factor: f64) -> DVec3 {
        let n = |v: &[[f32; 3]]| glam::Vec3::from_array(v[index as usize]).as_dvec3();
        morph_normal(n(&self.normals), n(&self.morph_normals), factor)
    }

    /// A vertex's height field height as the vertex shader morphs it by `factor`, m.
    pub fn morphed_height_m(&self, index: u32, factor: f64) -> f64 {
        let (own, target) = (
            f64::from(self.heights_m[index as usize]),
            f64::from(self.morph_heights_m[index as usize]),
        );
        own + (target - own) * factor
    }
}

#[cfg(test)]
mod tests {
    use std::collections::{HashMap, HashSet};

    use super::super::geomorph::{morphed_vertex_m, switch_distance_m};
    use super::super::lod::{LodSettings, LodView, select_chunks};
    use super::*;

    const R: f64 = 6.36e6;

    /// Smooth relief of a few kilometres, different on every face.
    struct Waves;

    impl HeightField for Waves {
        fn height_m(&self, d: DVec3) -> f64 {
            3000.0 * (7.0 * d.x).sin() * (5.0 * d.y).cos() + 1500.0 * (11.0 * d.z + 1.0).sin()
        }
        fn max_abs_height_m(&self) -> f64 {
            4500.0
        }
        fn sample_spacing_rad(&self) -> f64 {
            1e-3
        }
    }

    #[test]
    fn the_normal_map_built_with_the_mesh_vertices_equals_the_one_evaluated_alone() {
        let surface = TerrainSurface::new(Waves, R);
        let key = ChunkKey::root(super::super::cube_sphere::Face(2)).children()[3].children()[0];
        let chunk = SelectedChunk {
            key,
            coarser: [false; 4],
        };
        let mesh = ChunkMesh::build(&surface, &chunk, 8);
        assert_eq!(mesh.normal_map, NormalMap::build(&surface, key, 8));
    }

    fn bits(p: DVec3) -> [u64; 3] {
        p.to_array().map(f64::to_bits)
    }

    /// All chunks chosen for a camera low over a cube corner (three faces and many levels
    /// meet there) form one closed surface: every triangle edge, in f64 positions bit for
    /// bit, is matched by exactly one reversed edge of another or the same chunk, and the
    /// Euler characteristic is that of a sphere. No crack, no T-junction.
    #[test]
    fn chunks_close_up_without_cracks() {
        let cells = 8;
        let surface = TerrainSurface {
            exaggeration: 2.0,
            sea_surface: false,
            ..TerrainSurface::new(Waves, R)
        };
        let settings = LodSettings {
            cells,
            max_error_px: 40.0,
            max_level: 9,
            ..LodSettings::new(R)
        };
        let up = DVec3::new(1.0, 1.0, 1.02).normalize();
        let camera = up * (R + surface.elevation_m(up) + 500.0);
        let elevation = |d: DVec3| surface.elevation_m(d);
        let chunks =
            select_chunks(&settings, &LodView::new(camera, 1080.0, 1.0), elevation).unwrap();
        let levels: HashSet<u8> = chunks.iter().map(|c| c.key.level).collect();
        assert!(levels.len() >= 6, "levels {levels:?}");
        assert!(chunks.iter().any(|c| c.coarser.iter().any(|&b| b)));

        let mut edges: HashMap<([u64; 3], [u64; 3]), u32> = HashMap::new();
        let mut vertices = HashSet::new();
        let mut triangles = 0;
        for chunk in &chunks {
            let mesh = ChunkMesh::build(&surface, chunk, cells);
            let world = |k: u32| {
                let (i, j) = (k % (cells + 1), k / (cells + 1));
                surface.position_m(vertex_direction(chunk.key, cells, i, j))
            };
            let size = settings.bounding_sphere(chunk.key, &elevation).1;
            for t in mesh.indices.chunks(3) {
                let p = [world(t[0]), world(t[1]), world(t[2])];
                // Outward winding.
                assert!((p[1] - p[0]).cross(p[2] - p[0]).dot(p[0]) > 0.0);
                for (k, q) in t.iter().zip(p) {
                    assert!((mesh.world_position_m(*k) - q).length() < 1.2e-7 * size + 1e-9);
                    vertices.insert(bits(q));
                }
                for (a, b) in [(p[0], p[1]), (p[1], p[2]), (p[2], p[0])] {
                    *edges.entry((bits(a), bits(b))).or_default() += 1;
                }
                triangles += 1;
            }
        }
        for (&(a, b), &count) in &edges {
            assert_eq!(count, 1, "edge used twice in one direction");
            assert_eq!(
                edges.get(&(b, a)),
                Some(&1),
                "open edge: a crack or a T-junction"
            );
        }
        let euler = vertices.len() as i64 - (edges.len() / 2) as i64 + triangles;
        assert_eq!(euler, 2);
    }

    /// Normals are the surface's at the chunk's resolution: unit length, outwards, and
    /// within the cell's curvature error of the smooth surface's normal.
    #[test]
    fn normals_follow_the_height_field() {
        let surface = TerrainSurface {
            sea_surface: false,
            ..TerrainSurface::new(Waves, R)
        };
        let mut key = super::super::chunk_key::ChunkKey::root(super::super::cube_sphere::Face(2));
        for _ in 0..10 {
            key = key.children()[1];
        }
        let chunk = SelectedChunk {
            key,
            coarser: [false; 4],
        };
        let cells = 8;
        let mesh = ChunkMesh::build(&surface, &chunk, cells);
        // The smooth surface's normal from differences over 1 m.
        let exact = |d: DVec3| {
            let t1 = DVec3::Z.cross(d).normalize();
            let t2 = d.cross(t1);
            let step = 1.0 / R;
            let p = |t: DVec3, s: f64| surface.position_m((d + t * s).normalize());
            (p(t1, step) - p(t1, -step))
                .cross(p(t2, step) - p(t2, -step))
                .normalize()
        };
        for (k, n) in mesh.normals.iter().enumerate() {
            let n = glam::Vec3::from_array(*n).as_dvec3();
            let d = vertex_direction(key, cells, k as u32 % (cells + 1), k as u32 / (cells + 1));
            assert!((n.length() - 1.0).abs() < 1e-6);
            assert!((n - exact(d)).length() < 1e-4, "{n} {}", exact(d));
            assert!(n.dot(d) > 0.5);
        }
    }

    /// The mesh's f32 targets give the f64 specification's morphed positions.
    #[test]
    fn the_meshes_targets_round_the_specification() {
        let surface = TerrainSurface::new(Waves, R);
        let mut key = super::super::chunk_key::ChunkKey::root(super::super::cube_sphere::Face(5));
        for _ in 0..9 {
            key = key.children()[1];
        }
        let chunk = SelectedChunk {
            key,
            coarser: [true, false, false, true],
        };
        let cells = 8;
        let settings = LodSettings {
            cells,
            ..LodSettings::new(R)
        };
        let mesh = ChunkMesh::build(&surface, &chunk, cells);
        let origin = mesh.origin_m;
        let view = LodView::new(origin * 1.000_05, 720.0, 1.0);
        let ends = MorphEnds::of_level(&settings, &view, key.level);
        for k in 0..mesh.positions.len() as u32 {
            let (i, j) = (k % (cells + 1), k / (cells + 1));
            let exact = morphed_vertex_m(&surface, &chunk, cells, (i, j), view.camera_m, ends);
            let m = mesh.morph_factor(k, chunk.coarser, view.camera_m, ends);
            let drawn = mesh.morphed_position_m(k, m);
            assert!((drawn - exact).length() < 2.4e-7 * (exact - origin).length() + 1e-9);
        }
    }

    /// Ripples 20 km long under cells of 5 and 10 km: a child's normals are far from its
    /// parent's.
    struct Ripples;

    impl HeightField for Ripples {
        fn height_m(&self, d: DVec3) -> f64 {
            600.0 * (2000.0 * d.x).sin() * (1700.0 * d.y).cos() + 300.0 * (2300.0 * d.z).sin()
        }
        fn max_abs_height_m(&self) -> f64 {
            900.0
        }
        fn sample_spacing_rad(&self) -> f64 {
            1e-4
        }
    }

    /// With the parent exactly at its switch distance, every vertex of its four children
    /// has the normal the parent's triangles give it: the parent mesh's vertex normal at
    /// an even-even vertex, the normalised mean of the two parent vertices' normals
    /// around an odd one (within 1e-6, f32 normals); unmorphed they depart by up to 0.1. With
    /// the camera at the parent's sphere they are their own.
    #[test]
    fn at_the_switch_distance_children_have_their_parents_normals() {
        let surface = TerrainSurface::new(Ripples, R);
        let cells = 8;
        let settings = LodSettings {
            cells,
            ..LodSettings::new(R)
        };
        let mut parent = ChunkKey::root(super::super::cube_sphere::Face(1));
        for _ in 0..7 {
            parent = parent.children()[1];
        }
        let elevation = |d: DVec3| surface.elevation_m(d);
        let (centre, radius) = settings.bounding_sphere(parent, &elevation);
        let pixels = LodView::new(DVec3::ZERO, 360.0, 1.0);
        let switch = switch_distance_m(&settings, &pixels, parent.level);
        let camera = |distance: f64| centre + centre.normalize() * (radius + distance);
        let whole = |key| SelectedChunk {
            key,
            coarser: [false; 4],
        };
        let parent_mesh = ChunkMesh::build(&surface, &whole(parent), cells);
        let parent_normal = |(i, j): (u32, u32)| {
            let k = j * (cells + 1) + i;
            glam::Vec3::from_array(parent_mesh.normals[k as usize]).as_dvec3()
        };
        let (mut worst, mut unmorphed_best) = (0.0f64, f64::INFINITY);
        let mut unmorphed_worst = 0.0f64;
        for key in parent.children() {
            let mesh = ChunkMesh::build(&surface, &whole(key), cells);
            let ends = MorphEnds::of_level(&settings, &pixels, key.level);
            // The child's grid point (i, j), both even, in the parent's grid.
            let in_parent =
                |(i, j): (u32, u32)| (((key.x & 1) * cells + i) / 2, ((key.y & 1) * cells + j) / 2);
            for k in 0..mesh.normals.len() as u32 {
                let (i, j) = (k % (cells + 1), k / (cells + 1));
                let m = mesh.normal_morph_factor(k, [false; 4], camera(switch), ends);
                assert_eq!(m, 1.0);
                let [a, b] = normal_pair(key, cells, i, j).map(in_parent);
                let expected = (parent_normal(a) + parent_normal(b)).normalize();
                worst = worst.max((mesh.morphed_normal(k, m) - expected).length());
                let own = mesh.morphed_normal(k, 0.0);
                let off = (own - expected).length();
                unmorphed_worst = unmorphed_worst.max(off);
                if i % 2 == 1 || j % 2 == 1 {
                    unmorphed_best = unmorphed_best.min(off);
                }
                let near = mesh.normal_morph_factor(k, [false; 4], camera(0.0), ends);
                assert_eq!(mesh.morphed_normal(k, near), own);
            }
        }
        eprintln!("morphed {worst:e}, unmorphed up to {unmorphed_worst:e}");
        assert!(worst < 1e-6, "{worst}");
        assert!(unmorphed_worst > 0.05, "{unmorphed_worst}");
        assert!(unmorphed_best > 0.0, "{unmorphed_best}");
    }
}
