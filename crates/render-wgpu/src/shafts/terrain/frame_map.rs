//! The shadow map of a frame: the grid follows the camera (its centre under the camera,
//! its cells finer the lower the camera), the relief's heights are sampled again only
//! when the camera leaves the grid's middle or changes scale, and the shadow's tops are
//! swept again when the sun or the heights change.

use atmosphere_core::models::error::ModelError;
use atmosphere_core::shafts::{GnomonicGrid, Relief, ShadowMap};
use glam::DVec3;
use rayon::prelude::*;

/// Cells per side of the shadow map.
pub const MAP_CELLS: usize = 256;

/// Beyond the horizon of the camera's altitude, the grid reaches this far on each side,
/// m: for the mountains that cast shadows into the air the camera sees.
const BEYOND_HORIZON_M: f64 = 25_000.0;

/// The finest and coarsest cells, m: a power of two between them.
const CELL_RANGE_M: (f64, f64) = (1.0, 4096.0);

/// The side of a cell for a camera `altitude_m` above the reference sphere of radius
/// `radius_m`: the grid spans twice the horizon distance plus a margin each side, in
/// cells of the power of two at or below that width over [`MAP_CELLS`].
pub fn cell_for_altitude(altitude_m: f64, radius_m: f64) -> f64 {
    let horizon_m = (2.0 * radius_m * altitude_m.max(0.0)).sqrt();
    let width_m = 2.0 * (horizon_m + BEYOND_HORIZON_M);
    let cell = (width_m / MAP_CELLS as f64).log2().floor().exp2();
    cell.clamp(CELL_RANGE_M.0, CELL_RANGE_M.1)
}

/// The shadow map of the frames so far, and the heights it was swept from.
#[derive(Debug, Default)]
pub struct FrameShadow {
    heights: Option<(GnomonicGrid, Vec<f32>)>,
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
        let cell_m = cell_for_altitude(camera_m.length() - radius_m, radius_m);
        let up = camera_m.normalize();
        let width_m = cell_m * MAP_CELLS as f64;
        let fits = |g: &GnomonicGrid| {
            g.cell_m == cell_m
                && g.radius_m == radius_m
                && g.up.angle_between(up) * radius_m < width_m / 8.0
        };
        let resampled = match &self.heights {
            Some((grid, _)) if fits(grid) => false,
            _ => {
                let grid = GnomonicGrid::new(up, radius_m, cell_m, MAP_CELLS)?;
                self.heights = Some((grid, sample(&grid, relief)));
                true
            }
        };
        let (grid, heights) = self.heights.as_ref().expect("sampled above");
        let stale = resampled || self.map.as_ref().is_none_or(|(s, _)| *s != sun);
        if stale {
            self.map = Some((sun, ShadowMap::new(*grid, heights, sun)?));
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
}
