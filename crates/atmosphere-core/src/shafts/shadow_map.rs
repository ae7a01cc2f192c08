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
//!
//! Cascades: a map may sit inside an outer map of twice its cells on the same centre and
//! axes (and so on outwards), as cascaded shadow maps nest finer maps near the camera in
//! coarser ones. A point takes the finest map over it. A nested map's sweep starts from
//! the outer map's `S` where its upstream point lies beyond its own edge, so the shadows
//! of mountains outside it still enter it.

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
    /// The highest `S` of this map and the outer ones: no point above it is shadowed.
    pub max_top_m: f32,
    /// Width of the penumbra below `S` over which the visibility falls from 1 to 0, m:
    /// the rise of the sun's ray over one cell, between 1 m and one cell.
    pub band_m: f32,
    /// The tangent of the sun's elevation over the grid's centre (the band of a cell
    /// `c` wide is `c` times it, between 1 m and `c`).
    pub sun_slope: f64,
    /// Cells of this map and the outer ones whose air holds shadow (`S` above the
    /// relief): none, and the terrain casts no shadow into the air over the grids.
    pub shadowing_cells: usize,
    /// The map of twice the cells around this one, if any.
    pub outer: Option<Box<ShadowMap>>,
}

impl ShadowMap {
    /// The shadow of `heights` (per cell, row by row, m, as `GnomonicGrid::sample` gives
    /// them) for the sun direction `sun`; an error names a wrong count of heights, a
    /// height that is not finite or a sun that is not a direction.
    pub fn new(grid: GnomonicGrid, heights: &[f32], sun: DVec3) -> Result<ShadowMap, ModelError> {
        ShadowMap::swept(grid, heights, sun, None)
    }

    /// The shadow of `heights` over `grid` nested in `outer`, whose grid must have the
    /// same centre, axes and size and cells twice as wide; an error names what differs.
    pub fn nested(
        grid: GnomonicGrid,
        heights: &[f32],
        sun: DVec3,
        outer: ShadowMap,
    ) -> Result<ShadowMap, ModelError> {
        let o = &outer.grid;
        let nests = o.up == grid.up
            && o.east == grid.east
            && o.radius_m == grid.radius_m
            && o.size == grid.size
            && o.cell_m == 2.0 * grid.cell_m;
        if !nests {
            return Err(ModelError::Settings(format!(
                "shadow map: a {} m grid cannot nest in a {} m one of other centre, axes or size",
                grid.cell_m, o.cell_m
            )));
        }
        ShadowMap::swept(grid, heights, sun, Some(outer))
    }

    /// The maps from this one outwards.
    pub fn levels(&self) -> impl Iterator<Item = &ShadowMap> {
        std::iter::successors(Some(self), |m| m.outer.as_deref())
    }

    /// The width of the outermost grid, m: no point beyond it is shadowed.
    pub fn width_m(&self) -> f64 {
        self.outermost().cell_m * self.outermost().size as f64
    }

    /// The cell by which the view segments' samples are counted (two per cell): the
    /// outermost level's. The finer levels sharpen each sample's visibility near the
    /// camera; they do not add samples.
    pub fn sample_cell_m(&self) -> f64 {
        self.outermost().cell_m
    }

    fn outermost(&self) -> &GnomonicGrid {
        self.levels().last().map_or(&self.grid, |m| &m.grid)
    }

    fn swept(
        grid: GnomonicGrid,
        heights: &[f32],
        sun: DVec3,
        outer: Option<ShadowMap>,
    ) -> Result<ShadowMap, ModelError> {
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
            sweep(&grid, heights, &mut tops, sun, ((sx, sy), outer.as_ref()));
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
        let own_top_m = tops.iter().fold(f32::MIN, |m, &t| m.max(t));
        let max_top_m = outer
            .as_ref()
            .map_or(own_top_m, |o| o.max_top_m.max(own_top_m));
        Ok(ShadowMap {
            grid,
            tops_m: tops,
            max_top_m,
            band_m,
            sun_slope: centre_tan,
            shadowing_cells: shadowing_cells + outer.as_ref().map_or(0, |o| o.shadowing_cells),
            outer: outer.map(Box::new),
        })
    }

    /// `S` at the tangent-plane point `(x, y)` (m) when it lies inside the grid.
    fn top_at_m(&self, x_m: f64, y_m: f64) -> Option<f64> {
        let centre = 0.5 * self.grid.size as f64 - 0.5;
        let (column, row) = (
            x_m / self.grid.cell_m + centre,
            y_m / self.grid.cell_m + centre,
        );
        let last = (self.grid.size - 1) as f64;
        ((0.0..=last).contains(&column) && (0.0..=last).contains(&row))
            .then(|| self.top_at(column, row))
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

/// Fills `tops` by the recurrence, columns (or rows) in order away from the sun; an
/// upstream point beyond the grid takes `outer`'s `S`, or casts nothing without one.
fn sweep(
    grid: &GnomonicGrid,
    heights: &[f32],
    tops: &mut [f32],
    sun: DVec3,
    (s, outer): ((f64, f64), Option<&ShadowMap>),
) {
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
    // The outer map's S at the upstream point of cell (i, j), in the sweep's axes.
    let outer_upstream = |i: usize, j: usize| {
        let major_m = grid.cell_centre_m(i) + step as f64 * grid.cell_m;
        let minor_m = grid.cell_centre_m(j) + slide * grid.cell_m;
        let (x, y) = if along_x {
            (major_m, minor_m)
        } else {
            (minor_m, major_m)
        };
        outer.and_then(|o| o.top_at_m(x, y))
    };
    for &i in &order {
        let i_sun = i.checked_add_signed(step).filter(|&k| k < n);
        for j in 0..n {
            let j_sun = j as f64 + slide;
            let upstream = match i_sun {
                Some(i_sun) if (0.0..=(n - 1) as f64).contains(&j_sun) => {
                    let j0 = (j_sun.floor() as usize).min(n - 2);
                    let w = j_sun - j0 as f64;
                    let (t0, t1) = (
                        f64::from(tops[index(i_sun, j0)]),
                        f64::from(tops[index(i_sun, j0 + 1)]),
                    );
                    t0 + w * (t1 - t0)
                }
                _ => match outer_upstream(i, j) {
                    Some(top) => top,
                    None => continue,
                },
            };
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
    /// 1 at or above `S`, falling linearly to 0 at `band_m` below it, from the finest map
    /// over the point; 1 outside every grid. The sun direction is the map's (the
    /// argument is not read).
    fn sun_visible(&self, point_m: DVec3, _sun: DVec3) -> f64 {
        for map in self.levels() {
            let Some(p) = map.grid.locate(point_m) else {
                return 1.0;
            };
            if p.altitude_m >= f64::from(self.max_top_m) {
                return 1.0;
            }
            let last = (map.grid.size - 1) as f64;
            if (0.0..=last).contains(&p.column) && (0.0..=last).contains(&p.row) {
                let top = map.top_at(p.column, p.row);
                return ((p.altitude_m - top) / f64::from(map.band_m) + 1.0).clamp(0.0, 1.0);
            }
        }
        1.0
    }
}
