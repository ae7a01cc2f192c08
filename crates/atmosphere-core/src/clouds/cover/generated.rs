//! A global cloud cover generated deterministically from a seed, with the structure of
//! real weather: the zonal means of the satellite climatologies (`climatology.rs`), the
//! convective clusters of the tropics, the comma clouds of the mid-latitude storm tracks
//! (`cyclones.rs`), and cloud fields broken into cells and gaps at every scale between.
//!
//! A structure field `s` is summed from domain-warped fractal noise (fronts and sheets at
//! a thousand kilometres down to a few tens), cellular noise weighted to the tropics and
//! the cyclones weighted to the storm tracks. The cover is a soft threshold of `s`:
//! `smoothstep(tau - w, tau + w, s)`, with `tau(latitude)` the quantile of `s` on that
//! latitude circle above which a fraction equal to the zonal mean cover lies, measured
//! once when the cover is made. So the zonal means are the climatology's and the pattern
//! is the noise's; the same seed and day give the same cover on every machine.

use std::f64::consts::FRAC_PI_2;

use glam::DVec3;

use super::climatology::{itcz_latitude_deg, zonal_mean_cover};
use super::cyclones::Cyclones;
use crate::clouds::error::{CloudError, check_range};
use crate::geo::equirectangular::{direction, lat_lon};
use crate::numerics::cellular_noise::cellular_distance;
use crate::numerics::gradient_noise::{derived_seed, fractal_noise};

/// Latitude circles on which the threshold is measured (1 degree apart).
const CALIBRATION_BANDS: usize = 181;
/// Points per latitude circle for the threshold's quantile.
const CALIBRATION_POINTS: usize = 1024;
/// Half-width of the soft threshold, in units of the structure field.
const EDGE_HALF_WIDTH: f64 = 0.14;

/// What a generated cover is made from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoverParameters {
    /// Any seed: each gives another weather map.
    pub seed: u32,
    /// Day of the year (1 to 366): moves the convergence zone with the sun.
    pub day_of_year: f64,
}

impl Default for CoverParameters {
    fn default() -> Self {
        CoverParameters {
            seed: 1,
            day_of_year: 172.0,
        }
    }
}

/// The generated cover, ready to evaluate anywhere.
#[derive(Clone, Debug)]
pub struct GeneratedCover {
    parameters: CoverParameters,
    cyclones: Cyclones,
    /// The threshold on each calibration circle, south pole first.
    thresholds: Vec<f64>,
}

impl GeneratedCover {
    pub fn new(parameters: CoverParameters) -> Result<Self, CloudError> {
        check_range("cover day_of_year", parameters.day_of_year, 1.0, 366.0)?;
        let mut cover = GeneratedCover {
            parameters,
            cyclones: Cyclones::new(parameters.seed),
            thresholds: Vec::new(),
        };
        cover.thresholds = (0..CALIBRATION_BANDS)
            .map(|band| cover.calibrate(band_latitude_deg(band)))
            .collect();
        Ok(cover)
    }

    pub fn parameters(&self) -> CoverParameters {
        self.parameters
    }

    /// The threshold on the latitude circle `lat_deg`: the `1 - zonal mean` quantile of
    /// the structure field there.
    fn calibrate(&self, lat_deg: f64) -> f64 {
        let target = zonal_mean_cover(lat_deg, self.parameters.day_of_year);
        // A small latitude just off the pole keeps a circle of distinct points.
        let lat = lat_deg.clamp(-89.9, 89.9).to_radians();
        let mut values: Vec<f64> = (0..CALIBRATION_POINTS)
            .map(|k| {
                let lon = (k as f64 + 0.5) / CALIBRATION_POINTS as f64 * std::f64::consts::TAU;
                self.structure(direction(lat, lon))
            })
            .collect();
        values.sort_by(f64::total_cmp);
        let rank = ((1.0 - target) * CALIBRATION_POINTS as f64)
            .clamp(0.0, (CALIBRATION_POINTS - 1) as f64);
        values[rank as usize]
    }

    /// The structure field at a unit direction: larger where cloud is likelier.
    fn structure(&self, point: DVec3) -> f64 {
        let seed = self.parameters.seed;
        let lat_deg = point.z.clamp(-1.0, 1.0).asin().to_degrees();
        // Domain warp: large-scale flow bends the fronts and sheets.
        let warp = DVec3::new(
            fractal_noise(derived_seed(seed, 1), point * 2.0, 3, 0.5),
            fractal_noise(derived_seed(seed, 2), point * 2.0, 3, 0.5),
            fractal_noise(derived_seed(seed, 3), point * 2.0, 3, 0.5),
        );
        // The westerlies and trades stretch cloud along the circles of latitude.
        let zonal = DVec3::new(point.x, point.y, point.z * 1.8);
        let sheets = fractal_noise(derived_seed(seed, 4), zonal * 3.0 + warp * 0.9, 8, 0.6);
        // Convective clusters a few hundred kilometres across, strongest in the
        // convergence zone and fading into the subtropics.
        let itcz = itcz_latitude_deg(self.parameters.day_of_year);
        let tropics = (-0.5 * ((lat_deg - itcz) / 14.0).powi(2)).exp();
        let cells = 0.5 - cellular_distance(derived_seed(seed, 5), point * 24.0 + warp * 0.5);
        // The storm tracks' lows.
        let storms = self.cyclones.cloudiness(point);
        sheets + 0.35 * tropics * cells + storms
    }

    /// Cloud cover (0 to 1) in the planet-fixed unit direction `point`.
    pub fn cover(&self, point: DVec3) -> f64 {
        let (lat, _) = lat_lon(point);
        let tau = self.threshold(lat);
        let s = self.structure(point.normalize());
        let t = ((s - tau + EDGE_HALF_WIDTH) / (2.0 * EDGE_HALF_WIDTH)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    }

    /// The threshold at latitude `lat` (radians), linear between calibration circles.
    fn threshold(&self, lat: f64) -> f64 {
        let x = (lat + FRAC_PI_2).to_degrees().clamp(0.0, 180.0);
        let i = (x.floor() as usize).min(CALIBRATION_BANDS - 2);
        let f = x - i as f64;
        self.thresholds[i] * (1.0 - f) + self.thresholds[i + 1] * f
    }
}

fn band_latitude_deg(band: usize) -> f64 {
    -90.0 + band as f64
}
