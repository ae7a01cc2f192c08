//! Geomorphing: a chunk's vertices blend from its parent's surface to their own over the
//! band of camera distance before the level-of-detail switch, so that a split or a merge
//! moves no vertex (the vertex morph of Strugar 2009, "Continuous Distance-Dependent Level
//! of Detail for Rendering Heightmaps", here on the quadtree's screen-space switch of
//! `lod.rs`). The vertex shader (`shaders/terrain/terrain.wgsl`, `morphed`) is the twin of
//! [`morph_factor`] and [`morph_role`] applied to the mesh's targets.
//!
//! A chunk of level `L` exists where its parent's projected error exceeds the limit, that
//! is where the parent's bounding sphere is nearer than the parent's switch distance
//! `D(L-1) = e(L-1) P / max_error_px` ([`switch_distance_m`]). A vertex at distance `d` from
//! the camera takes the morph factor `m = clamp((d / D(L-1) - s) / (1 - s), 0, 1)` with
//! `s` = [`MORPH_START`]: its own position where `d <= s D(L-1)` (where its own children
//! may begin), the parent's surface where `d >= D(L-1)`, and is drawn at `p + m (t - p)`,
//! `t` its target on the parent's surface. At the switch every vertex of the parent's
//! sphere is at least `D(L-1)` away, so the children draw exactly the parent's triangles.
//!
//! Targets, on the triangulation of `stitching.rs`: an even-even vertex is the parent's
//! own; a vertex odd along one grid direction moves to the midpoint of its two even
//! neighbours (the parent's edge), an odd-odd one to the midpoint of the parent cell's
//! diagonal. Fully morphed, the eight triangles around an odd-odd vertex lie in the
//! parent cell's two triangles.
//!
//! Edges bordering a coarser chunk: the stitched edge runs through this chunk's even
//! vertices, which are the coarser chunk's vertices, and the coarser chunk morphs them
//! towards its own parent with its own factor (end `D(L-2)`). On such an edge an even
//! vertex therefore takes the coarser chunk's target, the midpoint of its neighbours two
//! apart where it is odd in the coarser chunk, and factor ([`MorphRole::Edge`]): the
//! shared vertices stay equal, bit for bit in f64. Since an even vertex's own target is
//! itself, its slot in the mesh holds that edge target. Cells are a multiple of 4, so a
//! chunk's corners are its grandparent's vertices and never move.
//!
//! Normals morph with their vertices ([`morph_normal`]): a vertex's normal blends, by the
//! same factor, to the parent's normal at its target, which is the parent's vertex normal
//! for an even-even vertex and the normalised mean of the two parent vertices' normals
//! whose midpoint is its target otherwise (the parent's triangles interpolate normals
//! linearly, and the shader normalises). At the switch a child's mesh normals are the
//! parent's as its triangles shade them. The parent's own vertices do not move, but their
//! normals blend with the chunk's own factor ([`normal_factor`]); on an edge bordering a
//! coarser chunk an even vertex's normal blends, with the neighbour's factor, to the
//! parent's normal at the vertex ([`normal_pair`]): normals there stay each chunk's own.

use glam::DVec3;

use super::chunk_key::{ChunkKey, Edge};
use super::height_field::HeightField;
use super::lod::{LodSettings, LodView, SelectedChunk};
use super::surface::TerrainSurface;

/// The fraction of the switch distance where the morph begins.
pub const MORPH_START: f64 = 0.5;

/// The camera distance below which a chunk of `level` is split, metres: where its
/// projected geometric error reaches `max_error_px`.
pub fn switch_distance_m(settings: &LodSettings, view: &LodView, level: u8) -> f64 {
    settings.geometric_error_m(level) * view.pixels_per_radian / settings.max_error_px
}

/// Where a chunk's morphs end, metres (0: no morph, at the root levels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MorphEnds {
    /// The chunk's own morph towards its parent: the parent's switch distance.
    pub own_m: f64,
    /// The morph of a coarser neighbour towards its parent, on stitched edges.
    pub edge_m: f64,
}

