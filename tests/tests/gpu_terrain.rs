//! The terrain pass on the GPU (`render_wgpu::terrain::pass`, `shaders/terrain/terrain.wgsl`) against its
//! CPU twin: the surface buffer's distance, normal and albedo at each pixel equal the
//! nearest hit of the pixel's ray (`Frame::pixel_ray`) on the chunk meshes the CPU
//! selects for the same camera (`select_chunks`, `ChunkMesh`), the normal interpolated
//! across the triangle and the albedo from `ColourMap::sample_linear` with rock and snow
//! laid over it (`geo::land_cover::land_albedo`), the sea marked as water; from a metre-scale
//! near plane to the whole disc from 20,000 km. And the planner: looking into space
//! skips the pass and changes no pixel.
//!
//! Needs a GPU adapter (lavapipe will do); see `support/mod.rs`.

mod support;

use atmosphere_core::geo::land_cover::{SnowLine, land_albedo};
use atmosphere_core::models::id::ModelId;
use std::collections::HashMap;

use glam::DVec3;
use render_wgpu::Frame;
use render_wgpu::frame::{LocalView, TerrainOptions, location_rotation};
use render_wgpu::terrain::chunk_key::ChunkKey;
use render_wgpu::terrain::detail_morph::{detail_factor, morphed_detail, morphed_texel_m};
use render_wgpu::terrain::geo_grid::lat_lon;
use render_wgpu::terrain::geomorph::MorphEnds;
use render_wgpu::terrain::lod::{LodSettings, LodView, SelectedChunk, select_chunks};
use render_wgpu::terrain::normal_map::{detail_weight, shading_normal, texel_size_m};
use render_wgpu::terrain::sea_colour::open_sea_albedo;
use render_wgpu::terrain::{ChunkMesh, EarthData, HeightField, RefinedHeights, TerrainSurface};
use support::{frame, renderer_or_skip};

/// A frame of nishita at a place, azimuths geographic, with terrain.
fn terrain_frame(lat: f64, lon: f64, view: LocalView, fov_deg: f64, w: u32, h: u32) -> Frame {
    let local = LocalView {
        view_azimuth_deg: -view.view_azimuth_deg,
        sun_azimuth_deg: -view.sun_azimuth_deg,
        ..view
    };
    let mut f = frame(ModelId::Nishita, local, fov_deg, w, h);
    let place = location_rotation(lat, lon);
    f.camera_position_m = place * f.camera_position_m;
    f.orientation = place * f.orientation;
    f.sun_direction = place * f.sun_direction;
    f.terrain = Some(TerrainOptions {
        exaggeration: 2.0,
        ..TerrainOptions::default()
    });
    f
}

fn view(altitude_m: f64, view_zenith_deg: f64, view_azimuth_deg: f64) -> LocalView {
    LocalView {
        altitude_m,
        view_zenith_deg,
        view_azimuth_deg,
        sun_zenith_deg: 50.0,
        sun_azimuth_deg: 200.0,
    }
}

