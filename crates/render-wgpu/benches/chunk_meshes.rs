//! What the refined relief costs on the CPU: building the chunk meshes of the default
//! scene's view (3 km above the Pennine Alps, 1280 x 720, 60 degrees) on the refined
//! heights against the same chunks on the data's bilinear heights, and choosing the
//! chunks (`select_chunks`) on each, on one thread; and the refined mesh's normal map
//! (`normal_map.rs`, part of the mesh) alone, and the parent's map over a chunk
//! (`detail_morph.rs`, part of the mesh) from the mesh's grid; rounds interleaved,
//! medians, and their ratios, so the machine's load cancels.
//!
//! Run: `cargo bench -p render-wgpu --bench chunk_meshes`.

use std::time::Instant;

use render_wgpu::terrain::cube_sphere::direction as face_direction;
use render_wgpu::terrain::detail_morph::ParentNormalMap;
use render_wgpu::terrain::geo_grid::direction;
use render_wgpu::terrain::lod::{LodSettings, LodView, SelectedChunk, select_chunks};
use render_wgpu::terrain::normal_map::NormalMap;
use render_wgpu::terrain::{ChunkMesh, EarthData, HeightField, TerrainSurface};

const ROUNDS: usize = 5;
/// Chunks meshed per round (the nearest of the selection come first in key order, so
/// every `k`-th is taken to mix levels).
const MESHED: usize = 400;

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn time<T>(work: impl FnOnce() -> T) -> (f64, T) {
    let start = Instant::now();
    let out = work();
    (start.elapsed().as_secs_f64(), out)
}

fn main() {
    let radius = 6.36e6;
    let earth = EarthData::BuiltIn;
    let (load_data, data) = time(|| earth.heights().expect("the height map"));
    let (load_refined, refined) = time(|| earth.refined_heights().expect("the refined heights"));
    println!(
        "load: height map {load_data:.3} s, refined heights (map, mask, amplitude) {load_refined:.3} s"
    );
    let data_lod = LodSettings::for_spacing(radius, data.sample_spacing_rad());
    let refined_lod = LodSettings::for_spacing(radius, refined.sample_spacing_rad());
    let plain = TerrainSurface::new(data, radius);
    let fine = TerrainSurface::new(refined, radius);
    let up = direction(46.0f64.to_radians(), 7.8f64.to_radians());
    let view = LodView::new(up * (radius + 5600.0), 720.0, 60f64.to_radians());
    let select = |lod: &LodSettings, surface: &dyn Fn(glam::DVec3) -> f64| {
        select_chunks(lod, &view, surface).expect("valid settings")
    };
    let chunks: Vec<SelectedChunk> = select(&refined_lod, &|d| fine.elevation_m(d));
    let step = chunks.len().div_ceil(MESHED);
    let sample: Vec<&SelectedChunk> = chunks.iter().step_by(step).collect();
    println!(
        "{} chunks chosen on the refined heights (finest level {}), {} on the data's (finest level {}); meshing {} of them, {} cells each",
        chunks.len(),
        refined_lod.max_level,
        select(&data_lod, &|d| plain.elevation_m(d)).len(),
        data_lod.max_level,
        sample.len(),
        refined_lod.cells
    );
    let (mut mesh_plain, mut mesh_fine, mut select_plain, mut select_fine, mut map_fine) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    // Each chunk's grid points from -1 to cells + 1, which its mesh holds already.
    let cells = refined_lod.cells;
    let side = i64::from(cells) + 3;
    let grids: Vec<Vec<glam::DVec3>> = sample
        .iter()
        .map(|c| {
            (-1..=i64::from(cells) + 1)
                .flat_map(|j| (-1..=i64::from(cells) + 1).map(move |i| (i, j)))
                .map(|(i, j)| {
                    let (u, v) = c.key.vertex_uv(cells, i, j);
                    fine.position_m(face_direction(c.key.face, u, v))
                })
                .collect()
        })
        .collect();
    let mut parent_maps = Vec::new();
    for _ in 0..ROUNDS {
        let build = |surface: &dyn Fn(&SelectedChunk) -> ChunkMesh| {
            time(|| {
                sample
                    .iter()
                    .map(|c| surface(c).positions.len())
                    .sum::<usize>()
            })
            .0
        };
        mesh_plain.push(build(&|c| ChunkMesh::build(&plain, c, refined_lod.cells)));
        mesh_fine.push(build(&|c| ChunkMesh::build(&fine, c, refined_lod.cells)));
        let maps = |c: &&SelectedChunk| NormalMap::build(&fine, c.key, refined_lod.cells);
        map_fine.push(time(|| sample.iter().map(|c| maps(c).normals.len()).sum::<usize>()).0);
        let parent_map = |c: &SelectedChunk, grid: &[glam::DVec3]| {
            ParentNormalMap::build(c.key, cells, |i, j| grid[((j + 1) * side + i + 1) as usize])
        };
        let parents = || {
            sample
                .iter()
                .zip(&grids)
                .map(|(c, g)| parent_map(c, g).map.normals.len())
                .sum::<usize>()
        };
        parent_maps.push(time(parents).0);
        select_plain.push(time(|| select(&refined_lod, &|d| plain.elevation_m(d))).0);
        select_fine.push(time(|| select(&refined_lod, &|d| fine.elevation_m(d))).0);
    }
    let per_chunk = |v: Vec<f64>| median(v) / sample.len() as f64 * 1e3;
    let (mp, mf) = (per_chunk(mesh_plain), per_chunk(mesh_fine));
    println!("chunk mesh, data's heights: {mp:.3} ms per chunk");
    println!(
        "chunk mesh, refined heights: {mf:.3} ms per chunk (x{:.1})",
        mf / mp
    );
    let map = per_chunk(map_fine);
    println!(
        "the normal map alone, every corner evaluated: {map:.3} ms per chunk ({:.0} % of the refined mesh with its map)",
        100.0 * map / mf
    );
    let parent = per_chunk(parent_maps);
    println!(
        "the parent's map over a chunk from the mesh's grid: {parent:.4} ms per chunk ({:.1} % of the refined mesh with its maps)",
        100.0 * parent / mf
    );
    let (sp, sf) = (median(select_plain) * 1e3, median(select_fine) * 1e3);
    println!("select_chunks, data's heights: {sp:.1} ms");
    println!(
        "select_chunks, refined heights: {sf:.1} ms (x{:.1})",
        sf / sp
    );
}
