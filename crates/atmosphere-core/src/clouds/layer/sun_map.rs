//! The cloud layer's attenuation of the sun over the view's region, made once a frame:
//! Dobashi, Yamamoto and Nishita 2002, section 5.4, render from the sun the attenuation
//! ratio of sunlight at points of each cloud sphere into an attenuation texture G_i; here
//! the same ratio is stored as the optical depth towards the sun through the layer at
//! `levels` spheres of the shell, over a gnomonic grid (`shafts::GnomonicGrid`) on the
//! sphere of the layer's base centred under the camera.
//!
//! Texel (i, j, k) holds the optical depth from the point at radius
//! `R_k = R_base + k thickness / levels` in the grid direction of cell (i, j) to the
//! shell's boundary along the sun, by a midpoint march of `steps` equal steps through the
//! light's extinction (`CloudMedium::light_extinction`, `shadow_octaves` octaves of
//! noise); the top (k = levels) holds 0. A point below the base is carried along the sun
//! to the base sphere (every sun ray from below the base crosses it once, and beyond that
//! crossing the path is the texel's), then read on level 0; a point inside the shell is
//! read at its own direction, bilinearly in the grid and linearly in radius between the
//! levels around it; a point above the top, or off the grid, sees no cloud.

use glam::DVec3;

use super::field::CloudLayer;
use super::shell::Shell;
use crate::clouds::error::{CloudError, check_range};
use crate::clouds::medium::CloudMedium;
use crate::optics::geometry::distance_to_exit;
use crate::shafts::GnomonicGrid;

/// The map's resolution: cells per side, spheres of the shell, march steps per texel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunMapResolution {
    /// Cells per side of the grid, [16, 1024].
    pub cells: usize,
    /// Spheres of the shell with texels, from the base up, [1, 16].
    pub levels: usize,
    /// Midpoint steps of each texel's march towards the sun, [1, 256].
    pub steps: usize,
}

impl Default for SunMapResolution {
    fn default() -> Self {
        SunMapResolution {
            cells: 256,
            levels: 4,
            steps: 16,
        }
    }
}

impl SunMapResolution {
    /// The map of a frame whose layer is lit by it (`sun_light = map`): 16 levels, since
    /// the optical depth inside the layer is far from linear between 4 (the tests in
    /// `cloud_sun_light.rs`), with half the default's cells a side: as many samples.
    pub const LIT: SunMapResolution = SunMapResolution {
        cells: 64,
        levels: 16,
        steps: 8,
    };

    /// `Ok` when every field lies in its range, else an error naming it.
    pub fn check(&self) -> Result<(), CloudError> {
        check_range("sun map cells", self.cells as f64, 16.0, 1024.0)?;
        check_range("sun map levels", self.levels as f64, 1.0, 16.0)?;
        check_range("sun map steps", self.steps as f64, 1.0, 256.0)
    }
}

/// The half width of the map under a camera `altitude_m` above a planet of `radius_m`:
/// the camera's horizon, beyond which no ground is seen, and 20 km for the sun's slant
/// from a ground point to the cloud above it.
pub fn half_width_m(radius_m: f64, altitude_m: f64) -> f64 {
    (2.0 * radius_m * altitude_m.max(0.0)).sqrt() + 20_000.0
}

/// The optical depth from `point` towards the unit `sun` to the layer's shell boundary
/// (or from below the base, through the whole layer), by `steps` midpoint steps of the
/// light's extinction: the direct march the map is checked against.
pub fn optical_depth_to_sun(layer: &CloudLayer, point: DVec3, sun: DVec3, steps: usize) -> f64 {
    let shell = layer.shell();
    let r = point.length();
    if r >= shell.top_radius_m {
        return 0.0;
    }
    let start = if r < shell.base_radius_m {
        point + sun * base_crossing(point, sun, shell.base_radius_m)
    } else {
        point
    };
    let length = shell.exit_distance(start, sun);
    let ds = length / steps as f64;
    (0..steps)
        .map(|k| layer.light_extinction(start + sun * ((k as f64 + 0.5) * ds)) * ds)
        .sum()
}

/// From `point` inside the sphere of `radius` along the unit `sun`: the distance to where
/// the ray leaves it.
pub fn base_crossing(point: DVec3, sun: DVec3, radius: f64) -> f64 {
    let r = point.length();
    distance_to_exit(r, (point.dot(sun) / r).clamp(-1.0, 1.0), radius)
}

/// The map: the grid, the sun and the optical depths, level by level, row by row.
#[derive(Clone, Debug, PartialEq)]
pub struct CloudSunMap {
    pub grid: GnomonicGrid,
    pub sun: DVec3,
    pub base_radius_m: f64,
    pub top_radius_m: f64,
    pub levels: usize,
    /// Optical depth per texel: index `(k * cells + j) * cells + i`.
    pub depths: Vec<f32>,
}

