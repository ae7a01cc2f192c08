//! Which chunks to draw: level of detail by screen-space error, restricted so that
//! neighbours differ by at most one level.
//!
//! Geometric error: a chunk of level `L` with `n x n` cells has cells of about
//! `e_L = R (pi / 2) / (n 2^L)` (a face spans a quarter of a great circle), and `e_L` is
//! taken as the chunk's geometric error: the most its surface can depart from its
//! children's where the relief bends within a cell. Projected at distance `d` (camera to
//! the chunk's bounding sphere, 0 inside it) with the viewport's `pixels_per_radian`
//! (`(height_px / 2) / tan(fov_y / 2)`), it covers `e_L / d * pixels_per_radian` pixels.
//!
//! The bounding sphere is estimated from the drawn elevation at the chunk's 3 x 3 corner,
//! edge-middle and centre points: centred on the centre's point at the middle of their
//! elevation range, reaching the farthest corner at the top of the range, plus half the
//! range. Not a strict bound (relief between the samples can stick out), which the metric
//! does not need: a chunk small enough to matter near the camera is sampled finely
//! enough, and a large one holds the camera in its sphere anyway. A global elevation bound
//! instead (9 km on the Earth) would split every chunk within 9 km of the camera to the
//! finest level: thousands of them.
//! Starting from the six faces, a chunk is split while that exceeds `max_error_px` and
//! its level is below `max_level`. The selection does not depend on the view direction
//! (no frustum culling here: the renderer culls the chosen chunks), so it changes only as
//! the camera moves.
//!
//! Restriction: after the split, any chunk with a neighbour two or more levels finer is
//! split again, until every pair of neighbours differs by at most one level, and each
//! chunk records which of its edges border a coarser neighbour: its mesh drops the
//! odd vertices of those edges (see `stitching.rs`).

use std::collections::BTreeSet;
use std::f64::consts::FRAC_PI_2;

use glam::DVec3;
use thiserror::Error;

use super::chunk_key::{ChunkKey, Edge, MAX_LEVEL};
use super::cube_sphere::{Face, direction};

/// Level-of-detail settings out of range; the message names the field.
#[derive(Debug, Error, PartialEq)]
#[error("invalid level-of-detail settings: {0}")]
pub struct InvalidLodSettings(pub String);

/// What the level of detail depends on besides the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LodSettings {
    /// The reference radius `R`, metres.
    pub radius_m: f64,
    /// Cells along a chunk's side `n` (a multiple of 4: even for stitching, and so that
    /// a chunk's corners are its grandparent's vertices for geomorphing).
    pub cells: u32,
    /// Split while a chunk's projected geometric error is above this, pixels.
    pub max_error_px: f64,
    /// The finest level.
    pub max_level: u8,
}

impl LodSettings {
    /// Defaults for a planet of radius `radius_m`: 32 cells per chunk, 8 px, and levels
    /// down to cells of about 5 m on the Earth (level 16).
    pub fn new(radius_m: f64) -> LodSettings {
        LodSettings {
            radius_m,
            cells: 32,
            max_error_px: 8.0,
            max_level: 16,
        }
    }

    /// The defaults with `max_level` at the finest level whose cells are no larger than a
    /// height field's `sample_spacing_rad` (see [`LodSettings::finest_level`]).
    pub fn for_spacing(radius_m: f64, sample_spacing_rad: f64) -> LodSettings {
        let mut settings = LodSettings::new(radius_m);
        settings.max_level = settings.finest_level(sample_spacing_rad);
        settings
    }

    /// The first level whose cells (`e_L`) are no larger than `sample_spacing_rad` on the
    /// reference sphere: splitting further would only resample the same detail.
    pub fn finest_level(&self, sample_spacing_rad: f64) -> u8 {
        let spacing_m = sample_spacing_rad * self.radius_m;
        (0..MAX_LEVEL)
            .find(|&level| self.geometric_error_m(level) <= spacing_m)
            .unwrap_or(MAX_LEVEL)
    }

