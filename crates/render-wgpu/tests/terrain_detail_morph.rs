//! The normal map's morph across a level switch (`terrain/detail_morph.rs`, docs/terrain.md
//! "No popping"): with the parent chunk exactly at its switch distance, its four
//! children, their vertices, mesh normals and normal maps morphed, shade every point as
//! the parent does there (the interpolated mesh normal, the map's sample and the detail's
//! fade, `normal_map::shading_normal`), while unmorphed they shade it otherwise.

use glam::DVec3;
use render_wgpu::terrain::chunk_key::ChunkKey;
use render_wgpu::terrain::cube_sphere::Face;
use render_wgpu::terrain::detail_morph::{detail_factor, morphed_detail, morphed_texel_m};
use render_wgpu::terrain::geomorph::{MorphEnds, switch_distance_m};
use render_wgpu::terrain::lod::{LodSettings, LodView, SelectedChunk};
use render_wgpu::terrain::normal_map::{detail_weight, shading_normal, texel_size_m};
use render_wgpu::terrain::{ChunkMesh, HeightField, TerrainSurface};

const R: f64 = 6.36e6;

/// Relief from 40 km down to bumps about 6 km wide, under parent cells of 9.8 km (texels
/// of 4.9 km) and child cells of 4.9 km (texels of 2.4 km): each level's map differs.
struct Bumps;

impl HeightField for Bumps {
    fn height_m(&self, d: DVec3) -> f64 {
        600.0 * (1000.0 * d.x).sin() * (900.0 * d.y).cos()
            + 250.0 * (6500.0 * d.y).sin() * (7000.0 * d.z).cos()
            + 120.0 * (9000.0 * d.x + 3.0 * d.z).sin()
    }
    fn max_abs_height_m(&self) -> f64 {
        970.0
    }
    fn sample_spacing_rad(&self) -> f64 {
        1e-5
    }
}

const CELLS: u32 = 8;

/// Grid coordinates of vertex `k` of a chunk.
fn grid(k: u32) -> DVec3 {
    DVec3::new(f64::from(k % (CELLS + 1)), f64::from(k / (CELLS + 1)), 0.0)
}

/// The child's shading normal and point at barycentric weights `b` of triangle `t`, for
/// a camera at `camera` with `pixels_per_radian`, morphed or not (the terrain shader's
/// twin: vertex factors, normals and map factor interpolated).
fn child_shading(
    mesh: &ChunkMesh,
    t: &[u32],
    b: [f64; 3],
    camera: DVec3,
    pixels_per_radian: f64,
    ends: Option<MorphEnds>,
) -> (DVec3, DVec3) {
    let none = [false; 4];
    let lerp = |f: &dyn Fn(u32) -> DVec3| (0..3).map(|k| f(t[k]) * b[k]).sum::<DVec3>();
    let point = lerp(&|k| {
        let m = ends.map_or(0.0, |e| mesh.morph_factor(k, none, camera, e));
        mesh.morphed_position_m(k, m)
    });
    let normal = lerp(&|k| {
        let m = ends.map_or(0.0, |e| mesh.normal_morph_factor(k, none, camera, e));
        mesh.morphed_normal(k, m)
    });
    let m = lerp(&|k| {
        let distance = (mesh.world_position_m(k) - camera).length();
        DVec3::splat(ends.map_or(0.0, |e| detail_factor(distance, e)))
    })
    .x;
    let uv = lerp(&grid) / f64::from(CELLS);
    let map = morphed_detail(
        mesh.normal_map.sample(uv.x, uv.y),
        mesh.parent_map.sample(uv.x, uv.y),
        m,
    );
    let texel = morphed_texel_m(texel_size_m(R, CELLS, mesh.key.level), m);
    let weight = detail_weight(texel, pixels_per_radian, (point - camera).length());
    (shading_normal(normal, map, weight), point)
}

/// The parent's own shading normal and point at grid coordinates `g` of its grid.
fn parent_shading(
    parent: &ChunkMesh,
    g: DVec3,
    camera: DVec3,
    pixels_per_radian: f64,
) -> (DVec3, DVec3) {
    // The parent's triangle holding g, and g's weights in it.
    let (t, b) = parent
        .indices
        .chunks(3)
        .find_map(|t| {
            let [a, b, c] = [grid(t[0]), grid(t[1]), grid(t[2])];
            let area = (b - a).cross(c - a).z;
            let u = (g - a).cross(c - a).z / area;
            let v = (b - a).cross(g - a).z / area;
            let w = [1.0 - u - v, u, v];
            w.iter().all(|&w| w >= -1e-12).then_some((t, w))
        })
        .expect("a point in the parent");
    let lerp = |f: &dyn Fn(u32) -> DVec3| (0..3).map(|k| f(t[k]) * b[k]).sum::<DVec3>();
    let point = lerp(&|k| parent.world_position_m(k));
    let normal = lerp(&|k| glam::Vec3::from_array(parent.normals[k as usize]).as_dvec3());
    let uv = g / f64::from(CELLS);
    let map = parent.normal_map.sample(uv.x, uv.y);
    let texel = texel_size_m(R, CELLS, parent.key.level);
    let weight = detail_weight(texel, pixels_per_radian, (point - camera).length());
    (shading_normal(normal, map, weight), point)
}