/// The nearest hit of a ray on a triangle (Moller-Trumbore in f64): distance and
/// barycentric weights of the second and third vertex.
fn hit_triangle(origin: DVec3, dir: DVec3, p: [DVec3; 3]) -> Option<(f64, f64, f64)> {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let h = dir.cross(e2);
    let det = e1.dot(h);
    if det.abs() < 1e-30 {
        return None;
    }
    let s = origin - p[0];
    let u = s.dot(h) / det;
    let q = s.cross(e1);
    let v = dir.dot(q) / det;
    let t = e2.dot(q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some((t, u, v))
}

/// The CPU twin of the surface buffer: chunks and meshes for a frame.
struct CpuTerrain {
    surface: TerrainSurface<RefinedHeights>,
    settings: LodSettings,
    view: LodView,
    /// The chosen chunks.
    chunks: Vec<SelectedChunk>,
    meshes: HashMap<ChunkKey, ChunkMesh>,
}

impl CpuTerrain {
    fn new(f: &Frame) -> CpuTerrain {
        let heights = EarthData::BuiltIn.refined_heights().unwrap();
        let radius = f.atmosphere.bottom_radius_m;
        let heights_spacing = heights.sample_spacing_rad();
        let surface = TerrainSurface {
            exaggeration: f.terrain.unwrap().exaggeration,
            ..TerrainSurface::new(heights, radius)
        };
        let settings = LodSettings::for_spacing(radius, heights_spacing);
        let lod_view = LodView::new(
            f.camera_position_m,
            f64::from(f.height),
            f.vertical_fov_deg.to_radians(),
        );
        let chunks = select_chunks(&settings, &lod_view, |d| surface.elevation_m(d)).unwrap();
        CpuTerrain {
            surface,
            settings,
            view: lod_view,
            chunks,
            meshes: HashMap::new(),
        }
    }

    /// Nearest hit: distance, shading normal (the interpolated mesh normal with the
    /// normal map's detail), hit point, interpolated height of the height field, and the
    /// detail: how far the shading normal is from the mesh's, from the one with unmorphed
    /// mesh normals, and from the one with the chunk's own map unmorphed.
    fn cast(&mut self, origin: DVec3, dir: DVec3) -> Option<(f64, DVec3, DVec3, f64, [f64; 3])> {
        let mut best: Option<(f64, DVec3, DVec3, f64, [f64; 3])> = None;
        for chunk in &self.chunks {
            let mesh = self
                .meshes
                .entry(chunk.key)
                .or_insert_with(|| ChunkMesh::build(&self.surface, chunk, self.settings.cells));
            // The mesh's vertices' sphere holds its triangles.
            let (centre, radius) = mesh.bounding_sphere();
            let to_centre = centre - origin;
            let along = to_centre.dot(dir);
            if (to_centre - dir * along).length() > radius || along < -radius {
                continue;
            }
            // Geomorphed as the vertex shader does (`geomorph.rs`).
            let ends = MorphEnds::of_level(&self.settings, &self.view, chunk.key.level);
            let factor = |k: u32| mesh.morph_factor(k, chunk.coarser, self.view.camera_m, ends);
            for t in mesh.indices.chunks(3) {
                let m = [0, 1, 2].map(|k| factor(t[k]));
                let p = [0, 1, 2].map(|k| mesh.morphed_position_m(t[k], m[k]));
                if let Some((d, u, v)) = hit_triangle(origin, dir, p)
                    && best.is_none_or(|b| d < b.0)
                {
                    // Normals morphed towards the parent's with the vertices.
                    let n = [0, 1, 2].map(|k| {
                        let nm =
                            mesh.normal_morph_factor(t[k], chunk.coarser, self.view.camera_m, ends);
                        mesh.morphed_normal(t[k], nm)
                    });
                    let interpolated = n[0] * (1.0 - u - v) + n[1] * u + n[2] * v;
                    // The normal map at the chunk coordinate (i, j) / cells, faded by the
                    // texel's size in pixels (`normal_map.rs`).
                    let cells = mesh.cells;
                    let chunk_uv = [0, 1, 2].map(|k| {
                        let (i, j) = (t[k] % (cells + 1), t[k] / (cells + 1));
                        DVec3::new(f64::from(i), f64::from(j), 0.0) / f64::from(cells)
                    });
                    let st = chunk_uv[0] * (1.0 - u - v) + chunk_uv[1] * u + chunk_uv[2] * v;
                    // Blended towards the parent's map by the chunk's own morph factor
                    // (`detail_morph.rs`).
                    let dm = [0, 1, 2].map(|k| {
                        let distance = (mesh.world_position_m(t[k]) - self.view.camera_m).length();
                        detail_factor(distance, ends)
                    });
                    let dm = dm[0] * (1.0 - u - v) + dm[1] * u + dm[2] * v;
                    let own_map = mesh.normal_map.sample(st.x, st.y);
                    let map = morphed_detail(own_map, mesh.parent_map.sample(st.x, st.y), dm);
                    let texel = texel_size_m(self.surface.radius_m, cells, chunk.key.level);
                    let p = self.view.pixels_per_radian;
                    let weight = detail_weight(morphed_texel_m(texel, dm), p, d);
                    let normal = shading_normal(interpolated, map, weight);
                    let unmorphed_map =
                        shading_normal(interpolated, own_map, detail_weight(texel, p, d));
                    let map_morphed = (normal - unmorphed_map).length();
                    let h = [0, 1, 2].map(|k| mesh.morphed_height_m(t[k], m[k]));
                    let height = h[0] * (1.0 - u - v) + h[1] * u + h[2] * v;
                    let detail = (normal - interpolated.normalize()).length();
                    let own = [0, 1, 2].map(|k| mesh.morphed_normal(t[k], 0.0));
                    let own = own[0] * (1.0 - u - v) + own[1] * u + own[2] * v;
                    let morphed = (normal - shading_normal(own, map, weight)).length();
                    best = Some((
                        d,
                        normal,
                        origin + dir * d,
                        height,
                        [detail, morphed, map_morphed],
                    ));
                }
            }
        }
        best
    }
}

/// A normal's change by the normal map that counts as detail (about 1.1 deg).
const MIN_DETAIL: f64 = 0.02;

/// The GPU's shading normal against the CPU's.
const MAX_NORMAL: f64 = 2e-3;

/// Compares every `step`-th pixel's surface texel with the CPU's hit (distances within
/// `max_distance`, relative); pixels where one
/// side sees terrain and the other not lie on silhouettes (the rasteriser's coverage
/// against an exact ray), at most `max_edge_fraction` of them. `near_albedo`: whether
/// some hits lie within 20 km, where the albedo is compared with the full-resolution map,
/// or with the water's albedo where the interpolated height is below 0. Returns the
/// numbers of water pixels, of land pixels under rock or snow, of pixels whose normal
/// the normal map turns by more than [`MIN_DETAIL`] from the mesh's, of pixels whose
/// normal the mesh normals' morph turns by more than [`MAX_NORMAL`], and of pixels whose
/// normal the normal map's morph turns by more than [`MAX_NORMAL`], compared (`None`:
/// no GPU, skipped).
fn check_surface(
    name: &str,
    f: &Frame,
    step: u32,
    max_distance: f64,
    max_edge_fraction: f64,
    near_albedo: bool,
) -> Option<(usize, usize, usize, usize, usize)> {
    let mut renderer = renderer_or_skip(name)?;
    let plan = renderer.render(f).unwrap();
    assert!(plan.runs("terrain"), "{plan}");
    let texels = renderer.read_surface().unwrap();
    let colours = EarthData::BuiltIn.colours().unwrap();
    let mut cpu = CpuTerrain::new(f);
    let heights = &cpu.surface.heights;
    let sea = open_sea_albedo(&colours, &heights.data, heights.mask.as_ref());
    let snow_line = SnowLine::for_declination(f.sun_direction.normalize().z.asin());
    let (mut water, mut covered, mut detailed, mut turned, mut map_turned) = (0, 0, 0, 0, 0);
    let (mut compared, mut edges, mut worst_distance, mut worst_normal, mut worst_albedo) =
        (0, 0, 0.0f64, 0.0f64, 0.0f64);
    let mut albedos = 0;
    for row in (0..f.height).step_by(step as usize) {
        for column in (0..f.width).step_by(step as usize) {
            let texel = texels[(row * f.width + column) as usize];
            let ray = f.pixel_ray(column, row);
            let hit = cpu.cast(ray.origin_m, ray.direction);
            let Some((distance, normal, point, height, [detail, morphed, map_morphed])) =
                hit.filter(|_| texel.distance_m > 0.0)
            else {
                if hit.is_some() != (texel.distance_m > 0.0) {
                    edges += 1;
                }
                continue;
            };
            compared += 1;
            detailed += usize::from(detail > MIN_DETAIL);
            // Pixels a GPU without the normals' morph would miss by more than the bound.
            turned += usize::from(morphed > MAX_NORMAL);
            // And without the normal map's morph.
            map_turned += usize::from(map_morphed > MAX_NORMAL);
            let gpu_distance = f64::from(texel.distance_m);
            worst_distance = worst_distance.max((gpu_distance - distance).abs() / distance);
            let gpu_normal = glam::Vec3::from(texel.normal).as_dvec3();
            worst_normal = worst_normal.max((gpu_normal - normal).length());
            // Near the camera the colour map is read at full resolution (texels of
            // 10 km are many pixels wide); farther, mip levels average it.
            // Within a centimetre of the coastline f32 interpolation may decide either way.
            if distance < 20_000.0 && height.abs() > 0.01 {
                let (lat, lon) = lat_lon(point);
                let cos_slope = normal.dot(point.normalize());
                let expected = if height < 0.0 {
                    water += 1;
                    sea
                } else {
                    let map = colours.sample_linear(lat, lon);
                    let land = land_albedo(map, lat, height, cos_slope, &snow_line);
                    covered += usize::from((0..3).any(|c| (land[c] - map[c]).abs() > 0.02));
                    land
                };
                assert_eq!(
                    texel.water,
                    height < 0.0,
                    "{name}: water at ({column}, {row})"
                );
                albedos += 1;
                for c in 0..3 {
                    worst_albedo =
                        worst_albedo.max((f64::from(texel.albedo[c]) - expected[c]).abs());
                }
            }
        }
    }
    let total = compared + edges;

    println!(
        "{name}: {compared} pixels compared, {edges} on silhouettes; worst relative distance \
         {worst_distance:.1e}, normal {worst_normal:.1e}, albedo {worst_albedo:.1e} ({albedos} \
         pixels within 20 km); plan: {plan}"
    );
    assert!(compared > total / 3, "{name}: too few terrain pixels");
    assert_eq!(
        albedos > 0,
        near_albedo,
        "{name}: {albedos} albedos compared"
    );
    assert!(
        (edges as f64) <= max_edge_fraction * total as f64,
        "{name}: {edges} of {total}"
    );
    // f32 camera-relative positions: 1e-5 of the distance, up to a few times more a
    // metre above the ground.
    assert!(
        worst_distance < max_distance,
        "{name}: distance {worst_distance:e}"
    );
    // The rasteriser interpolates the normal linearly; the CPU the same, then normalises;
    // the normal map's f16 texels and the sampler's filter weights add theirs.
    assert!(worst_normal < MAX_NORMAL, "{name}: normal {worst_normal:e}");
    // Bilinear sRGB filtering in 8 bits against the CPU's f64.
    assert!(worst_albedo < 6e-3, "{name}: albedo {worst_albedo:e}");
    println!(
        "{name}: {water} water pixels, {covered} under rock or snow, {detailed} shaded by the \
         normal map's detail, {turned} turned by the normals' morph and {map_turned} by the \
         map's morph by more than the bound"
    );
    Some((water, covered, detailed, turned, map_turned))
}

#[test]
fn terrain_over_the_alps_matches_the_cpu_meshes() {
    // Exaggeration 2 lifts the peaks near 9 km.
    let f = terrain_frame(46.05, 7.75, view(11_000.0, 95.0, 225.0), 60.0, 96, 54);
    let counts = check_surface("Alps from 11 km", &f, 3, 4e-5, 0.05, true);
    // No sea; rock and snow on the near slopes.
    assert!(
        counts.is_none_or(|(water, covered, _, turned, map_turned)| water == 0
            && covered > 10
            && turned > 0
            && map_turned > 0),
        "{counts:?}"
    );
}

#[test]
fn the_normal_maps_detail_shades_the_ground_two_metres_up_as_the_cpu_says() {
    // 2 m above a slope of the Pennine Alps (the 2 m golden's place), looking down it: the
    // normal map turns the shading normal away from the mesh's within its cells; without
    // the map on the GPU its normals would miss the CPU's by as much.
    let mut f = terrain_frame(46.0, 7.8, view(0.0, 97.0, 40.0), 60.0, 64, 36);
    f.terrain = Some(TerrainOptions::default());
    let up = f.camera_position_m.normalize();
    let cpu = CpuTerrain::new(&f);
    let ground = cpu.surface.elevation_m(up);
    f.camera_position_m = up * (f.atmosphere.bottom_radius_m + ground + 2.0);
    let counts = check_surface("2 m over the Alps", &f, 2, 1.2e-4, 0.05, true);
    assert!(
        counts.is_none_or(|(_, _, detailed, _, map_turned)| detailed > 100 && map_turned > 0),
        "{counts:?}"
    );
}

#[test]
fn terrain_a_metre_above_the_ground_matches_the_cpu_meshes() {
    // The Sahara at true scale: ground 1.5 m below the camera, the near plane 0.75 m.
    let mut f = terrain_frame(23.0, 10.0, view(0.0, 100.0, 30.0), 70.0, 64, 36);
    f.terrain = Some(TerrainOptions::default());
    let up = f.camera_position_m.normalize();
    let cpu = CpuTerrain::new(&f);
    let ground = cpu.surface.elevation_m(up);
    f.camera_position_m = up * (f.atmosphere.bottom_radius_m + ground + 1.5);
    // Rays graze metre-scale facets a few metres away, geomorphing within the band: the
    // GPU's f32 morph departs from the CPU's by a fraction of a millimetre there.
    let counts = check_surface("1.5 m over the Sahara", &f, 2, 1.2e-4, 0.05, true);
    assert!(
        counts.is_none_or(|(water, _, _, _, map_turned)| water == 0 && map_turned > 0),
        "{counts:?}"
    );
}

#[test]
fn the_whole_disc_from_20000_km_matches_the_cpu_meshes() {
    let f = terrain_frame(30.0, 10.0, view(2e7, 180.0, 0.0), 40.0, 64, 64);
    // Every hit is far beyond 20 km: the albedo comes from averaged mip levels and is
    // not compared here (`colour_mips.rs` has its own test).
    check_surface("disc from 20,000 km", &f, 2, 4e-5, 0.08, false);
}

#[test]
fn looking_into_space_skips_the_terrain_and_changes_nothing() {
    let Some(mut renderer) = renderer_or_skip("terrain plan") else {
        return;
    };
    // 2 km over the Atlantic, looking up.
    let mut f = terrain_frame(40.0, -30.0, view(2_000.0, 20.0, 225.0), 40.0, 32, 18);
    let plan = renderer.render(&f).unwrap();
    assert!(!plan.runs("terrain"), "{plan}");
    assert!(plan.to_string().contains("no terrain in view"), "{plan}");
    let with_terrain = renderer.read_hdr().unwrap();
    f.terrain = None;
    renderer.render(&f).unwrap();
    assert_eq!(with_terrain, renderer.read_hdr().unwrap());
}

#[test]
fn a_bad_exaggeration_is_refused() {
    let Some(mut renderer) = renderer_or_skip("terrain exaggeration") else {
        return;
    };
    let mut f = terrain_frame(46.05, 7.75, view(4_000.0, 20.0, 225.0), 40.0, 8, 8);
    f.terrain = Some(TerrainOptions {
        exaggeration: f64::NAN,
        ..TerrainOptions::default()
    });
    let err = renderer.render(&f).unwrap_err().to_string();
    assert!(err.contains("exaggeration"), "{err}");
}