    /// Checks the settings; the message names the field.
    pub fn validate(&self) -> Result<(), InvalidLodSettings> {
        self.check().map_err(InvalidLodSettings)
    }

    fn check(&self) -> Result<(), String> {
        if !(self.radius_m > 0.0 && self.radius_m.is_finite()) {
            return Err(format!("radius_m: {} (expected > 0)", self.radius_m));
        }
        if self.cells < 4 || !self.cells.is_multiple_of(4) || self.cells > 256 {
            return Err(format!(
                "cells: {} (expected a multiple of 4, 4 to 256)",
                self.cells
            ));
        }
        if !(self.max_error_px > 0.0 && self.max_error_px.is_finite()) {
            return Err(format!(
                "max_error_px: {} (expected > 0)",
                self.max_error_px
            ));
        }
        if self.max_level > MAX_LEVEL {
            return Err(format!(
                "max_level: {} (expected 0 to {MAX_LEVEL})",
                self.max_level
            ));
        }
        Ok(())
    }

    /// The geometric error `e_L` of a chunk of level `level`, metres.
    pub fn geometric_error_m(&self, level: u8) -> f64 {
        self.radius_m * FRAC_PI_2 / (self.cells as f64 * (1u64 << level) as f64)
    }

    /// The chunk's estimated bounding sphere (centre, radius) for the drawn elevation
    /// function `elevation_m` (metres above the reference sphere, of a unit direction).
    pub fn bounding_sphere(
        &self,
        key: ChunkKey,
        elevation_m: &impl Fn(DVec3) -> f64,
    ) -> (DVec3, f64) {
        let half = self.cells as i64 / 2;
        let direction_at = |i: i64, j: i64| {
            let (u, v) = key.vertex_uv(self.cells, i * half, j * half);
            direction(key.face, u, v)
        };
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        for j in 0..3 {
            for i in 0..3 {
                let e = elevation_m(direction_at(i, j));
                low = low.min(e);
                high = high.max(e);
            }
        }
        let centre = direction_at(1, 1) * (self.radius_m + 0.5 * (low + high));
        let reach = [(0, 0), (2, 0), (0, 2), (2, 2)]
            .iter()
            .map(|&(i, j)| (direction_at(i, j) * (self.radius_m + high) - centre).length())
            .fold(0.0, f64::max);
        (centre, reach + 0.5 * (high - low))
    }
}

/// The camera as the level of detail sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LodView {
    /// Planet-centred, metres.
    pub camera_m: DVec3,
    /// Pixels per radian at the image centre.
    pub pixels_per_radian: f64,
}

impl LodView {
    /// A view of vertical field of view `fov_y_rad` on a viewport `height_px` tall.
    pub fn new(camera_m: DVec3, height_px: f64, fov_y_rad: f64) -> LodView {
        LodView {
            camera_m,
            pixels_per_radian: 0.5 * height_px / (0.5 * fov_y_rad).tan(),
        }
    }
}

/// A chunk to draw and which of its edges (indexed by [`Edge`]) border a coarser chunk.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SelectedChunk {
    pub key: ChunkKey,
    pub coarser: [bool; 4],
}

/// The projected geometric error of a chunk, pixels (infinite with the camera inside its
/// bounding sphere).
pub fn screen_error_px(
    settings: &LodSettings,
    view: &LodView,
    key: ChunkKey,
    elevation_m: &impl Fn(DVec3) -> f64,
) -> f64 {
    let (centre, radius) = settings.bounding_sphere(key, elevation_m);
    let distance = (view.camera_m - centre).length() - radius;
    if distance <= 0.0 {
        return f64::INFINITY;
    }
    settings.geometric_error_m(key.level) / distance * view.pixels_per_radian
}

