//! The refined relief on the built-in maps (`terrain/refined_heights.rs`, docs/terrain.md
//! "Refinement"): refined cells average back to the data, heights are a pure function of
//! the place (continuous across data cells, the antimeridian and coasts), the chunks
//! chosen near a camera at 2 m and 3 km close up without a crack, and the coastline
//! follows the 1 km land mask.

use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;

use glam::DVec3;
use render_wgpu::terrain::chunk_mesh::vertex_direction;
use render_wgpu::terrain::geo_grid::direction;
use render_wgpu::terrain::geomorph::{MorphEnds, morphed_vertex_m};
use render_wgpu::terrain::lod::{LodSettings, LodView, select_chunks};
use render_wgpu::terrain::refined_heights::RefinementSettings;
use render_wgpu::terrain::{ChunkMesh, EarthData, HeightField, RefinedHeights, TerrainSurface};

const R: f64 = 6.36e6;

fn refined(with_mask: bool) -> RefinedHeights {
    let data = EarthData::BuiltIn;
    let mask = if with_mask {
        data.land_mask().unwrap()
    } else {
        None
    };
    RefinedHeights::new(data.heights().unwrap(), mask, RefinementSettings::default())
}

/// A deterministic sequence in [0, 1) (the fractional parts of multiples of the golden
/// ratio's inverse and of sqrt 2's, a low-discrepancy pair).
fn point(k: usize) -> (f64, f64) {
    let k = k as f64;
    (
        (k * 0.618_033_988_749_895).fract(),
        (k * 0.414_213_562_373_095).fract(),
    )
}

/// The mean of the detail over the data cell holding a latitude and longitude (degrees),
/// by the midpoint rule on an n x n grid in the cell's grid coordinates, and its RMS.
fn cell_detail(heights: &RefinedHeights, lat: f64, lon: f64, n: usize) -> (f64, f64) {
    let (s, t) = heights.grid_coordinates(lat.to_radians(), lon.to_radians());
    let (i, j) = (s.floor(), t.floor());
    let (mut sum, mut squares) = (0.0, 0.0);
    for b in 0..n {
        for a in 0..n {
            let d = heights.detail_m(
                i + (a as f64 + 0.5) / n as f64,
                j + (b as f64 + 0.5) / n as f64,
            );
            sum += d;
            squares += d * d;
        }
    }
    let count = (n * n) as f64;
    (sum / count, (squares / count).sqrt())
}

/// Every cell's detail integrates to zero (the refined cell's mean is the data's mean
/// within 1 m), in mountains, on plains, on the sea floor, at the antimeridian and near
/// the poles; and the detail is large where the relief is.
#[test]
fn refined_cells_average_back_to_the_data_within_a_metre() {
    let heights = refined(false);
    let cells = [
        ("Pennine Alps", 46.0, 7.8),
        ("Himalaya", 28.0, 86.9),
        ("Altiplano", -20.0, -68.0),
        ("Mid-Atlantic Ridge", 30.0, -42.0),
        ("Pacific abyssal plain", 0.0, -150.0),
        ("Sahara", 23.0, 10.0),
        ("Great Plains", 40.0, -100.0),
        ("Chukotka at the antimeridian", 66.0, 179.95),
        ("East Antarctica", -80.0, 30.0),
    ];
    let mut rms = HashMap::new();
    for (name, lat, lon) in cells {
        let (mean, r) = cell_detail(&heights, lat, lon, 256);
        println!("{name}: detail mean {mean:.3} m, RMS {r:.1} m");
        assert!(mean.abs() < 1.0, "{name}: the cell's mean moved {mean} m");
        rms.insert(name, r);
    }
    assert!(rms["Pennine Alps"] > 100.0, "{rms:?}");
    assert!(rms["Himalaya"] > 100.0, "{rms:?}");
    for quiet in ["Pacific abyssal plain", "Great Plains", "Sahara"] {
        assert!(rms[quiet] < 0.2 * rms["Pennine Alps"], "{quiet}: {rms:?}");
        assert!(rms[quiet] > 0.5, "{quiet} is a mirror: {rms:?}");
    }
    // The refined height is the data's bilinear height plus the detail.
    let (lat, lon) = (46.0f64.to_radians(), 7.8f64.to_radians());
    let (s, t) = heights.grid_coordinates(lat, lon);
    let expected = heights.data.sample(lat, lon) + heights.detail_m(s, t);
    assert_eq!(heights.unconstrained_m(lat, lon), expected);
}

/// Heights are a pure function of the direction: two loads agree bit for bit, so the same
/// place gets the same height in every chunk, at every level and after a restart; and
/// they are continuous, also across data cells' borders, the antimeridian and coasts.
#[test]
fn heights_are_a_pure_continuous_function_of_place() {
    let (a, b) = (refined(true), refined(true));
    for k in 0..2000 {
        let (x, y) = point(k);
        let d = direction((2.0 * y - 1.0).asin(), PI * (2.0 * x - 1.0));
        assert_eq!(a.height_m(d).to_bits(), b.height_m(d).to_bits(), "{d}");
    }
    // Steps of 1e-9 rad (6 mm) across a cell border in latitude and longitude, the
    // antimeridian, and the Ligurian coast near Genoa.
    let across = [
        (46.0, 7.81, 0.0, 1.0),
        (46.01, 7.0 + 2.0 / 12.0, 1.0, 0.0),
        (66.0, 180.0, 1.0, 0.0),
        (44.4, 8.9, 1.0, 1.0),
    ];
    for (lat, lon, dlon, dlat) in across {
        let centre = f64::to_radians(lat);
        for k in -200..200 {
            let step = k as f64 * 1e-5;
            let at = |e: f64| {
                let p = direction(
                    centre + (step + e) * dlat * 1e-3,
                    f64::to_radians(lon) + (step + e) * dlon * 1e-3,
                );
                a.height_m(p)
            };
            let jump = (at(1e-6) - at(0.0)).abs();
            assert!(jump < 0.5, "{lat}, {lon}: {jump} m over 1e-9 rad");
        }
    }
}