/// At the parent's switch distance (its projected cell error at the limit) the children,
/// morphed, shade each point as the parent: within 1e-5, where the mesh normals' morph
/// interpolates normalised targets across the child's triangles (the map's texels are
/// the parent's bits); their own shading departs from the parent's by more than 1e-2.
/// For a small viewport, where the parent's texels cover under 2 pixels and the detail
/// fades towards the mesh normal, and a larger one, where the map alone shades.
#[test]
fn at_the_switch_distance_children_are_shaded_as_their_parent() {
    let surface = TerrainSurface::new(Bumps, R);
    let settings = LodSettings {
        cells: CELLS,
        ..LodSettings::new(R)
    };
    let mut parent = ChunkKey::root(Face(1));
    for _ in 0..7 {
        parent = parent.children()[1];
    }
    let elevation = |d: DVec3| surface.elevation_m(d);
    let (centre, radius) = settings.bounding_sphere(parent, &elevation);
    let whole = |key| SelectedChunk {
        key,
        coarser: [false; 4],
    };
    let parent_mesh = ChunkMesh::build(&surface, &whole(parent), CELLS);
    let children = parent
        .children()
        .map(|key| ChunkMesh::build(&surface, &whole(key), CELLS));
    let weights = [
        [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
        [0.6, 0.3, 0.1],
        [0.1, 0.1, 0.8],
        [0.45, 0.1, 0.45],
        [0.0, 0.5, 0.5],
    ];
    for height_px in [40.0, 360.0] {
        let pixels = LodView::new(DVec3::ZERO, height_px, 1.0).pixels_per_radian;
        let view = LodView {
            camera_m: DVec3::ZERO,
            pixels_per_radian: pixels,
        };
        let switch = switch_distance_m(&settings, &view, parent.level);
        let camera = centre + centre.normalize() * (radius + switch);
        let (mut worst, mut unmorphed_worst, mut worst_point) = (0.0f64, 0.0f64, 0.0f64);
        let (mut faded, mut weight_range) = (0, (f64::INFINITY, 0.0f64));
        for mesh in &children {
            let ends = MorphEnds::of_level(&settings, &view, mesh.key.level);
            for t in mesh.indices.chunks(3) {
                for b in weights {
                    let (morphed, point) = child_shading(mesh, t, b, camera, pixels, Some(ends));
                    let (own, _) = child_shading(mesh, t, b, camera, pixels, None);
                    // The point in the parent's grid.
                    let g = (0..3).map(|k| grid(t[k]) * b[k]).sum::<DVec3>();
                    let odd = DVec3::new(f64::from(mesh.key.x % 2), f64::from(mesh.key.y % 2), 0.0);
                    let g = (odd * f64::from(CELLS) + g) * 0.5;
                    let (expected, at) = parent_shading(&parent_mesh, g, camera, pixels);
                    worst = worst.max((morphed - expected).length());
                    unmorphed_worst = unmorphed_worst.max((own - expected).length());
                    worst_point = worst_point.max((point - at).length());
                    let texel = texel_size_m(R, CELLS, parent.level);
                    let weight = detail_weight(texel, pixels, (at - camera).length());
                    faded += usize::from(weight < 1.0);
                    weight_range = (weight_range.0.min(weight), weight_range.1.max(weight));
                }
            }
        }
        eprintln!(
            "{height_px} px: morphed within {worst:.1e} of the parent, unmorphed up to \
             {unmorphed_worst:.1e}; points within {worst_point:.1e} m; {faded} points faded, \
             the parent's detail weight {:.2} to {:.2}",
            weight_range.0, weight_range.1
        );
        assert!(worst_point < 0.05, "{worst_point}");
        assert!(worst < 1e-5, "{worst}");
        assert!(unmorphed_worst > 1e-2, "{unmorphed_worst}");
        assert_eq!(faded > 0, height_px < 100.0, "{faded}");
    }
}
