//! The normal map's detail morphed across a level switch: each chunk also carries its
//! parent's normal map over its own area, and the terrain shader blends the chunk's map
//! towards it with the chunk's morph factor, as the vertices and their normals blend
//! towards the parent's (`geomorph.rs`; the vertex morph of Strugar 2009 carried to the
//! shading), so that at the switch a child is shaded as its parent (docs/terrain.md,
//! "No popping").
//!
//! The parent's texels over a chunk: the parent's map has [`TEXELS_PER_CELL`] texels per
//! parent cell, a parent cell is two of the chunk's cells, so a parent texel is one of the
//! chunk's mesh cells, and its corners are the chunk's mesh vertices. Its normal is the
//! parent's rule, `(p11 - p00) x (p01 - p10)` over that cell, from the mesh's own grid,
//! which reaches two cells beyond the chunk: no height is evaluated for it. The map holds
//! `cells + 2` texels along a side, one beyond the chunk on every side, so that the
//! bilinear sample within half a texel of the chunk's edge reads the parent's texel
//! across it as the parent's sampler does; where the chunk's edge is the parent's own, the
//! parent's sampler clamps, and the texels beyond repeat the edge's.
//!
//! The shader's twin: with `m` the chunk's own morph factor ([`detail_factor`], the
//! vertex's, interpolated), the map's normal is [`morphed_detail`] of the two samples and
//! the texel's side in [`super::normal_map::detail_weight`] is [`morphed_texel_m`], the
//! parent's at `m = 1`.

use glam::DVec3;

use super::chunk_key::ChunkKey;
use super::geomorph::{MorphEnds, morph_factor};
use super::normal_map::{NormalMap, TEXELS_PER_CELL};

// A parent texel is one of the chunk's cells.
const _: () = assert!(TEXELS_PER_CELL == 2);

/// The parent's normal map over a chunk's area and one texel beyond it: texel (a, b)
/// covers the chunk's mesh cell (a - 1, b - 1).
#[derive(Clone, Debug, PartialEq)]
pub struct ParentNormalMap {
    /// `cells + 2` texels along a side.
    pub map: NormalMap,
}

impl ParentNormalMap {
    /// The parent's map over chunk `key` of `cells` cells, from `grid(i, j)`, the chunk's
    /// surface at its grid point (i, j) (planet-centred, m) for i, j in -1 ..= cells + 1.
    pub fn build(key: ChunkKey, cells: u32, grid: impl Fn(i64, i64) -> DVec3) -> ParentNormalMap {
        let texels = cells + 2;
        let last = i64::from(cells) + 1;
        // Beyond an edge that is the parent's own, the edge's texel again.
        let clamp = |k: i64, first_child: bool| {
            if first_child {
                k.max(1)
            } else {
                k.min(last - 1)
            }
        };
        let (first_u, first_v) = (key.x.is_multiple_of(2), key.y.is_multiple_of(2));
        let normals = (0..=last)
            .flat_map(|b| (0..=last).map(move |a| (a, b)))
            .map(|(a, b)| {
                let (i, j) = (clamp(a, first_u) - 1, clamp(b, first_v) - 1);
                let d1 = grid(i + 1, j + 1) - grid(i, j);
                let d2 = grid(i, j + 1) - grid(i + 1, j);
                d1.cross(d2).normalize().as_vec3().to_array()
            })
            .collect();
        ParentNormalMap {
            map: NormalMap { texels, normals },
        }
    }

    /// The bilinear sample at the chunk's coordinates `(s, t)` in [0, 1]² (the parent's
    /// own sample there), before normalising: the shader's `parent_uv` and sampler.
    pub fn sample(&self, s: f64, t: f64) -> DVec3 {
        let n = f64::from(self.map.texels);
        let inner = |s: f64| (s * (n - 2.0) + 1.0) / n;
        self.map.sample(inner(s), inner(t))
    }
}

/// The morph factor of a chunk's map at a vertex `distance_m` from the camera: the
/// chunk's own (`geomorph::morph_factor` with the end `ends.own_m`) at every vertex,
/// as a vertex that moves with the chunk takes it; 1 where the parent's switch is reached.
pub fn detail_factor(distance_m: f64, ends: MorphEnds) -> f64 {
    morph_factor(distance_m, ends.own_m)
}

/// The map's normal blended from the chunk's own sample `own` towards the parent's
/// `parent` by `m`, unit: `normalize(mix(normalize(own), normalize(parent), m))`.
pub fn morphed_detail(own: DVec3, parent: DVec3, m: f64) -> DVec3 {
    let own = own.normalize();
    (own + (parent.normalize() - own) * m).normalize()
}