/// The chunks covering the planet for this view, ordered by key, with neighbours at most
/// one level apart, over the drawn elevation `elevation_m` (metres above the reference
/// sphere, of a unit direction: `TerrainSurface::elevation_m`).
pub fn select_chunks(
    settings: &LodSettings,
    view: &LodView,
    elevation_m: impl Fn(DVec3) -> f64,
) -> Result<Vec<SelectedChunk>, InvalidLodSettings> {
    settings.validate()?;
    let mut leaves = BTreeSet::new();
    let mut pending: Vec<ChunkKey> = Face::ALL.iter().map(|&f| ChunkKey::root(f)).collect();
    while let Some(key) = pending.pop() {
        if key.level < settings.max_level
            && screen_error_px(settings, view, key, &elevation_m) > settings.max_error_px
        {
            pending.extend(key.children());
        } else {
            leaves.insert(key);
        }
    }
    restrict(&mut leaves);
    Ok(leaves
        .iter()
        .map(|&key| SelectedChunk {
            key,
            coarser: Edge::ALL.map(|edge| {
                let n = key.neighbour(edge);
                !leaves.contains(&n) && n.level > 0 && leaves.contains(&n.parent())
            }),
        })
        .collect())
}

/// The leaf covering the same-level key `key` or an ancestor of it, if one is a leaf
/// (none when `key` is subdivided).
pub fn covering_leaf(leaves: &BTreeSet<ChunkKey>, key: ChunkKey) -> Option<ChunkKey> {
    let mut k = key;
    loop {
        if leaves.contains(&k) {
            return Some(k);
        }
        if k.level == 0 {
            return None;
        }
        k = k.parent();
    }
}

