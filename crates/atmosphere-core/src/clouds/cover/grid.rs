//! A cloud cover sampled on an equirectangular grid (`geo::equirectangular`'s layout: north
//! up, the first column at 180 W), read back bilinearly: what the GPU's cover texture
//! holds and what its CPU twin samples. A grid comes from a generated cover or from the
//! values of an image's channel.

use glam::DVec3;
use rayon::prelude::*;

use crate::clouds::error::CloudError;
use crate::geo::equirectangular::{bilinear_taps, direction, lat_lon, texel_centre};

/// The most texels along a grid's width (a 16384 x 8192 grid is 512 MiB of f32).
pub const MAX_WIDTH: usize = 16_384;

/// Cover on an equirectangular grid, row-major, the first row at the north pole.
#[derive(Clone, Debug, PartialEq)]
pub struct CoverGrid {
    width: usize,
    height: usize,
    values: Vec<f32>,
}

impl CoverGrid {
    /// A grid from its values; `what` names their source in errors (a file, a channel).
    pub fn from_values(
        what: &str,
        width: usize,
        height: usize,
        values: Vec<f32>,
    ) -> Result<Self, CloudError> {
        check_size(what, width, height)?;
        if values.len() != width * height {
            return Err(CloudError(format!(
                "{what}: {} values for a {width} x {height} grid",
                values.len()
            )));
        }
        if let Some((k, v)) = values
            .iter()
            .enumerate()
            .find(|(_, v)| !(v.is_finite() && (0.0..=1.0).contains(*v)))
        {
            return Err(CloudError(format!(
                "{what}: cover {v} at texel ({}, {}) must lie in [0, 1]",
                k % width,
                k / width
            )));
        }
        Ok(CoverGrid {
            width,
            height,
            values,
        })
    }

    /// The grid of `cover` at the texel centres.
    pub fn rasterize(
        width: usize,
        height: usize,
        cover: impl Fn(DVec3) -> f64 + Sync,
    ) -> Result<Self, CloudError> {
        check_size("cover grid", width, height)?;
        let values = (0..width * height)
            .into_par_iter()
            .map(|k| {
                let (lat, lon) = texel_centre(width, height, k % width, k / width);
                cover(direction(lat, lon)).clamp(0.0, 1.0) as f32
            })
            .collect();
        Ok(CoverGrid {
            width,
            height,
            values,
        })
    }

    pub fn width(&self) -> usize {
        self.width
    }

    pub fn height(&self) -> usize {
        self.height
    }

    /// The texels, row-major, north first.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// Bilinear cover at a planet-fixed direction (need not be unit).
    pub fn sample(&self, point: DVec3) -> f64 {
        let (lat, lon) = lat_lon(point);
        bilinear_taps(self.width, self.height, lat, lon)
            .iter()
            .map(|&(k, w)| w * f64::from(self.values[k]))
            .sum()
    }
}

fn check_size(what: &str, width: usize, height: usize) -> Result<(), CloudError> {
    if width < 2 || height < 1 || width > MAX_WIDTH || height > MAX_WIDTH / 2 {
        return Err(CloudError(format!(
            "{what}: a {width} x {height} grid; cover grids are 2 to {MAX_WIDTH} texels wide \
             and 1 to {} high",
            MAX_WIDTH / 2
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texel_centres_read_back_and_the_date_line_wraps() {
        let grid = CoverGrid::rasterize(36, 18, |p| 0.5 + 0.5 * p.y).unwrap();
        let (lat, lon) = texel_centre(36, 18, 7, 4);
        let at = grid.sample(direction(lat, lon));
        assert!((at - grid.values()[4 * 36 + 7] as f64).abs() < 1e-6);
        // Either side of 180 degrees the same value: the grid wraps there.
        let east = grid.sample(direction(0.2, std::f64::consts::PI - 1e-9));
        let west = grid.sample(direction(0.2, -std::f64::consts::PI + 1e-9));
        assert!((east - west).abs() < 1e-6);
    }

    #[test]
    fn bad_grids_are_refused_by_name() {
        let e = CoverGrid::from_values("clouds.png alpha", 4, 2, vec![0.5; 7]).unwrap_err();
        assert!(
            e.0.contains("clouds.png alpha: 7 values for a 4 x 2 grid"),
            "{e}"
        );
        let mut values = vec![0.5; 8];
        values[5] = 1.5;
        let e = CoverGrid::from_values("x", 4, 2, values).unwrap_err();
        assert!(e.0.contains("cover 1.5 at texel (1, 1)"), "{e}");
        assert!(CoverGrid::from_values("x", 1, 1, vec![0.5]).is_err());
        assert!(CoverGrid::rasterize(40_000, 10, |_| 0.0).is_err());
    }
}