/// Every triangle edge of the chunks chosen for `camera`, in f64 positions bit for bit and
/// geomorphed for that camera (`geomorph.rs`), is matched by exactly one reversed edge,
/// and the Euler characteristic is 2: one closed surface, without a crack between chunks
/// of different levels or across cube faces. Returns the number of chunks and whether the
/// finest level is among them.
fn assert_watertight(surface: &TerrainSurface<RefinedHeights>, camera: DVec3) -> (usize, bool) {
    let cells = 8;
    let mut settings = LodSettings {
        cells,
        max_error_px: 40.0,
        ..LodSettings::new(R)
    };
    settings.max_level = settings.finest_level(surface.heights.sample_spacing_rad());
    let elevation = |d: DVec3| surface.elevation_m(d);
    let view = LodView::new(camera, 1080.0, 1.0);
    let chunks = select_chunks(&settings, &view, elevation).unwrap();
    let levels: HashSet<u8> = chunks.iter().map(|c| c.key.level).collect();
    assert!(levels.len() >= 6, "{levels:?}");
    assert!(chunks.iter().any(|c| c.coarser.iter().any(|&b| b)));
    let bits = |p: DVec3| p.to_array().map(f64::to_bits);
    let mut edges: HashMap<([u64; 3], [u64; 3]), u32> = HashMap::new();
    let mut vertices = HashSet::new();
    let mut triangles = 0i64;
    let mut moved = 0;
    for chunk in &chunks {
        let mesh = ChunkMesh::build(surface, chunk, cells);
        let ends = MorphEnds::of_level(&settings, &view, chunk.key.level);
        let world = |k: u32| {
            let (i, j) = (k % (cells + 1), k / (cells + 1));
            morphed_vertex_m(surface, chunk, cells, (i, j), camera, ends)
        };
        for t in mesh.indices.chunks(3) {
            let p = [world(t[0]), world(t[1]), world(t[2])];
            for (k, q) in t.iter().zip(p) {
                // The shader's twin, from f32 offsets from the chunk's origin, rounded.
                let offset = (q - mesh.origin_m).length();
                let m = mesh.morph_factor(*k, chunk.coarser, camera, ends);
                let drawn = mesh.morphed_position_m(*k, m);
                assert!((drawn - q).length() < 2.4e-7 * offset + 1e-9);
                let (i, j) = (k % (cells + 1), k / (cells + 1));
                let own = surface.position_m(vertex_direction(chunk.key, cells, i, j));
                moved += usize::from((own - q).length() > 1e-3);
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
    assert!(moved > 0, "no vertex is morphed");
    (chunks.len(), levels.contains(&settings.max_level))
}

#[test]
fn chunks_near_the_ground_are_watertight() {
    let surface = TerrainSurface::new(refined(true), R);
    // The default scene's place in the Pennine Alps, and the coast near Genoa; a cube
    // corner (three faces meet) in the Zagros.
    let places = [
        (46.0, 7.8, 2.0),
        (46.0, 7.8, 3000.0),
        (44.4, 8.9, 2.0),
        (35.26, 45.0, 3000.0),
    ];
    for (lat, lon, clearance) in places {
        let up = direction(f64::to_radians(lat), f64::to_radians(lon));
        {
            let camera = up * (R + surface.elevation_m(up) + clearance);
            let (count, finest) = assert_watertight(&surface, camera);
            println!("{lat}, {lon}, {clearance} m: {count} chunks, closed");
            // At 2 m the chunks under the camera reach the finest level.
            assert_eq!(finest, clearance == 2.0);
        }
    }
}

/// The refined coastline agrees with the mask on points near coasts: the height is above
/// sea level where the mask's cell is land and below it where it is sea.
#[test]
fn the_coastline_follows_the_land_mask() {
    let heights = refined(true);
    let mask = heights.mask.as_ref().unwrap();
    let cell = PI / mask.height as f64;
    let (mut near_coast, mut agree) = (0usize, 0usize);
    let mut k = 0;
    while near_coast < 4000 {
        k += 1;
        let (x, y) = point(k);
        let (lat, lon) = ((2.0 * y - 1.0).asin() * 0.95, PI * (2.0 * x - 1.0));
        let land = mask.is_land(lat, lon);
        // Near a coast: a cell of the other kind within 3 cells.
        let coastal = (-3..=3).any(|a| {
            (-3..=3).any(|b| mask.is_land(lat + a as f64 * cell, lon + b as f64 * cell) != land)
        });
        if !coastal {
            continue;
        }
        near_coast += 1;
        if (heights.height_m(direction(lat, lon)) > 0.0) == land {
            agree += 1;
        }
    }
    let agreement = agree as f64 / near_coast as f64;
    println!("coastline agreement {agreement:.4} on {near_coast} points near coasts");
    assert!(agreement >= 0.95, "{agreement}");
    // The mask's orientation: known land and sea.
    let at = |lat: f64, lon: f64| mask.is_land(lat.to_radians(), lon.to_radians());
    assert!(at(46.0, 7.8) && at(-80.0, 30.0) && at(23.0, 10.0) && at(-33.9, 18.5));
    assert!(!at(0.0, -150.0) && !at(80.0, 0.0) && !at(-60.0, -120.0) && !at(43.0, 5.0));
}