/// Splits leaves until no two neighbours differ by more than one level.
fn restrict(leaves: &mut BTreeSet<ChunkKey>) {
    let mut pending: Vec<ChunkKey> = leaves.iter().copied().collect();
    while let Some(key) = pending.pop() {
        if !leaves.contains(&key) {
            continue;
        }
        for edge in Edge::ALL {
            if let Some(coarse) = covering_leaf(leaves, key.neighbour(edge))
                && coarse.level + 1 < key.level
            {
                leaves.remove(&coarse);
                for child in coarse.children() {
                    leaves.insert(child);
                    pending.push(child);
                }
                // The split leaf may still be too coarse for `key`: look again.
                pending.push(key);
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: f64 = 6.36e6;

    fn view(altitude_m: f64, at: DVec3) -> LodView {
        LodView::new(
            at.normalize() * (R + altitude_m),
            1080.0,
            60f64.to_radians(),
        )
    }

    fn settings() -> LodSettings {
        LodSettings::new(R)
    }

    /// Hills of a few kilometres.
    fn hills(d: DVec3) -> f64 {
        2000.0 * (1.0 + (20.0 * d.x).sin() * (17.0 * d.y + 0.5 * d.z).cos())
    }

    /// The selection covers the sphere exactly once: the leaves' areas in face
    /// coordinates add up to six faces, and no leaf is another's ancestor.
    fn assert_partition(chunks: &[SelectedChunk]) {
        let area: f64 = chunks
            .iter()
            .map(|c| 4.0 / (c.key.side() as f64).powi(2))
            .sum();
        assert!((area - 24.0).abs() < 1e-9, "{area}");
        let keys: BTreeSet<_> = chunks.iter().map(|c| c.key).collect();
        for c in chunks {
            let mut k = c.key;
            while k.level > 0 {
                k = k.parent();
                assert!(!keys.contains(&k), "{:?} inside {k:?}", c.key);
            }
        }
    }

    /// From 400,000 km (beyond the Moon's distance) only the six faces are drawn.
    #[test]
    fn far_camera_gets_the_coarsest_level() {
        let chunks =
            select_chunks(&settings(), &view(4e8, DVec3::new(1.0, 0.3, 0.2)), hills).unwrap();
        assert_eq!(chunks.len(), 6);
        assert!(
            chunks
                .iter()
                .all(|c| c.key.level == 0 && c.coarser == [false; 4])
        );
    }

    /// Near chunks are finer than far ones: the chunk under a camera at 2 m is at the
    /// finest level, the one on the far side of the planet coarse.
    #[test]
    fn near_chunks_are_finer_than_far_ones() {
        let at = DVec3::new(0.3, -0.8, 0.5);
        let chunks =
            select_chunks(&settings(), &view(2.0 + hills(at.normalize()), at), hills).unwrap();
        assert_partition(&chunks);
        let level_at = |d: DVec3| {
            let (face, u, v) = super::super::cube_sphere::face_coordinates(d);
            chunks
                .iter()
                .find(|c| {
                    let side = c.key.side() as f64;
                    c.key.face == face
                        && ((u + 1.0) / 2.0 * side).floor().min(side - 1.0) as u32 == c.key.x
                        && ((v + 1.0) / 2.0 * side).floor().min(side - 1.0) as u32 == c.key.y
                })
                .unwrap()
                .key
                .level
        };
        assert_eq!(level_at(at), settings().max_level);
        assert!(level_at(-at) <= 2, "{}", level_at(-at));
        // Levels fall off with distance along a great circle away from the camera.
        let mut previous = u8::MAX;
        for k in 0..8 {
            let angle = 0.01 * 2f64.powi(k);
            let d = (at.normalize() * angle.cos() + DVec3::Z.cross(at).normalize() * angle.sin())
                .normalize();
            let level = level_at(d);
            assert!(level <= previous, "{angle} rad: {level} after {previous}");
            previous = level;
        }
    }

    /// The chunk count stays bounded from 1 m to 10^9 m (with the defaults and a
    /// 1080-pixel, 60-degree view), and neighbours differ by at most one level, with the
    /// coarser flags saying where.
    #[test]
    fn counts_are_bounded_and_neighbours_restricted() {
        let s = settings();
        let at = DVec3::new(1.0, 1.0, 1.0); // a cube corner, where three faces meet
        let mut counts = Vec::new();
        for altitude in [1.0, 1e2, 1e4, 1e5, 1e6, 1e7, 1e9] {
            let chunks =
                select_chunks(&s, &view(altitude + hills(at.normalize()), at), hills).unwrap();
            assert_partition(&chunks);
            counts.push((altitude, chunks.len()));
            let keys: BTreeSet<_> = chunks.iter().map(|c| c.key).collect();
            for c in &chunks {
                for edge in Edge::ALL {
                    let covering = covering_leaf(&keys, c.key.neighbour(edge));
                    match covering {
                        Some(n) => {
                            assert!(c.key.level - n.level <= 1, "{:?} next to {n:?}", c.key);
                            assert_eq!(c.coarser[edge as usize], n.level < c.key.level);
                        }
                        None => assert!(!c.coarser[edge as usize]),
                    }
                }
            }
        }
        assert!(counts.iter().all(|&(_, n)| n <= 4000), "{counts:?}");
    }

    /// The finest level follows the height field's detail: cells of 10' data (18.5 km)
    /// stop at level 5, metre-scale detail goes to level 18 (1.2 m cells).
    #[test]
    fn the_finest_level_follows_the_sample_spacing() {
        let data = LodSettings::for_spacing(R, std::f64::consts::PI / 1080.0);
        assert_eq!(data.max_level, 5);
        assert!(data.geometric_error_m(5) <= 18_500.0 && data.geometric_error_m(4) > 18_500.0);
        let fine = LodSettings::for_spacing(R, 2.26 / R);
        assert_eq!(fine.max_level, 18);
        assert_eq!(LodSettings::for_spacing(R, 1e-12).max_level, MAX_LEVEL);
    }

    #[test]
    fn settings_are_checked() {
        let mut s = settings();
        s.cells = 7;
        assert!(s.validate().unwrap_err().0.starts_with("cells"));
        s.cells = 6;
        assert!(s.validate().unwrap_err().0.contains("multiple of 4"));
        let mut s = settings();
        s.max_error_px = 0.0;
        assert!(s.validate().unwrap_err().0.starts_with("max_error_px"));
        let e = select_chunks(&s, &view(1.0, DVec3::X), hills).unwrap_err();
        assert!(e.to_string().contains("max_error_px"), "{e}");
        assert!(settings().validate().is_ok());
    }
}
