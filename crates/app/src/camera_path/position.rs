//! The camera's place between keyframes: the direction from the planet's centre by a
//! monotone cubic per component, normalised back onto the sphere, and the altitude by a
//! monotone cubic through `ln(altitude - base + 1 m)` (`base`: the path's
//! `log_altitude_base_m`, the ground under a climb that starts on a mountain), so a climb
//! from the ground to orbit spends as long on each factor of ten and never dips or leaps
//! between keyframes.

use glam::DVec3;

use crate::camera_path::spline::{hermite, slopes};

/// Added to altitudes before their logarithm, m: the ground itself stays finite.
pub const LOG_OFFSET_M: f64 = 1.0;

/// The logarithmic altitude of the interpolation above `base_m`.
pub fn log_altitude(altitude_m: f64, base_m: f64) -> f64 {
    (altitude_m - base_m + LOG_OFFSET_M).ln()
}

/// The altitude of a logarithmic altitude above `base_m`.
pub fn altitude_of_log(log_altitude: f64, base_m: f64) -> f64 {
    (log_altitude.exp() - LOG_OFFSET_M + base_m)
        .max(base_m)
        .max(0.0)
}

/// The place splines through every keyframe.
#[derive(Clone, Debug)]
pub struct PositionSpline {
    times: Vec<f64>,
    ups: Vec<DVec3>,
    up_slopes: [Vec<f64>; 3],
    logs: Vec<f64>,
    log_slopes: Vec<f64>,
    base_m: f64,
}

impl PositionSpline {
    /// The splines through `(times[i], ups[i], altitudes[i])`; times strictly increasing,
    /// altitudes at least `base_m`.
    pub fn new(times: &[f64], ups: &[DVec3], altitudes_m: &[f64], base_m: f64) -> PositionSpline {
        let component = |k: usize| slopes(times, &ups.iter().map(|u| u[k]).collect::<Vec<_>>());
        let logs: Vec<f64> = altitudes_m
            .iter()
            .map(|&a| log_altitude(a, base_m))
            .collect();
        PositionSpline {
            times: times.to_vec(),
            ups: ups.to_vec(),
            up_slopes: [component(0), component(1), component(2)],
            log_slopes: slopes(times, &logs),
            logs,
            base_m,
        }
    }

    /// The unit up vector and the altitude at fraction `h` of segment `i` (from keyframe
    /// `i` to `i + 1`); `None` where the direction passes through the planet's centre.
    pub fn at(&self, i: usize, h: f64) -> Option<(DVec3, f64)> {
        let dt = self.times[i + 1] - self.times[i];
        let mut up = DVec3::ZERO;
        for k in 0..3 {
            let m = &self.up_slopes[k];
            up[k] = hermite(self.ups[i][k], self.ups[i + 1][k], m[i], m[i + 1], dt, h);
        }
        let log = hermite(
            self.logs[i],
            self.logs[i + 1],
            self.log_slopes[i],
            self.log_slopes[i + 1],
            dt,
            h,
        );
        Some((up.try_normalize()?, altitude_of_log(log, self.base_m)))
    }
}
