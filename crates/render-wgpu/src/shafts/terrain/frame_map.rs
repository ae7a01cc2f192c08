//! The shadow map of a frame: cascaded grids on one centre under the camera, the
//! outermost spanning the camera's horizon and a margin, each inner one half as wide in
//! cells half as wide (so the shadows of narrow valleys near the camera are kept, while
//! far mountains still cast theirs); the cells are finer the lower the camera. The
//! relief's heights are sampled again only when the camera leaves the finest grid's
//! middle or changes scale, and the shadow's tops are swept again when the sun or the
//! heights change.

use atmosphere_core::models::error::ModelError;
use atmosphere_core::shafts::{GnomonicGrid, Relief, ShadowMap};
use glam::DVec3;
use rayon::prelude::*;

/// Cells per side of each level of the shadow map.
pub const MAP_CELLS: usize = 256;

/// Levels of the cascade, the finest with cells `2^(MAP_LEVELS - 1)` times narrower than
/// the outermost's (fewer where that would go below the finest cell).
pub const MAP_LEVELS: usize = 4;

/// Beyond the horizon of the camera's altitude, the grid reaches this far on each side,
/// m: for the mountains that cast shadows into the air the camera sees.
const BEYOND_HORIZON_M: f64 = 25_000.0;

/// The finest and coarsest cells, m: a power of two between them.
const CELL_RANGE_M: (f64, f64) = (1.0, 4096.0);

/// The side of the outermost level's cell for a camera `altitude_m` above the reference
/// sphere of radius `radius_m`: that grid spans twice the horizon distance plus a margin
/// each side, in cells of the power of two at or below that width over [`MAP_CELLS`].
pub fn cell_for_altitude(altitude_m: f64, radius_m: f64) -> f64 {
    let horizon_m = (2.0 * radius_m * altitude_m.max(0.0)).sqrt();
    let width_m = 2.0 * (horizon_m + BEYOND_HORIZON_M);
    let cell = (width_m / MAP_CELLS as f64).log2().floor().exp2();
    cell.clamp(CELL_RANGE_M.0, CELL_RANGE_M.1)
}

/// The cells of the cascade's levels, finest first, for an outermost cell `outer_m`.
pub fn level_cells(outer_m: f64) -> Vec<f64> {
    let mut cells = vec![outer_m];
    while cells.len() < MAP_LEVELS && cells[0] / 2.0 >= CELL_RANGE_M.0 {
        cells.insert(0, cells[0] / 2.0);
    }
    cells
}

/// Unit sun directions closer than this (a chord, about the angle in rad) share a map.
const SAME_SUN: f64 = 1e-9;

/// The shadow map of the frames so far, and the heights it was swept from (per level,
/// finest first).
#[derive(Debug, Default)]
pub struct FrameShadow {
    heights: Vec<(GnomonicGrid, Vec<f32>)>,
    map: Option<(DVec3, ShadowMap)>,
}

impl FrameShadow {
    /// The shadow map of `relief` for a camera at `camera_m` (planet-centred) and the
    /// unit sun direction `sun`, on the sphere of radius `radius_m`; an error names what
    /// the map cannot take (a relief whose height is not finite).
    pub fn update<R: Relief + Sync>(
        &mut self,
        camera_m: DVec3,
        sun: DVec3,
        radius_m: f64,
        relief: &R,
    ) -> Result<&ShadowMap, ModelError> {
        let cells = level_cells(cell_for_altitude(camera_m.length() - radius_m, radius_m));
        let up = camera_m.normalize();
        let finest_width_m = cells[0] * MAP_CELLS as f64;
        let fits = |g: &GnomonicGrid| {
            g.cell_m == cells[0]
                && g.radius_m == radius_m
                && g.up.angle_between(up) * radius_m < finest_width_m / 8.0
        };
        let resampled = match self.heights.first() {
            Some((grid, _)) if fits(grid) && self.heights.len() == cells.len() => false,
            _ => {
                self.heights = cells
                    .iter()
                    .map(|&cell_m| {
                        let grid = GnomonicGrid::new(up, radius_m, cell_m, MAP_CELLS)?;
                        Ok((grid, sample(&grid, relief)))
                    })
                    .collect::<Result<_, ModelError>>()?;
                true
            }
        };
        // Suns that differ in their last bits (rays turned one by one) share a map.
        let stale = resampled
            || self
                .map
                .as_ref()
                .is_none_or(|(s, _)| (*s - sun).length() > SAME_SUN);
        if stale {
            let mut levels = self.heights.iter().rev();
            let (grid, heights) = levels.next().expect("at least one level");
            let mut map = ShadowMap::new(*grid, heights, sun)?;
            for (grid, heights) in levels {
                map = ShadowMap::nested(*grid, heights, sun, map)?;
            }
            self.map = Some((sun, map));
        }
        Ok(&self.map.as_ref().expect("swept above").1)
    }

    /// The last map made (`None` before any).
    pub fn map(&self) -> Option<&ShadowMap> {
        self.map.as_ref().map(|(_, m)| m)
    }
}

/// `GnomonicGrid::sample`, its rows in parallel.
fn sample<R: Relief + Sync>(grid: &GnomonicGrid, relief: &R) -> Vec<f32> {
    (0..grid.size)
        .into_par_iter()
        .flat_map_iter(|j| {
            let y = grid.cell_centre_m(j);
            (0..grid.size).map(move |i| {
                let d = grid.direction(grid.cell_centre_m(i), y);
                relief.elevation_m(d) as f32
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_grow_with_altitude_and_stay_in_range() {
        let r = 6.36e6;
        assert_eq!(cell_for_altitude(1.0, r), 128.0);
        assert_eq!(cell_for_altitude(3_000.0, r), 1024.0);
        assert_eq!(cell_for_altitude(1.0e7, r), CELL_RANGE_M.1);
        assert_eq!(cell_for_altitude(-5.0, r), cell_for_altitude(0.0, r));
    }

    #[test]
    fn levels_halve_their_cells_down_to_the_finest() {
        assert_eq!(level_cells(2048.0), vec![256.0, 512.0, 1024.0, 2048.0]);
        assert_eq!(level_cells(2.0), vec![1.0, 2.0]);
        assert_eq!(level_cells(1.0), vec![1.0]);
    }
}
