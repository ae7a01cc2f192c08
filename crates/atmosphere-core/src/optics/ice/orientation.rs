//! How crystals are oriented, as the direction of the incident light in the crystal's
//! frame: at random (every direction alike), or plates falling with their c-axis near
//! the vertical (Greenler 1980, chapter 2: sundogs), tilted by a Gaussian spread, turned
//! at random about the axis, and lit by the sun at an elevation.

use std::f64::consts::PI;

use glam::DVec3;
use thiserror::Error;

use crate::numerics::sampling::{Sampler, orthonormal_basis};

/// The range of the plates' tilt spread (standard deviation of each tilt component).
pub const TILT_SPREAD_RANGE_DEG: [f64; 2] = [0.0, 30.0];
/// The range of the sun's elevation for oriented plates: horizon to overhead.
pub const SUN_ELEVATION_RANGE_DEG: [f64; 2] = [0.0, 90.0];

#[derive(Clone, Debug, Error, PartialEq)]
#[error("{what} {value} deg is outside [{lo}, {hi}] deg")]
pub struct OrientationError {
    pub what: &'static str,
    pub value: f64,
    pub lo: f64,
    pub hi: f64,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Orientation {
    Random,
    /// The c-axis vertical within `tilt_spread_deg`; the phase function then depends on
    /// the sun's elevation, and the table gives it per scattering angle, averaged over
    /// the azimuth around the sun.
    HorizontalPlates {
        tilt_spread_deg: f64,
        sun_elevation_deg: f64,
    },
}

impl Orientation {
    pub fn horizontal_plates(
        tilt_spread_deg: f64,
        sun_elevation_deg: f64,
    ) -> Result<Orientation, OrientationError> {
        for (what, value, [lo, hi]) in [
            ("tilt spread", tilt_spread_deg, TILT_SPREAD_RANGE_DEG),
            ("sun elevation", sun_elevation_deg, SUN_ELEVATION_RANGE_DEG),
        ] {
            if !(lo..=hi).contains(&value) {
                return Err(OrientationError {
                    what,
                    value,
                    lo,
                    hi,
                });
            }
        }
        Ok(Orientation::HorizontalPlates {
            tilt_spread_deg,
            sun_elevation_deg,
        })
    }

    /// A direction of incident light in the crystal's frame.
    pub fn sample_incident(&self, sampler: &mut Sampler) -> DVec3 {
        match *self {
            Orientation::Random => {
                let z = 2.0 * sampler.uniform() - 1.0;
                let phi = 2.0 * PI * sampler.uniform();
                let s = (1.0 - z * z).max(0.0).sqrt();
                DVec3::new(s * phi.cos(), s * phi.sin(), z)
            }
            Orientation::HorizontalPlates {
                tilt_spread_deg,
                sun_elevation_deg,
            } => {
                let [a, b, axis] = plate_frame(tilt_spread_deg, sampler);
                // Light from the sun, travelling down and away from it.
                let e = sun_elevation_deg.to_radians();
                let d = DVec3::new(-e.cos(), 0.0, -e.sin());
                DVec3::new(d.dot(a), d.dot(b), d.dot(axis))
            }
        }
    }
}

/// The axes of a falling plate's frame in the sky's (z up): the c-axis vertical but for
/// two normal tilt components of standard deviation `tilt_spread_deg`, turned at random
/// about it; a direction's coordinates in the crystal are its dot products with them.
pub fn plate_frame(tilt_spread_deg: f64, sampler: &mut Sampler) -> [DVec3; 3] {
    let spread = tilt_spread_deg.to_radians();
    let (tx, ty) = gaussian_pair(sampler);
    let axis = DVec3::new(spread * tx, spread * ty, 1.0).normalize();
    let (e1, e2) = orthonormal_basis(axis);
    let turn = 2.0 * PI * sampler.uniform();
    let a = turn.cos() * e1 + turn.sin() * e2;
    [a, axis.cross(a), axis]
}

/// Two independent standard normal numbers (Box and Muller 1958).
fn gaussian_pair(sampler: &mut Sampler) -> (f64, f64) {
    let r = (-2.0 * (1.0 - sampler.uniform()).ln()).sqrt();
    let phi = 2.0 * PI * sampler.uniform();
    (r * phi.cos(), r * phi.sin())
}
