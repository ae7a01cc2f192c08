//! A chunk's normal map: the refined relief's normals at [`TEXELS_PER_CELL`] texels per
//! mesh cell along each side, so a chunk is shaded by relief finer than its mesh
//! (docs/terrain.md, "Normal maps").
//!
//! Texel (a, b) of a chunk with `T = TEXELS_PER_CELL x cells` texels along a side covers
//! the square between the chunk's grid lines a and a + 1 along u and b and b + 1 along v
//! of the grid of `T` cells (`ChunkKey::vertex_uv(T, ..)`); its normal is the cross
//! product of the square's diagonals on the drawn surface, `(p11 - p00) x (p01 - p10)`,
//! which is twice the central differences' `along_u x along_v` at the square's centre,
//! the mesh normals' rule at the texel's spacing. The terrain shader samples the map
//! bilinearly, clamped to the chunk's edge, at the chunk coordinate `(i, j) / cells` of
//! the mesh vertices interpolated across each triangle ([`NormalMap::sample`] is its CPU
//! twin), and blends it with the mesh's interpolated normal by [`detail_weight`], so
//! that texels smaller than a pixel (far chunks, cover chunks, grazing distance) fade to
//! the mesh's normal instead of aliasing.

use glam::DVec3;

use super::chunk_key::ChunkKey;
use super::cube_sphere::direction;
use super::height_field::HeightField;
use super::surface::TerrainSurface;

/// Normal-map texels per mesh cell along each side.
pub const TEXELS_PER_CELL: u32 = 2;

/// The refined relief's normals over one chunk, row by row (v), texel (a, b) at
/// `b texels + a`.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalMap {
    /// Texels along a side.
    pub texels: u32,
    /// Outward unit normals, planet frame.
    pub normals: Vec<[f32; 3]>,
}

impl NormalMap {
    /// The map of chunk `key`, meshed with `cells` cells along a side, on `surface`,
    /// every texel corner evaluated.
    pub fn build<H: HeightField>(
        surface: &TerrainSurface<H>,
        key: ChunkKey,
        cells: u32,
    ) -> NormalMap {
        let texels = TEXELS_PER_CELL * cells;
        let per_cell = i64::from(TEXELS_PER_CELL);
        let vertex = |i: i64, j: i64| {
            let (u, v) = key.vertex_uv(texels, per_cell * i, per_cell * j);
            surface.position_m(direction(key.face, u, v))
        };
        NormalMap::build_sharing(surface, key, cells, vertex)
    }

    /// The same map, taking the texel corners that are mesh vertices, (2i, 2j), from
    /// `vertex(i, j)` (the mesh's positions, planet-centred, which are the same bits):
    /// a quarter of the corners are not evaluated again.
    pub fn build_sharing<H: HeightField>(
        surface: &TerrainSurface<H>,
        key: ChunkKey,
        cells: u32,
        vertex: impl Fn(i64, i64) -> DVec3,
    ) -> NormalMap {
        let texels = TEXELS_PER_CELL * cells;
        let side = texels as usize + 1;
        let per_cell = i64::from(TEXELS_PER_CELL);
        let corners: Vec<DVec3> = (0..=texels as i64)
            .flat_map(|b| (0..=texels as i64).map(move |a| (a, b)))
            .map(|(a, b)| {
                if a % per_cell == 0 && b % per_cell == 0 {
                    return vertex(a / per_cell, b / per_cell);
                }
                let (u, v) = key.vertex_uv(texels, a, b);
                surface.position_m(direction(key.face, u, v))
            })
            .collect();
        let corner = |a: usize, b: usize| corners[b * side + a];
        let normals = (0..texels as usize)
            .flat_map(|b| (0..texels as usize).map(move |a| (a, b)))
            .map(|(a, b)| {
                let d1 = corner(a + 1, b + 1) - corner(a, b);
                let d2 = corner(a, b + 1) - corner(a + 1, b);
                d1.cross(d2).normalize().as_vec3().to_array()
            })
            .collect();
        NormalMap { texels, normals }
    }

    /// The bilinear sample at chunk coordinates `(s, t)` in [0, 1]² (s along u), texel
    /// centres at `(a + 1/2) / texels`, clamped to the edge texels: the GPU sampler's
    /// twin, before normalising.
    pub fn sample(&self, s: f64, t: f64) -> DVec3 {
        let n = self.texels as usize;
        let texel = |a: usize, b: usize| {
            glam::Vec3::from_array(self.normals[b.min(n - 1) * n + a.min(n - 1)]).as_dvec3()
        };
        let (x, y) = (s * n as f64 - 0.5, t * n as f64 - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let clamp = |k: f64| k.max(0.0) as usize;
        let (a0, b0) = (clamp(x0), clamp(y0));
        let (a1, b1) = (clamp(x0 + 1.0), clamp(y0 + 1.0));
        let bottom = texel(a0, b0) * (1.0 - fx) + texel(a1, b0) * fx;
        let top = texel(a0, b1) * (1.0 - fx) + texel(a1, b1) * fx;
        bottom * (1.0 - fy) + top * fy
    }
}

/// A texel's side on the reference sphere at a chunk level, m: the mesh cell's
/// (`LodSettings::geometric_error_m`) over [`TEXELS_PER_CELL`].
pub fn texel_size_m(radius_m: f64, cells: u32, level: u8) -> f64 {
    radius_m * std::f64::consts::FRAC_PI_2
        / ((TEXELS_PER_CELL * cells) as f64 * (1u64 << level) as f64)
}

/// The normal map's weight against the mesh normal for a texel of `texel_m` seen
/// `distance_m` away at `pixels_per_radian`: 1 where a texel covers 2 pixels or more,
/// 0 where it covers 1 pixel or less (bilinear sampling of texels under a pixel would
/// alias), linear between.
pub fn detail_weight(texel_m: f64, pixels_per_radian: f64, distance_m: f64) -> f64 {
    (texel_m * pixels_per_radian / distance_m - 1.0).clamp(0.0, 1.0)
}

/// The shading normal: the mesh's interpolated normal and the map's sample, blended by
/// `weight` ([`detail_weight`]) and normalised.
pub fn shading_normal(mesh: DVec3, map: DVec3, weight: f64) -> DVec3 {
    let mesh = mesh.normalize();
    (mesh + (map.normalize() - mesh) * weight).normalize()
}

#[cfg(test)]
mod tests {
    use super::super::cube_sphere::Face;
    use super::*;