impl MorphEnds {
    /// The ends for a chunk of `level`.
    pub fn of_level(settings: &LodSettings, view: &LodView, level: u8) -> MorphEnds {
        let end = |up: u8| {
            level
                .checked_sub(up)
                .map_or(0.0, |l| switch_distance_m(settings, view, l))
        };
        MorphEnds {
            own_m: end(1),
            edge_m: end(2),
        }
    }
}

/// The morph factor of a vertex `distance_m` from the camera, for a morph ending at
/// `end_m` (0: none).
pub fn morph_factor(distance_m: f64, end_m: f64) -> f64 {
    if end_m <= 0.0 {
        return 0.0;
    }
    ((distance_m / end_m - MORPH_START) / (1.0 - MORPH_START)).clamp(0.0, 1.0)
}

/// How a vertex morphs in a chunk drawn with the coarser edges `coarser`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MorphRole {
    /// The parent's vertex: never moves (its normal morphs with the chunk's own factor).
    Fixed,
    /// Towards its target with the chunk's own factor.
    Own,
    /// Towards its target with the coarser neighbour's factor.
    Edge,
}

/// Whether vertex (i, j) of a chunk of `cells` cells lies on `edge`.
fn on_edge(cells: u32, edge: Edge, i: u32, j: u32) -> bool {
    match edge {
        Edge::UMin => i == 0,
        Edge::UMax => i == cells,
        Edge::VMin => j == 0,
        Edge::VMax => j == cells,
    }
}

/// The role of vertex (i, j) (see the module documentation).
pub fn morph_role(cells: u32, coarser: [bool; 4], i: u32, j: u32) -> MorphRole {
    if i % 2 == 1 || j % 2 == 1 {
        MorphRole::Own
    } else if Edge::ALL
        .iter()
        .any(|&e| coarser[e as usize] && on_edge(cells, e, i, j))
    {
        MorphRole::Edge
    } else {
        MorphRole::Fixed
    }
}

/// The two grid points whose midpoint is the target of vertex (i, j) of chunk `key`
/// (both the vertex itself where it has none).
pub fn target_pair(key: ChunkKey, cells: u32, i: u32, j: u32) -> [(u32, u32); 2] {
    match (i % 2, j % 2) {
        (1, 0) => [(i - 1, j), (i + 1, j)],
        (0, 1) => [(i, j - 1), (i, j + 1)],
        (1, 1) => {
            // The parent cell's index in the parent's grid gives its diagonal.
            let cell_u = ((key.x & 1) * cells + i - 1) / 2;
            let cell_v = ((key.y & 1) * cells + j - 1) / 2;
            if (cell_u + cell_v).is_multiple_of(2) {
                [(i - 1, j - 1), (i + 1, j + 1)]
            } else {
                [(i + 1, j - 1), (i - 1, j + 1)]
            }
        }
        _ => {
            // Even-even: on an edge, the coarser neighbour's target where the vertex is
            // odd there (index 2 mod 4 along the edge).
            let along_u = (j == 0 || j == cells) && i % 4 == 2;
            let along_v = (i == 0 || i == cells) && j % 4 == 2;
            if along_u {
                [(i - 2, j), (i + 2, j)]
            } else if along_v {
                [(i, j - 2), (i, j + 2)]
            } else {
                [(i, j), (i, j)]
            }
        }
    }
}

/// The morph factor of a vertex in the role `role`, `distance_m` from the camera, in a
/// chunk with the morph ends `ends`.
pub fn vertex_factor(role: MorphRole, distance_m: f64, ends: MorphEnds) -> f64 {
    match role {
        MorphRole::Fixed => 0.0,
        MorphRole::Own => morph_factor(distance_m, ends.own_m),
        MorphRole::Edge => morph_factor(distance_m, ends.edge_m),
    }
}