impl CloudSunMap {
    /// The grid of the map for a camera at `camera_m` (planet-centred) over the layer's
    /// `shell`; an error names a resolution out of range or a camera at the planet's
    /// centre.
    pub fn grid_for(
        shell: &Shell,
        camera_m: DVec3,
        resolution: &SunMapResolution,
    ) -> Result<GnomonicGrid, CloudError> {
        resolution.check()?;
        let altitude = camera_m.length() - shell.ground_radius_m;
        let width = 2.0 * half_width_m(shell.ground_radius_m, altitude);
        GnomonicGrid::new(
            camera_m,
            shell.base_radius_m,
            width / resolution.cells as f64,
            resolution.cells,
        )
        .map_err(|e| CloudError(format!("sun map: {e}")))
    }

    /// The map of `layer` over `grid` for the unit sun direction `sun`.
    pub fn new(
        layer: &CloudLayer,
        grid: GnomonicGrid,
        sun: DVec3,
        resolution: &SunMapResolution,
    ) -> Result<CloudSunMap, CloudError> {
        resolution.check()?;
        let sun = sun
            .try_normalize()
            .ok_or_else(|| CloudError(format!("sun map: sun {sun} is not a direction")))?;
        let shell = layer.shell();
        let n = grid.size;
        let mut depths = Vec::with_capacity(n * n * resolution.levels);
        for k in 0..resolution.levels {
            let radius = level_radius(
                shell.base_radius_m,
                shell.top_radius_m,
                k,
                resolution.levels,
            );
            for j in 0..n {
                for i in 0..n {
                    let d = grid.direction(grid.cell_centre_m(i), grid.cell_centre_m(j));
                    let p = d * radius;
                    let length = shell.exit_distance(p, sun);
                    let ds = length / resolution.steps as f64;
                    let tau: f64 = (0..resolution.steps)
                        .map(|s| layer.light_extinction(p + sun * ((s as f64 + 0.5) * ds)) * ds)
                        .sum();
                    depths.push(tau as f32);
                }
            }
        }
        Ok(CloudSunMap {
            grid,
            sun,
            base_radius_m: shell.base_radius_m,
            top_radius_m: shell.top_radius_m,
            levels: resolution.levels,
            depths,
        })
    }

    /// The optical depth towards the map's sun from the planet-centred `point`; see the
    /// module documentation.
    pub fn optical_depth(&self, point: DVec3) -> f64 {
        let r = point.length();
        if r >= self.top_radius_m {
            return 0.0;
        }
        let (p, x) = if r <= self.base_radius_m {
            let t = base_crossing(point, self.sun, self.base_radius_m);
            (point + self.sun * t, 0.0)
        } else {
            let x = (r - self.base_radius_m) / (self.top_radius_m - self.base_radius_m);
            (point, x * self.levels as f64)
        };
        let Some(at) = self.grid.locate(p) else {
            return 0.0;
        };
        let last = (self.grid.size - 1) as f64;
        if !(0.0..=last).contains(&at.column) || !(0.0..=last).contains(&at.row) {
            return 0.0;
        }
        let k = (x.floor() as usize).min(self.levels - 1);
        let f = x - k as f64;
        let low = self.level_depth(k, at.column, at.row);
        let high = if k + 1 < self.levels {
            self.level_depth(k + 1, at.column, at.row)
        } else {
            0.0
        };
        low + f * (high - low)
    }

    /// The sun's transmittance through the cloud from `point`, exp(-optical depth).
    pub fn transmittance(&self, point: DVec3) -> f64 {
        (-self.optical_depth(point)).exp()
    }

    /// Level `k`'s depth at fractional cell coordinates inside the grid (bilinear).
    fn level_depth(&self, k: usize, column: f64, row: f64) -> f64 {
        let n = self.grid.size;
        let i = (column.floor() as usize).min(n - 2);
        let j = (row.floor() as usize).min(n - 2);
        let (a, b) = (column - i as f64, row - j as f64);
        let s = |i: usize, j: usize| f64::from(self.depths[(k * n + j) * n + i]);
        let low = s(i, j) + a * (s(i + 1, j) - s(i, j));
        let high = s(i, j + 1) + a * (s(i + 1, j + 1) - s(i, j + 1));
        low + b * (high - low)
    }
}

/// The radius of level `k` of `levels`, m.
pub fn level_radius(base_m: f64, top_m: f64, k: usize, levels: usize) -> f64 {
    base_m + (top_m - base_m) * k as f64 / levels as f64
}