    const R: f64 = 6.36e6;

    /// Ripples 10 m high (5 m either side of 10 m, above the sea) and 200 m long along the planet's y axis (face 0's u): relief
    /// finer than the cells of a 32-cell chunk of level 10 (305 m) at face 0's centre.
    struct Ripples;

    impl HeightField for Ripples {
        fn height_m(&self, d: DVec3) -> f64 {
            10.0 + 5.0 * (d.y * R * std::f64::consts::TAU / 200.0).sin()
        }
        fn max_abs_height_m(&self) -> f64 {
            15.0
        }
        fn sample_spacing_rad(&self) -> f64 {
            1e-6
        }
    }

    struct Flat;

    impl HeightField for Flat {
        fn height_m(&self, _: DVec3) -> f64 {
            0.0
        }
        fn max_abs_height_m(&self) -> f64 {
            0.0
        }
        fn sample_spacing_rad(&self) -> f64 {
            1e-6
        }
    }

    fn key() -> ChunkKey {
        ChunkKey {
            face: Face(0),
            level: 10,
            x: 512,
            y: 512,
        }
    }

    #[test]
    fn a_flat_planet_has_the_radial_normal_at_every_texel_centre() {
        let surface = TerrainSurface::new(Flat, R);
        let map = NormalMap::build(&surface, key(), 32);
        assert_eq!(map.texels, 64);
        for b in 0..64u32 {
            for a in 0..64u32 {
                let (u0, v0) = key().vertex_uv(64, a as i64, b as i64);
                let (u1, v1) = key().vertex_uv(64, a as i64 + 1, b as i64 + 1);
                let centre = direction(Face(0), 0.5 * (u0 + u1), 0.5 * (v0 + v1));
                let n = map.sample((f64::from(a) + 0.5) / 64.0, (f64::from(b) + 0.5) / 64.0);
                assert!(n.normalize().dot(centre) > 1.0 - 1e-9, "texel ({a}, {b})");
            }
        }
    }

    #[test]
    fn the_map_follows_relief_finer_than_the_mesh_cells() {
        // Ripples of 200 m under cells of 305 m and texels of 152 m.
        let surface = TerrainSurface::new(Ripples, R);
        let cells = 32;
        let size = texel_size_m(R, cells, key().level);
        assert!((size - 152.4).abs() < 0.5, "{size}");
        let map = NormalMap::build(&surface, key(), cells);
        // The relief's own normal at a texel's centre: the height's gradient along y.
        let mut tilts = Vec::new();
        for b in 0..map.texels {
            for a in 0..map.texels {
                let (u0, v0) = key().vertex_uv(map.texels, a as i64, b as i64);
                let (u1, v1) = key().vertex_uv(map.texels, a as i64 + 1, b as i64 + 1);
                let d = direction(Face(0), 0.5 * (u0 + u1), 0.5 * (v0 + v1));
                let n = map.sample(
                    (f64::from(a) + 0.5) / f64::from(map.texels),
                    (f64::from(b) + 0.5) / f64::from(map.texels),
                );
                tilts.push(n.normalize().angle_between(d));
            }
        }
        // Slopes up to 2 pi 5 / 200 = 0.157; across a texel of 0.76 ripples the secant
        // slope reaches 10 sin(0.76 pi) / 152.4 m = 0.0446: 2.55 deg.
        let max_tilt = tilts.iter().copied().fold(0.0, f64::max).to_degrees();
        assert!((max_tilt - 2.55).abs() < 0.1, "{max_tilt}");
    }

    #[test]
    fn samples_between_texel_centres_are_bilinear_and_clamped_at_the_edges() {
        let map = NormalMap {
            texels: 2,
            normals: vec![
                [0.0, 0.0, 1.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [1.0, 1.0, 1.0],
            ],
        };
        assert_eq!(map.sample(0.25, 0.25), DVec3::Z);
        assert_eq!(map.sample(0.0, 0.0), DVec3::Z);
        assert_eq!(map.sample(0.5, 0.25), DVec3::new(0.5, 0.0, 0.5));
        assert_eq!(map.sample(1.0, 1.0), DVec3::ONE);
        assert_eq!(map.sample(0.5, 0.5), DVec3::new(0.5, 0.5, 0.5));
    }

    #[test]
    fn the_detail_fades_from_two_pixels_a_texel_to_one() {
        let (texel, p) = (10.0, 1000.0);
        assert_eq!(detail_weight(texel, p, 1000.0), 1.0);
        assert_eq!(detail_weight(texel, p, 5000.0), 1.0);
        assert!((detail_weight(texel, p, 10_000.0 / 1.5) - 0.5).abs() < 1e-12);
        assert_eq!(detail_weight(texel, p, 10_000.0), 0.0);
        assert_eq!(detail_weight(texel, p, 1e9), 0.0);
        let (mesh, map) = (DVec3::Z, DVec3::X);
        assert_eq!(shading_normal(mesh, map, 0.0), DVec3::Z);
        assert_eq!(shading_normal(mesh, map, 1.0), DVec3::X);
    }
}