/// A vertex `position_m` with target `target_m` in the role `role`, drawn for a camera at
/// `camera_m` with the chunk's morph ends: `p + m (t - p)`.
pub fn morph(
    position_m: DVec3,
    target_m: DVec3,
    role: MorphRole,
    camera_m: DVec3,
    ends: MorphEnds,
) -> DVec3 {
    let m = vertex_factor(role, (position_m - camera_m).length(), ends);
    position_m + (target_m - position_m) * m
}

/// The morph factor of the normal of a vertex in the role `role`: its position's, but
/// the chunk's own for the parent's vertices, which move no further than their normals.
pub fn normal_factor(role: MorphRole, distance_m: f64, ends: MorphEnds) -> f64 {
    match role {
        MorphRole::Fixed => morph_factor(distance_m, ends.own_m),
        _ => vertex_factor(role, distance_m, ends),
    }
}

/// The grid points whose parent normals' normalised mean is the morph target's normal of
/// vertex (i, j): [`target_pair`] for a vertex odd in either direction, the vertex itself
/// for an even-even one (on an edge bordering a coarser chunk too, where its position
/// moves to the edge target: the mesh serves every pattern of coarser edges).
pub fn normal_pair(key: ChunkKey, cells: u32, i: u32, j: u32) -> [(u32, u32); 2] {
    if i % 2 == 1 || j % 2 == 1 {
        target_pair(key, cells, i, j)
    } else {
        [(i, j), (i, j)]
    }
}

/// A vertex's unit normal `normal` blended by the morph factor `factor` towards its
/// target's `target`: `normalize(n + m (t - n))`, the vertex shader's
/// `normalize(mix(n, t, m))`.
pub fn morph_normal(normal: DVec3, target: DVec3, factor: f64) -> DVec3 {
    (normal + (target - normal) * factor).normalize()
}

/// The drawn position of vertex (i, j) of `chunk` on `surface`, all in f64: the
/// specification the meshes' f32 targets round.
pub fn morphed_vertex_m<H: HeightField>(
    surface: &TerrainSurface<H>,
    chunk: &SelectedChunk,
    cells: u32,
    (i, j): (u32, u32),
    camera_m: DVec3,
    ends: MorphEnds,
) -> DVec3 {
    let at = |(i, j): (u32, u32)| {
        let (u, v) = chunk.key.vertex_uv(cells, i as i64, j as i64);
        surface.position_m(super::cube_sphere::direction(chunk.key.face, u, v))
    };
    let [a, b] = target_pair(chunk.key, cells, i, j);
    let role = morph_role(cells, chunk.coarser, i, j);
    morph(at((i, j)), (at(a) + at(b)) * 0.5, role, camera_m, ends)
}

#[cfg(test)]
mod tests {
    use super::super::chunk_key::ChunkKey;
    use super::super::cube_sphere::{Face, direction};
    use super::super::lod::screen_error_px;
    use super::super::stitching::stitched_indices;
    use super::*;

    const R: f64 = 6.36e6;

    /// Smooth relief of a few kilometres.
    struct Swell;

    impl HeightField for Swell {
        fn height_m(&self, d: DVec3) -> f64 {
            2500.0 * (9.0 * d.x).sin() * (6.0 * d.y).cos() + 800.0 * (13.0 * d.z).sin()
        }
        fn max_abs_height_m(&self) -> f64 {
            3300.0
        }
        fn sample_spacing_rad(&self) -> f64 {
            1e-4
        }
    }

    fn vertex_direction(key: ChunkKey, cells: u32, i: u32, j: u32) -> DVec3 {
        let (u, v) = key.vertex_uv(cells, i as i64, j as i64);
        direction(key.face, u, v)
    }

