//! Where the Sun is in the sky for a UTC date and time and a place on Earth.
//!
//! The equations are those of NOAA's solar calculator, which takes them from Jean Meeus,
//! *Astronomical Algorithms* (2nd edition, 1998); chapter and equation numbers below refer
//! to that book:
//!
//! 1. the Julian Day of the date (chapter 7, eq. 7.1) and the Julian centuries `T` since
//!    J2000.0 (eq. 25.1);
//! 2. the Sun's geometric mean longitude `L0` (eq. 25.2), mean anomaly `M` (eq. 25.3), the
//!    eccentricity of the Earth's orbit `e` (eq. 25.4), the equation of the centre `C`, the
//!    true longitude `L0 + C` and the apparent longitude `lambda`, corrected for nutation
//!    and aberration with the longitude of the Moon's node `Omega` (all chapter 25, "Solar
//!    coordinates", low accuracy);
//! 3. the mean obliquity of the ecliptic `epsilon0` (eq. 22.2) and the apparent one
//!    `epsilon0 + 0.00256 deg cos Omega` (eq. 25.8); the apparent right ascension
//!    (eq. 25.6) and declination (eq. 25.7);
//! 4. the equation of time from Smart's formula (eq. 28.3), the true solar time and the
//!    hour angle `H` (NOAA's form: `H = true solar time / 4 min per deg - 180 deg`);
//! 5. the zenith angle and azimuth from the hour angle, declination and latitude
//!    (chapter 13, eqs. 13.5 and 13.6), and optionally the atmospheric refraction of
//!    Saemundsson's formula (chapter 16, eq. 16.4) with Meeus's correction that makes it
//!    zero at the zenith.
//!
//! The accuracy of chapter 25's low-accuracy method is about 0.01 deg in the Sun's
//! position. The input is taken as UTC and used as Dynamical Time (TD = UT + Delta T,
//! Delta T about 69 s in 2024): the Sun moves about 0.0007 deg in 69 s, ten times less than
//! the method's error, so Delta T is left out as NOAA's calculator does.
//!
//! Conventions: latitude positive north, longitude positive east (both in degrees);
//! azimuth measured from north towards east (north 0, east 90 deg, south 180 deg, west
//! 270 deg), as NOAA's calculator gives it; Meeus's azimuth (eq. 13.5) is measured from
//! south towards west and equals this one minus 180 deg. The local frame is east-north-up
//! (ENU): x east, y north, z up. The planet-fixed frame (see
//! [`SunPosition::direction_planet`]) has x towards latitude 0, longitude 0, y towards
//! latitude 0, longitude 90 deg east and z towards the north pole.

pub mod calendar;
pub mod error;
pub mod position;
pub mod refraction;
pub mod solar_coordinates;
#[cfg(test)]
mod tests;

pub use calendar::{UtcDateTime, days_in_month, is_leap_year};
pub use error::SunPositionError;
pub use position::{GeoLocation, SunPosition};
pub use refraction::{Refraction, saemundsson_refraction_deg};
pub use solar_coordinates::SolarCoordinates;
