//! The per-frame representation: over each cell of a grid of the view's region, the
//! altitude `S` of the top of the terrain's shadow volume for this frame's sun. A point
//! at altitude `a` over a cell sees the sun when `a >= S` there.
//!
//! `S` follows from one sweep away from the sun (the horizon recurrence of height-field
//! shadowing, Max 1988, "Horizon mapping", section 2, with a fixed light direction):
//! with `c'` the point one column (or row, along the axis closer to the sun's azimuth)
//! towards the sun, `L` the horizontal distance to it and `e` the sun's elevation over
//! cell `c`,
//!
//! `S(c) = max(h(c), S(c') - L tan e)`,
//!
//! `S(c')` interpolated linearly between its two neighbouring cells. Beyond the grid's
//! sunward edge nothing casts a shadow. The sun's azimuth is the grid centre's; the
//! sphere's curvature enters through the local `e`. Cells over which nothing casts a
//! shadow store `h - cell` instead of `h`, so that the air just above the drawn surface,
//! which may dip below the samples' interpolation, is not taken for shadow.

use glam::DVec3;

use super::gnomonic_grid::GnomonicGrid;
use super::sun_visibility::SunVisibility;
use crate::models::error::ModelError;

/// The shadow volume's top over a grid, for one sun direction.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowMap {
    pub grid: GnomonicGrid,
    /// `S` per cell, row by row, m above the reference sphere.
    pub tops_m: Vec<f32>,
    /// The highest `S`: no point above it is shadowed.
    pub max_top_m: f32,
    /// Width of the penumbra below `S` over which the visibility falls from 1 to 0, m:
    /// the rise of the sun's ray over one cell, between 1 m and one cell.
    pub band_m: f32,
    /// Cells whose air holds shadow (`S` above the relief): none, and the terrain casts
    /// no shadow into the air over the grid.
    pub shadowing_cells: usize,
}

impl ShadowMap {
    /// The shadow of `heights` (per cell, row by row, m, as `GnomonicGrid::sample` gives
    /// them) for the sun direction `sun`; an error names a wrong count of heights, a
    /// height that is not finite or a sun that is not a direction.
    pub fn new(grid: GnomonicGrid, heights: &[f32], sun: DVec3) -> Result<ShadowMap, ModelError> {
        let n = grid.size;
        let bad = |what: String| Err(ModelError::Settings(format!("shadow map: {what}")));
        if heights.len() != n * n {
            return bad(format!("{} heights for {n} x {n} cells", heights.len()));
        }
        if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
            return bad(format!("height {i} is {}", heights[i]));
        }
        let Some(sun) = sun.try_normalize() else {
            return bad(format!("sun {sun} is not a direction"));
        };
        let (sx, sy) = (sun.dot(grid.east), sun.dot(grid.north));
        let horizontal = sx.hypot(sy);
        let centre_tan = sun.dot(grid.up) / horizontal.max(1e-12);
        let band_m = (grid.cell_m * centre_tan).clamp(1.0, grid.cell_m) as f32;
        let mut tops = heights.to_vec();
        if horizontal > 1e-9 {
            sweep(&grid, heights, &mut tops, sun, (sx, sy));
        }
        // Where the relief casts no shadow, the air a cell's height below the sampled
        // relief still sees the sun: the drawn surface between samples may lie that far
        // below their interpolation, and its air must not count as shadowed.
        let mut shadowing_cells = 0;
        for (t, h) in tops.iter_mut().zip(heights) {
            if *t > *h {
                shadowing_cells += 1;
            } else {
                *t = h - grid.cell_m as f32;
            }
        }
        let max_top_m = tops.iter().fold(f32::MIN, |m, &t| m.max(t));
        Ok(ShadowMap {
            grid,
            tops_m: tops,
            max_top_m,
            band_m,
            shadowing_cells,
        })
    }

    /// `S` at fractional cell coordinates inside the grid (bilinear).
    fn top_at(&self, column: f64, row: f64) -> f64 {
        let n = self.grid.size;
        let i = (column.floor() as usize).min(n - 2);
        let j = (row.floor() as usize).min(n - 2);
        let (a, b) = (column - i as f64, row - j as f64);
        let s = |i: usize, j: usize| f64::from(self.tops_m[j * n + i]);
        let low = s(i, j) + a * (s(i + 1, j) - s(i, j));
        let high = s(i, j + 1) + a * (s(i + 1, j + 1) - s(i, j + 1));
        low + b * (high - low)
    }
}

/// Fills `tops` by the recurrence, columns (or rows) in order away from the sun.
fn sweep(grid: &GnomonicGrid, heights: &[f32], tops: &mut [f32], sun: DVec3, s: (f64, f64)) {
    let n = grid.size;
    // Swap the axes so that the sweep runs along i, the axis closer to the sun's azimuth.
    let along_x = s.0.abs() >= s.1.abs();
    let (major, minor) = if along_x { s } else { (s.1, s.0) };
    let step: isize = if major > 0.0 { 1 } else { -1 };
    let slide = minor / major.abs();
    let run_m = grid.cell_m * s.0.hypot(s.1) / major.abs();
    let index = |i: usize, j: usize| if along_x { j * n + i } else { i * n + j };
    let order: Vec<usize> = if step > 0 {
        (0..n).rev().collect()
    } else {
        (0..n).collect()
    };
    for &i in &order {
        let Some(i_sun) = i.checked_add_signed(step).filter(|&k| k < n) else {
            continue;
        };
        for j in 0..n {
            let j_sun = j as f64 + slide;
            if j_sun < 0.0 || j_sun > (n - 1) as f64 {
                continue;
            }
            let j0 = (j_sun.floor() as usize).min(n - 2);
            let w = j_sun - j0 as f64;
            let (t0, t1) = (
                f64::from(tops[index(i_sun, j0)]),
                f64::from(tops[index(i_sun, j0 + 1)]),
            );
            let upstream = t0 + w * (t1 - t0);
            let (x, y) = if along_x { (i, j) } else { (j, i) };
            let up = grid.direction(grid.cell_centre_m(x), grid.cell_centre_m(y));
            let sin_e = sun.dot(up);
            let tan_e = sin_e / (1.0 - sin_e * sin_e).sqrt().max(1e-12);
            let cast = upstream - run_m * tan_e;
            let k = index(i, j);
            tops[k] = f64::from(heights[k]).max(cast) as f32;
        }
    }
}

impl SunVisibility for ShadowMap {
    /// 1 at or above `S`, falling linearly to 0 at `band_m` below it; 1 outside the grid.
    /// The sun direction is the map's (the argument is not read).
    fn sun_visible(&self, point_m: DVec3, _sun: DVec3) -> f64 {
        let Some(p) = self.grid.locate(point_m) else {
            return 1.0;
        };
        let last = (self.grid.size - 1) as f64;
        if p.altitude_m >= f64::from(self.max_top_m)
            || !(0.0..=last).contains(&p.column)
            || !(0.0..=last).contains(&p.row)
        {
            return 1.0;
        }
        let top = self.top_at(p.column, p.row);
        ((p.altitude_m - top) / f64::from(self.band_m) + 1.0).clamp(0.0, 1.0)
    }
}