/// The texel's side for the detail's fade at morph factor `m`, m: the chunk's texel
/// `texel_m` at `m = 0`, the parent's (twice as wide) at `m = 1`.
pub fn morphed_texel_m(texel_m: f64, m: f64) -> f64 {
    texel_m * (1.0 + m)
}

#[cfg(test)]
mod tests {
    use super::super::cube_sphere::{Face, direction};
    use super::super::height_field::HeightField;
    use super::super::surface::TerrainSurface;
    use super::*;

    const R: f64 = 6.36e6;

    /// Bumps a few kilometres wide, all above the sea.
    struct Bumps;

    impl HeightField for Bumps {
        fn height_m(&self, d: DVec3) -> f64 {
            1500.0
                + 900.0 * (3000.0 * d.x).sin() * (2100.0 * d.y).cos()
                + 400.0 * (5000.0 * d.z).sin()
        }
        fn max_abs_height_m(&self) -> f64 {
            2800.0
        }
        fn sample_spacing_rad(&self) -> f64 {
            1e-4
        }
    }

    fn grid_of(key: ChunkKey, cells: u32) -> impl Fn(i64, i64) -> DVec3 {
        let surface = TerrainSurface::new(Bumps, R);
        move |i, j| {
            let (u, v) = key.vertex_uv(cells, i, j);
            surface.position_m(direction(key.face, u, v))
        }
    }

    /// The parent's map over each child equals the parent's own map's texels there, bit
    /// for bit (the same corners, the same rule), and beyond the parent's edges repeats
    /// the edge's texels.
    #[test]
    fn the_parents_texels_over_a_child_are_the_parents_own() {
        let cells = 8;
        let mut parent = ChunkKey::root(Face(3));
        for _ in 0..6 {
            parent = parent.children()[2];
        }
        let own = NormalMap::build(&TerrainSurface::new(Bumps, R), parent, cells);
        let side = TEXELS_PER_CELL * cells;
        for child in parent.children() {
            let over = ParentNormalMap::build(child, cells, grid_of(child, cells));
            assert_eq!(over.map.texels, cells + 2);
            let n = (cells + 2) as usize;
            for b in 0..n {
                for a in 0..n {
                    // The parent's texel, clamped to its edges.
                    let in_parent = |k: usize, odd: u32| {
                        (k as i64 - 1 + i64::from(odd * cells)).clamp(0, i64::from(side) - 1)
                    };
                    let (pa, pb) = (in_parent(a, child.x % 2), in_parent(b, child.y % 2));
                    let expected = own.normals[pb as usize * side as usize + pa as usize];
                    assert_eq!(
                        over.map.normals[b * n + a],
                        expected,
                        "{child:?} ({a}, {b})"
                    );
                }
            }
        }
    }

    /// The chunk's coordinate maps onto the parent's: the sample at the chunk's texel
    /// centres is that texel's normal, and the morph's ends are the two maps and texels.
    #[test]
    fn samples_and_blends_reach_both_ends() {
        let cells = 4;
        let key = ChunkKey::root(Face(0)).children()[1];
        let over = ParentNormalMap::build(key, cells, grid_of(key, cells));
        for b in 0..cells {
            for a in 0..cells {
                let centre = |k: u32| (f64::from(k) + 0.5) / f64::from(cells);
                let texel = over.map.normals[((b + 1) * (cells + 2) + a + 1) as usize];
                let expected = glam::Vec3::from_array(texel).as_dvec3();
                assert!((over.sample(centre(a), centre(b)) - expected).length() < 1e-12);
            }
        }
        let (own, parent) = (DVec3::Z * 2.0, DVec3::X);
        assert_eq!(morphed_detail(own, parent, 0.0), DVec3::Z);
        assert_eq!(morphed_detail(own, parent, 1.0), DVec3::X);
        assert_eq!(morphed_texel_m(3.0, 0.0), 3.0);
        assert_eq!(morphed_texel_m(3.0, 1.0), 6.0);
        let ends = MorphEnds {
            own_m: 1000.0,
            edge_m: 2000.0,
        };
        assert_eq!(detail_factor(500.0, ends), 0.0);
        assert_eq!(detail_factor(1000.0, ends), 1.0);
        assert!((detail_factor(750.0, ends) - 0.5).abs() < 1e-12);
    }
}
