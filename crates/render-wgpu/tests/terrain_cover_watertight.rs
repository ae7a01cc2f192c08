//! The chunks a frame draws while meshes are still being built (`terrain/chunk_cover.rs`,
//! docs/terrain.md "No popping"): the chosen chunks that are ready and the covers of
//! those that are not, stitched and geomorphed as one set, close up without a crack.

use std::collections::{HashMap, HashSet};

use glam::DVec3;
use render_wgpu::terrain::chunk_cover::cover;
use render_wgpu::terrain::chunk_key::ChunkKey;
use render_wgpu::terrain::cube_sphere::{Face, direction};
use render_wgpu::terrain::geomorph::{MorphEnds, morphed_vertex_m};
use render_wgpu::terrain::lod::{LodSettings, LodView, SelectedChunk, select_chunks};
use render_wgpu::terrain::{ChunkMesh, HeightField, TerrainSurface};

const R: f64 = 6.36e6;

/// Relief of a few kilometres.
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

/// The camera, the chosen chunks, those whose meshes were drawn before, and which chosen
/// meshes are ready besides.
type Scenario<'a> = (
    LodView,
    &'a [SelectedChunk],
    &'a [SelectedChunk],
    &'a dyn Fn(ChunkKey) -> bool,
);

/// Every triangle edge of `draws`, in f64 positions bit for bit and geomorphed for
/// `view`, meets exactly one reversed edge, and the Euler characteristic is 2. Returns
/// how many vertices the morph moved.
fn assert_watertight(
    surface: &TerrainSurface<Waves>,
    settings: &LodSettings,
    view: &LodView,
    draws: &[SelectedChunk],
) -> usize {
    let cells = settings.cells;
    let bits = |p: DVec3| p.to_array().map(f64::to_bits);
    let mut edges: HashMap<([u64; 3], [u64; 3]), u32> = HashMap::new();
    let mut vertices = HashSet::new();
    let mut triangles = 0i64;
    let mut moved = 0;
    for chunk in draws {
        let mesh = ChunkMesh::build(surface, chunk, cells);
        let ends = MorphEnds::of_level(settings, view, chunk.key.level);
        let world = |k: u32| {
            let (i, j) = (k % (cells + 1), k / (cells + 1));
            morphed_vertex_m(surface, chunk, cells, (i, j), view.camera_m, ends)
        };
        for t in mesh.indices.chunks(3) {
            let p = [world(t[0]), world(t[1]), world(t[2])];
            for (k, q) in t.iter().zip(p) {
                moved += usize::from((mesh.world_position_m(*k) - q).length() > 1e-3);
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
        assert_eq!(edges.get(&(b, a)), Some(&1), "open edge: a crack");
    }
    let euler = vertices.len() as i64 - (edges.len() / 2) as i64 + triangles;
    assert_eq!(euler, 2);
    moved
}

/// Over a cube corner (three faces meet): the camera descending (the meshes chosen from
/// 2,000 km ready, the choice from 500 m) and climbing (from 500 m to 50 km), a third of
/// the chosen meshes ready besides, and descending with the chosen meshes ready on one
/// side of a plane through the camera (fine chunks next to coarse covers, mended by the
/// restriction): covers meet chunks of other levels, and the drawn set, morphed for the
/// camera, is closed.
#[test]
fn covers_and_chosen_chunks_close_up_without_cracks() {
    let surface = TerrainSurface {
        sea_surface: false,
        ..TerrainSurface::new(Waves, R)
    };
    let settings = LodSettings {
        cells: 8,
        max_error_px: 40.0,
        max_level: 9,
        ..LodSettings::new(R)
    };
    let up = DVec3::new(1.0, 1.0, 1.02).normalize();
    let ground = R + surface.elevation_m(up);
    let view = |clearance_m: f64| LodView::new(up * (ground + clearance_m), 1080.0, 1.0);
    let elevation = |d: DVec3| surface.elevation_m(d);
    let choose = |v: &LodView| select_chunks(&settings, v, elevation).unwrap();
    let (low, middle, high) = (view(500.0), view(50_000.0), view(2e6));
    let (near, mid, far) = (choose(&low), choose(&middle), choose(&high));
    let across = up.cross(DVec3::Z).normalize();
    let one_side = |k: ChunkKey| {
        let (u, v) = k.vertex_uv(8, 4, 4);
        direction(k.face, u, v).dot(across) > 0.0
    };
    let third = |k: ChunkKey| (k.x + k.y).is_multiple_of(3);
    let scenarios: [Scenario; 3] = [
        (low, &near, &far, &third),
        (middle, &mid, &near, &third),
        (low, &near, &far, &one_side),
    ];
    for (camera, chosen, before, also_ready) in scenarios {
        let ready: HashSet<ChunkKey> = before
            .iter()
            .map(|c| c.key)
            .chain(chosen.iter().map(|c| c.key).filter(|&k| also_ready(k)))
            .chain(Face::ALL.map(ChunkKey::root))
            .collect();
        let draws = cover(chosen, |k| ready.contains(&k));
        let chosen_keys: HashSet<ChunkKey> = chosen.iter().map(|c| c.key).collect();
        let covers: Vec<&SelectedChunk> = draws
            .iter()
            .filter(|c| !chosen_keys.contains(&c.key))
            .collect();
        let levels: HashSet<u8> = draws.iter().map(|c| c.key.level).collect();
        assert!(
            covers.iter().any(|c| c.coarser.iter().any(|&b| b)),
            "no cover stitched to a coarser chunk"
        );
        let moved = assert_watertight(&surface, &settings, &camera, &draws);
        println!(
            "{} chunks drawn ({} covers), levels {levels:?}, {moved} vertices morphed: closed",
            draws.len(),
            covers.len()
        );
        assert!(moved > 0, "no vertex is morphed");
    }
}
