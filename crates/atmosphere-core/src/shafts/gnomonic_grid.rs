//! A square grid on the plane tangent to the planet under the view, reached by the
//! gnomonic (central) projection: a direction `d` maps to
//! `(x, y) = R (d . east, d . north) / (d . up)`, so great circles are straight lines and
//! a point's cell follows from two dot products of its position (no trigonometry), the
//! same on the GPU from camera-relative positions: `p . e = c . e + (p - c) . e`.

use glam::DVec3;

use crate::models::error::ModelError;

/// Cells per side a grid may have.
pub const GRID_SIZE_RANGE: std::ops::RangeInclusive<usize> = 2..=8192;

/// The grid: `size` x `size` cells of `cell_m`, centred on `up`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GnomonicGrid {
    /// Unit planet-fixed direction of the grid's centre.
    pub up: DVec3,
    /// Unit tangent directions of the grid's x and y axes.
    pub east: DVec3,
    pub north: DVec3,
    /// Radius of the reference sphere, m.
    pub radius_m: f64,
    /// Side of a cell on the tangent plane, m.
    pub cell_m: f64,
    /// Cells per side.
    pub size: usize,
}

/// Where a point lies over the grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridPoint {
    /// Fractional cell coordinates: cell `i`'s centre is at `i`.
    pub column: f64,
    pub row: f64,
    /// Height above the reference sphere, m.
    pub altitude_m: f64,
}

impl GnomonicGrid {
    /// The grid of `size` cells of `cell_m` centred on the direction `centre` over a
    /// sphere of `radius_m`; an error names a value out of its range.
    pub fn new(
        centre: DVec3,
        radius_m: f64,
        cell_m: f64,
        size: usize,
    ) -> Result<GnomonicGrid, ModelError> {
        let bad = |what: String| Err(ModelError::Settings(format!("shadow grid: {what}")));
        let Some(up) = centre.try_normalize() else {
            return bad(format!("centre {centre} is not a direction"));
        };
        if !(radius_m.is_finite() && radius_m > 0.0) {
            return bad(format!("radius_m {radius_m} must be finite and > 0"));
        }
        if !(cell_m.is_finite() && cell_m > 0.0) {
            return bad(format!("cell_m {cell_m} must be finite and > 0"));
        }
        if !GRID_SIZE_RANGE.contains(&size) {
            return bad(format!("size {size} outside {GRID_SIZE_RANGE:?}"));
        }
        let east = DVec3::Z
            .cross(up)
            .try_normalize()
            .unwrap_or_else(|| DVec3::X.cross(up).normalize());
        Ok(GnomonicGrid {
            up,
            east,
            north: up.cross(east),
            radius_m,
            cell_m,
            size,
        })
    }

    /// The tangent-plane coordinate of cell `i`'s centre, m.
    pub fn cell_centre_m(&self, i: usize) -> f64 {
        (i as f64 + 0.5 - 0.5 * self.size as f64) * self.cell_m
    }

    /// The unit direction of the tangent-plane point `(x, y)`, m.
    pub fn direction(&self, x_m: f64, y_m: f64) -> DVec3 {
        (self.up + x_m / self.radius_m * self.east + y_m / self.radius_m * self.north).normalize()
    }

    /// The point `point_m` (planet-centred) over the grid; `None` on the far hemisphere.
    pub fn locate(&self, point_m: DVec3) -> Option<GridPoint> {
        let along_up = point_m.dot(self.up);
        if along_up <= 0.0 {
            return None;
        }
        let scale = self.radius_m / along_up / self.cell_m;
        let centre = 0.5 * self.size as f64 - 0.5;
        Some(GridPoint {
            column: point_m.dot(self.east) * scale + centre,
            row: point_m.dot(self.north) * scale + centre,
            altitude_m: point_m.length() - self.radius_m,
        })
    }

    /// The relief's elevation at every cell's centre, row by row, m.
    pub fn sample(&self, elevation_m: impl Fn(DVec3) -> f64) -> Vec<f32> {
        let mut heights = Vec::with_capacity(self.size * self.size);
        for j in 0..self.size {
            for i in 0..self.size {
                let d = self.direction(self.cell_centre_m(i), self.cell_centre_m(j));
                heights.push(elevation_m(d) as f32);
            }
        }
        heights
    }
}