    /// Where the ray from the planet's centre through `p` meets triangle `t`, if it does.
    fn through_triangle(p: DVec3, t: [DVec3; 3]) -> Option<DVec3> {
        let dir = p.normalize();
        let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
        let h = dir.cross(e2);
        let det = e1.dot(h);
        let s = -t[0];
        let u = s.dot(h) / det;
        let q = s.cross(e1);
        let v = dir.dot(q) / det;
        let eps = 1e-9;
        (u >= -eps && v >= -eps && u + v <= 1.0 + eps).then(|| dir * (e2.dot(q) / det))
    }

    /// A camera with the parent chunk exactly at its switch distance: every vertex of its
    /// four children, morphed, lies on the parent's triangles (within 1 cm), though
    /// unmorphed they depart from them by metres; with the camera at the parent's sphere
    /// they are their own.
    #[test]
    fn at_the_switch_distance_children_lie_on_their_parent() {
        let surface = TerrainSurface::new(Swell, R);
        let cells = 8;
        let settings = LodSettings {
            cells,
            ..LodSettings::new(R)
        };
        let mut parent = ChunkKey::root(Face(0));
        for _ in 0..7 {
            parent = parent.children()[2];
        }
        let elevation = |d: DVec3| surface.elevation_m(d);
        let (centre, radius) = settings.bounding_sphere(parent, &elevation);
        let pixels = LodView::new(DVec3::ZERO, 360.0, 1.0);
        let switch = switch_distance_m(&settings, &pixels, parent.level);
        let at = |distance: f64| LodView {
            camera_m: centre + centre.normalize() * (radius + distance),
            ..pixels
        };
        let view = at(switch);
        let error = screen_error_px(&settings, &view, parent, &elevation);
        assert!(
            (error / settings.max_error_px - 1.0).abs() < 1e-9,
            "{error}"
        );
        let corner = |i, j| surface.position_m(vertex_direction(parent, cells, i, j));
        let triangles: Vec<[DVec3; 3]> = stitched_indices(cells, [false; 4])
            .chunks(3)
            .map(|t| [0, 1, 2].map(|k| corner(t[k] % (cells + 1), t[k] / (cells + 1))))
            .collect();
        let off_parent = |p: DVec3| {
            triangles
                .iter()
                .filter_map(|&t| through_triangle(p, t))
                .map(|hit| (hit - p).length())
                .fold(f64::INFINITY, f64::min)
        };
        let (mut worst, mut unmorphed_worst) = (0.0f64, 0.0f64);
        for key in parent.children() {
            let chunk = SelectedChunk {
                key,
                coarser: [false; 4],
            };
            let ends = MorphEnds::of_level(&settings, &view, key.level);
            assert_eq!(ends.own_m, switch);
            for j in 0..=cells {
                for i in 0..=cells {
                    let own = surface.position_m(vertex_direction(key, cells, i, j));
                    assert!((own - view.camera_m).length() >= switch);
                    let p = morphed_vertex_m(&surface, &chunk, cells, (i, j), view.camera_m, ends);
                    worst = worst.max(off_parent(p));
                    unmorphed_worst = unmorphed_worst.max(off_parent(own));
                    let near = at(0.0).camera_m;
                    let q = morphed_vertex_m(&surface, &chunk, cells, (i, j), near, ends);
                    assert_eq!(q, own);
                }
            }
        }
        assert!(worst < 0.01, "{worst} m off the parent");
        assert!(unmorphed_worst > 1.0, "{unmorphed_worst}");
    }

    /// The factor runs from 0 at MORPH_START of the end to 1 at the end, and is 0 without
    /// a parent.
    #[test]
    fn the_morph_factor_spans_the_band_before_the_switch() {
        assert_eq!(morph_factor(400.0, 1000.0), 0.0);
        assert_eq!(morph_factor(MORPH_START * 1000.0, 1000.0), 0.0);
        assert!((morph_factor(750.0, 1000.0) - 0.5).abs() < 1e-12);
        assert_eq!(morph_factor(1000.0, 1000.0), 1.0);
        assert_eq!(morph_factor(5000.0, 1000.0), 1.0);
        assert_eq!(morph_factor(5000.0, 0.0), 0.0);
    }
}
