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

use glam::DVec3;
use thiserror::Error;

/// An input outside its range; the message names the field.
#[derive(Debug, Error, PartialEq)]
pub enum SunPositionError {
    #[error("invalid {field}: {value} (expected {expected})")]
    Invalid {
        field: &'static str,
        value: f64,
        expected: String,
    },
}

/// A date and time in Coordinated Universal Time, Gregorian calendar.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UtcDateTime {
    /// From 1583 (the first whole Gregorian year) to 9999.
    pub year: i32,
    /// 1 to 12.
    pub month: u32,
    /// 1 to the month's length (29 February in leap years).
    pub day: u32,
    /// 0 to 23.
    pub hour: u32,
    /// 0 to 59.
    pub minute: u32,
    /// 0 to less than 61 (a leap second is 60.x).
    pub second: f64,
}

impl UtcDateTime {
    /// A checked date and time: each field out of range is an error naming it.
    pub fn new(
        year: i32,
        month: u32,
        day: u32,
        hour: u32,
        minute: u32,
        second: f64,
    ) -> Result<UtcDateTime, SunPositionError> {
        let t = UtcDateTime {
            year,
            month,
            day,
            hour,
            minute,
            second,
        };
        t.validate()?;
        Ok(t)
    }

    /// Checks every field; the error names the first one out of range.
    pub fn validate(&self) -> Result<(), SunPositionError> {
        let invalid = |field, value: f64, expected: String| {
            Err(SunPositionError::Invalid {
                field,
                value,
                expected,
            })
        };
        if !(1583..=9999).contains(&self.year) {
            return invalid("year", self.year as f64, "1583 to 9999".into());
        }
        if !(1..=12).contains(&self.month) {
            return invalid("month", self.month as f64, "1 to 12".into());
        }
        let days = days_in_month(self.year, self.month);
        if !(1..=days).contains(&self.day) {
            return invalid("day", self.day as f64, format!("1 to {days}"));
        }
        if self.hour > 23 {
            return invalid("hour", self.hour as f64, "0 to 23".into());
        }
        if self.minute > 59 {
            return invalid("minute", self.minute as f64, "0 to 59".into());
        }
        if !(0.0..61.0).contains(&self.second) {
            return invalid("second", self.second, "0 to less than 61".into());
        }
        Ok(())
    }

    /// The day's fraction elapsed, 0 at midnight.
    pub fn day_fraction(&self) -> f64 {
        (self.hour as f64 * 3600.0 + self.minute as f64 * 60.0 + self.second) / 86_400.0
    }

    /// The Julian Day (Meeus eq. 7.1, Gregorian calendar: `B = 2 - A + INT(A / 4)` with
    /// `A = INT(Y / 100)`, January and February counted as months 13 and 14 of the year
    /// before).
    pub fn julian_day(&self) -> f64 {
        let (y, m) = if self.month <= 2 {
            (self.year - 1, self.month + 12)
        } else {
            (self.year, self.month)
        };
        let a = y.div_euclid(100);
        let b = 2 - a + a.div_euclid(4);
        (365.25 * (y + 4716) as f64).floor()
            + (30.6001 * (m + 1) as f64).floor()
            + self.day as f64
            + self.day_fraction()
            + b as f64
            - 1524.5
    }
}

/// Whether `year` is a Gregorian leap year.
pub fn is_leap_year(year: i32) -> bool {
    (year % 4 == 0 && year % 100 != 0) || year % 400 == 0
}

/// The number of days of a month (1 to 12) of the Gregorian calendar.
pub fn days_in_month(year: i32, month: u32) -> u32 {
    match month {
        2 if is_leap_year(year) => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

/// A place on Earth: geodetic latitude and longitude in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeoLocation {
    /// -90 (south pole) to 90 (north pole).
    pub latitude_deg: f64,
    /// -180 to 180, positive east of Greenwich.
    pub longitude_deg: f64,
}

impl GeoLocation {
    /// A checked location: a field out of range (or not finite) is an error naming it.
    pub fn new(latitude_deg: f64, longitude_deg: f64) -> Result<GeoLocation, SunPositionError> {
        let location = GeoLocation {
            latitude_deg,
            longitude_deg,
        };
        location.validate()?;
        Ok(location)
    }

    /// Checks both fields; the error names the one out of range.
    pub fn validate(&self) -> Result<(), SunPositionError> {
        if !(-90.0..=90.0).contains(&self.latitude_deg) {
            return Err(SunPositionError::Invalid {
                field: "latitude",
                value: self.latitude_deg,
                expected: "-90 to 90 degrees".into(),
            });
        }
        if !(-180.0..=180.0).contains(&self.longitude_deg) {
            return Err(SunPositionError::Invalid {
                field: "longitude",
                value: self.longitude_deg,
                expected: "-180 to 180 degrees (east positive)".into(),
            });
        }
        Ok(())
    }
}

/// Whether the zenith angle includes atmospheric refraction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refraction {
    /// The geometric (true) position.
    None,
    /// The apparent position, raised by Saemundsson's refraction (Meeus eq. 16.4) at
    /// 1010 hPa and 10 deg C.
    Saemundsson,
}

/// The Sun's coordinates on the celestial sphere at an instant (Meeus chapters 22, 25 and
/// 28); independent of the observer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolarCoordinates {
    /// Julian centuries of 36525 days since J2000.0 (Meeus eq. 25.1).
    pub julian_centuries: f64,
    /// Geometric mean longitude `L0` referred to the mean equinox of the date, degrees in
    /// [0, 360) (eq. 25.2).
    pub mean_longitude_deg: f64,
    /// Mean anomaly `M`, degrees in [0, 360) (eq. 25.3).
    pub mean_anomaly_deg: f64,
    /// Eccentricity `e` of the Earth's orbit (eq. 25.4).
    pub eccentricity: f64,
    /// Equation of the centre `C`, degrees (chapter 25).
    pub equation_of_centre_deg: f64,
    /// True geometric longitude `L0 + C`, degrees.
    pub true_longitude_deg: f64,
    /// Apparent longitude `lambda = L0 + C - 0.00569 - 0.00478 sin Omega`, degrees.
    pub apparent_longitude_deg: f64,
    /// Mean obliquity of the ecliptic `epsilon0`, degrees (eq. 22.2).
    pub mean_obliquity_deg: f64,
    /// Apparent obliquity `epsilon0 + 0.00256 cos Omega`, degrees (eq. 25.8).
    pub apparent_obliquity_deg: f64,
    /// Apparent right ascension, degrees in [0, 360) (eq. 25.6).
    pub right_ascension_deg: f64,
    /// Apparent declination, degrees (eq. 25.7).
    pub declination_deg: f64,
    /// Equation of time, apparent minus mean solar time, minutes (Smart, eq. 28.3).
    pub equation_of_time_min: f64,
}

impl SolarCoordinates {
    /// The Sun's coordinates at Julian Day `jd` (taken as Julian Ephemeris Day).
    pub fn at_julian_day(jd: f64) -> SolarCoordinates {
        // Eq. 25.1.
        let t = (jd - 2_451_545.0) / 36_525.0;
        // Eqs. 25.2-25.4.
        let l0 = (280.46646 + t * (36000.76983 + t * 0.000_303_2)).rem_euclid(360.0);
        let m = (357.52911 + t * (35999.05029 - t * 0.000_153_7)).rem_euclid(360.0);
        let e = 0.016_708_634 - t * (0.000_042_037 + t * 0.000_000_126_7);
        let m_rad = m.to_radians();
        // The equation of the centre (chapter 25, after eq. 25.4).
        let c = (1.914_602 - t * (0.004_817 + t * 0.000_014)) * m_rad.sin()
            + (0.019_993 - t * 0.000_101) * (2.0 * m_rad).sin()
            + 0.000_289 * (3.0 * m_rad).sin();
        let true_longitude = l0 + c;
        // Nutation and aberration through the longitude of the Moon's ascending node.
        let omega = (125.04 - 1934.136 * t).to_radians();
        let lambda = true_longitude - 0.00569 - 0.00478 * omega.sin();
        // Eq. 22.2, arc seconds to degrees.
        let epsilon0 =
            23.0 + (26.0 + (21.448 - t * (46.8150 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
        // Eq. 25.8.
        let epsilon = epsilon0 + 0.00256 * omega.cos();
        let (lambda_rad, epsilon_rad) = (lambda.to_radians(), epsilon.to_radians());
        // Eqs. 25.6 and 25.7.
        let alpha = (epsilon_rad.cos() * lambda_rad.sin())
            .atan2(lambda_rad.cos())
            .to_degrees()
            .rem_euclid(360.0);
        let delta = (epsilon_rad.sin() * lambda_rad.sin()).asin().to_degrees();
        // Eq. 28.3 (Smart): E in radians, with y = tan^2(epsilon / 2) of the apparent
        // obliquity as NOAA's calculator takes it (the mean one changes E by under 0.02 s
        // in Example 28.b). 1 rad of hour angle is 720 / pi minutes.
        let y = (epsilon_rad / 2.0).tan().powi(2);
        let l0_rad = l0.to_radians();
        let eot_rad = y * (2.0 * l0_rad).sin() - 2.0 * e * m_rad.sin()
            + 4.0 * e * y * m_rad.sin() * (2.0 * l0_rad).cos()
            - 0.5 * y * y * (4.0 * l0_rad).sin()
            - 1.25 * e * e * (2.0 * m_rad).sin();
        SolarCoordinates {
            julian_centuries: t,
            mean_longitude_deg: l0,
            mean_anomaly_deg: m,
            eccentricity: e,
            equation_of_centre_deg: c,
            true_longitude_deg: true_longitude,
            apparent_longitude_deg: lambda,
            mean_obliquity_deg: epsilon0,
            apparent_obliquity_deg: epsilon,
            right_ascension_deg: alpha,
            declination_deg: delta,
            equation_of_time_min: eot_rad * 720.0 / std::f64::consts::PI,
        }
    }
}

/// The Sun as seen from a place at an instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunPosition {
    /// The Sun's celestial coordinates at the instant.
    pub coordinates: SolarCoordinates,
    /// Local hour angle, degrees in [-180, 180): negative before local solar noon.
    pub hour_angle_deg: f64,
    /// Greenwich hour angle (the hour angle at longitude 0), degrees in [-180, 180).
    pub greenwich_hour_angle_deg: f64,
    /// Angle from the zenith, degrees in [0, 180]; apparent when refraction is applied.
    pub zenith_deg: f64,
    /// Azimuth from north towards east, degrees in [0, 360).
    pub azimuth_deg: f64,
    /// The refraction added to the elevation, degrees (0 without refraction).
    pub refraction_deg: f64,
}

impl SunPosition {
    /// The Sun's position at `time` seen from `location`. Both are validated first.
    pub fn compute(
        time: &UtcDateTime,
        location: &GeoLocation,
        refraction: Refraction,
    ) -> Result<SunPosition, SunPositionError> {
        time.validate()?;
        location.validate()?;
        let coordinates = SolarCoordinates::at_julian_day(time.julian_day());
        // NOAA: true solar time in minutes = UTC minutes + equation of time + 4 min per
        // degree of longitude east; the hour angle is 0 at true solar noon.
        let utc_min = time.day_fraction() * 1440.0;
        let greenwich_hour_angle_deg =
            wrap_180((utc_min + coordinates.equation_of_time_min) / 4.0 - 180.0);
        let hour_angle_deg = wrap_180(greenwich_hour_angle_deg + location.longitude_deg);

        let (phi, h, delta) = (
            location.latitude_deg.to_radians(),
            hour_angle_deg.to_radians(),
            coordinates.declination_deg.to_radians(),
        );
        // Meeus eq. 13.6: sin(elevation) = sin phi sin delta + cos phi cos delta cos H.
        let cos_zenith =
            (phi.sin() * delta.sin() + phi.cos() * delta.cos() * h.cos()).clamp(-1.0, 1.0);
        let true_elevation_deg = 90.0 - cos_zenith.acos().to_degrees();
        // Meeus eq. 13.5 measures from south towards west:
        // tan A_s = sin H / (cos H sin phi - tan delta cos phi). From north towards east,
        // A = A_s + 180 deg; written with cos delta so the poles of declination are safe.
        let south_west = (h.sin() * delta.cos())
            .atan2(h.cos() * phi.sin() * delta.cos() - delta.sin() * phi.cos());
        let azimuth_deg = (south_west.to_degrees() + 180.0).rem_euclid(360.0);
        let refraction_deg = match refraction {
            Refraction::None => 0.0,
            Refraction::Saemundsson => saemundsson_refraction_deg(true_elevation_deg),
        };
        Ok(SunPosition {
            coordinates,
            hour_angle_deg,
            greenwich_hour_angle_deg,
            zenith_deg: (90.0 - true_elevation_deg - refraction_deg).clamp(0.0, 180.0),
            azimuth_deg,
            refraction_deg,
        })
    }

    /// Elevation above the horizon, degrees (`90 - zenith`).
    pub fn elevation_deg(&self) -> f64 {
        90.0 - self.zenith_deg
    }

    /// Unit vector towards the Sun in the local east-north-up frame:
    /// `(sin z sin A, sin z cos A, cos z)` with zenith `z` and azimuth `A`.
    pub fn direction_enu(&self) -> DVec3 {
        let (z, a) = (self.zenith_deg.to_radians(), self.azimuth_deg.to_radians());
        DVec3::new(z.sin() * a.sin(), z.sin() * a.cos(), z.cos())
    }

    /// Unit vector towards the Sun in the planet-fixed frame (x to latitude 0 longitude 0,
    /// y to latitude 0 longitude 90 E, z to the north pole), from the declination and
    /// Greenwich hour angle: the sub-solar point is at latitude `delta`, longitude
    /// `-GHA`. Geometric (no refraction, which depends on the observer); the Earth's radius
    /// against the Sun's distance (parallax, 8.8") is neglected.
    pub fn direction_planet(&self) -> DVec3 {
        let delta = self.coordinates.declination_deg.to_radians();
        let lon = (-self.greenwich_hour_angle_deg).to_radians();
        DVec3::new(
            delta.cos() * lon.cos(),
            delta.cos() * lon.sin(),
            delta.sin(),
        )
    }
}

/// Saemundsson's refraction (Meeus eq. 16.4) in degrees for a true elevation `h_deg`:
/// `R = 1.02' / tan(h + 10.3 / (h + 5.11))`, plus Meeus's 0.0019279' so that `R(90) = 0`.
/// The formula holds down to the horizon; below -1 deg its value at -1 deg is faded
/// linearly to zero at -5 deg (a rendering convenience that keeps the sun's track
/// continuous; no refraction is claimed there).
pub fn saemundsson_refraction_deg(h_deg: f64) -> f64 {
    let arcmin = |h: f64| 1.02 / (h + 10.3 / (h + 5.11)).to_radians().tan() + 0.001_927_9;
    let r = if h_deg >= -1.0 {
        arcmin(h_deg.min(90.0))
    } else {
        arcmin(-1.0) * ((h_deg + 5.0) / 4.0).max(0.0)
    };
    r / 60.0
}

/// An angle wrapped into [-180, 180) degrees.
fn wrap_180(deg: f64) -> f64 {
    (deg + 180.0).rem_euclid(360.0) - 180.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dms(d: f64, m: f64, s: f64) -> f64 {
        d.signum() * (d.abs() + m / 60.0 + s / 3600.0)
    }

    fn utc(y: i32, mo: u32, d: u32, h: u32, mi: u32, s: f64) -> UtcDateTime {
        UtcDateTime::new(y, mo, d, h, mi, s).unwrap()
    }

    /// Meeus chapter 7: Example 7.a (1957 October 4.81, the launch of Sputnik 1) and the
    /// table of instants after it.
    #[test]
    fn julian_days_of_meeus_chapter_7() {
        let sputnik = utc(1957, 10, 4, 19, 26, 24.0); // .81 day = 19h26m24s
        assert!((sputnik.julian_day() - 2_436_116.31).abs() < 1e-6);
        for (t, jd) in [
            (utc(2000, 1, 1, 12, 0, 0.0), 2_451_545.0),
            (utc(1999, 1, 1, 0, 0, 0.0), 2_451_179.5),
            (utc(1987, 1, 27, 0, 0, 0.0), 2_446_822.5),
            (utc(1987, 6, 19, 12, 0, 0.0), 2_446_966.0),
            (utc(1988, 1, 27, 0, 0, 0.0), 2_447_187.5),
            (utc(1988, 6, 19, 12, 0, 0.0), 2_447_332.0),
            (utc(1900, 1, 1, 0, 0, 0.0), 2_415_020.5),
            (utc(1600, 1, 1, 0, 0, 0.0), 2_305_447.5),
            (utc(1600, 12, 31, 0, 0, 0.0), 2_305_812.5),
        ] {
            assert_eq!(t.julian_day(), jd, "{t:?}");
        }
    }

    /// Meeus Example 25.a: the Sun on 1992 October 13.0 TD (JDE 2448908.5), every
    /// intermediate quantity to the digits the book prints.
    #[test]
    fn meeus_example_25a() {
        let c = SolarCoordinates::at_julian_day(utc(1992, 10, 13, 0, 0, 0.0).julian_day());
        let close = |got: f64, want: f64, tol: f64, what: &str| {
            assert!((got - want).abs() <= tol, "{what}: {got} vs {want}");
        };
        close(c.julian_centuries, -0.072_183_436, 1e-9, "T");
        close(c.mean_longitude_deg, 201.807_20, 1e-5, "L0");
        close(c.mean_anomaly_deg, 278.993_97, 1e-5, "M");
        close(c.eccentricity, 0.016_711_668, 1e-9, "e");
        close(c.equation_of_centre_deg, -1.897_32, 1e-5, "C");
        close(c.true_longitude_deg, 199.909_88, 1e-5, "true longitude");
        close(c.apparent_longitude_deg, 199.908_95, 1e-5, "lambda");
        close(
            c.mean_obliquity_deg,
            dms(23.0, 26.0, 24.83),
            0.01 / 3600.0,
            "epsilon0",
        );
        close(c.apparent_obliquity_deg, 23.439_99, 1e-5, "epsilon");
        // alpha_app = -161.61918 deg = 13h13m31.4s, delta_app = -7.78507 deg = -7d47'06".
        close(c.right_ascension_deg, 198.380_82, 1e-5, "alpha");
        close(
            c.right_ascension_deg / 15.0,
            13.0 + 13.0 / 60.0 + 31.4 / 3600.0,
            0.05 / 3600.0,
            "alpha (h)",
        );
        close(c.declination_deg, -7.785_07, 1e-5, "delta");
        close(
            c.declination_deg,
            dms(-7.0, 47.0, 6.0),
            0.5 / 3600.0,
            "delta (dms)",
        );
    }

    /// Meeus Example 28.b: the equation of time on 1992 October 13.0 TD from Smart's formula
    /// is 0.059825 rad = +13m42.7s.
    #[test]
    fn meeus_example_28b_equation_of_time() {
        let c = SolarCoordinates::at_julian_day(2_448_908.5);
        let seconds = c.equation_of_time_min * 60.0;
        assert!((seconds - (13.0 * 60.0 + 42.7)).abs() < 0.1, "{seconds} s");
    }

    /// The equation of time's yearly extremes (almanac values, stable to a few seconds over
    /// decades): about -14.2 min near 11-12 February and +16.4 min near 3 November.
    #[test]
    fn equation_of_time_extremes() {
        let over = |month, days: std::ops::RangeInclusive<u32>| {
            days.map(move |d| {
                SolarCoordinates::at_julian_day(utc(2024, month, d, 12, 0, 0.0).julian_day())
                    .equation_of_time_min
            })
        };
        let february_min = over(2, 1..=28).fold(f64::INFINITY, f64::min);
        let november_max = over(11, 1..=10).fold(f64::NEG_INFINITY, f64::max);
        assert!((february_min + 14.2).abs() < 0.1, "{february_min}");
        assert!((november_max - 16.4).abs() < 0.1, "{november_max}");
    }

    /// The 2024 equinoxes and solstices (USNO instants, to the minute): the declination is
    /// 0 at the equinoxes and +/- the obliquity (23.44 deg) at the solstices, within 0.01 deg
    /// (chapter 25's accuracy; the declination moves 0.016 deg per hour at an equinox).
    #[test]
    fn equinoxes_and_solstices_2024() {
        let delta =
            |t: UtcDateTime| SolarCoordinates::at_julian_day(t.julian_day()).declination_deg;
        assert!(delta(utc(2024, 3, 20, 3, 6, 0.0)).abs() < 0.01);
        assert!(delta(utc(2024, 9, 22, 12, 44, 0.0)).abs() < 0.01);
        assert!((delta(utc(2024, 6, 20, 20, 51, 0.0)) - 23.4362).abs() < 0.01);
        assert!((delta(utc(2024, 12, 21, 9, 21, 0.0)) + 23.4362).abs() < 0.01);
    }

    /// At true solar noon on the June solstice, the Sun culminates due south at elevation
    /// 90 - latitude + 23.44 deg: at Boulder, Colorado (NOAA's calculator's default,
    /// 40.0150 N, 105.2705 W) 73.42 deg. Noon is found from the equation of time:
    /// 12:00 UTC - 4 min per degree of east longitude - E.
    #[test]
    fn solstice_noon_at_boulder() {
        let place = GeoLocation::new(40.0150, -105.2705).unwrap();
        // E at 12:00 UTC first, then again at the noon it gives (E moves 13 s a day).
        let mut t = utc(2024, 6, 20, 12, 0, 0.0);
        for _ in 0..2 {
            let eot = SolarCoordinates::at_julian_day(t.julian_day()).equation_of_time_min;
            let noon_min = 720.0 - 4.0 * place.longitude_deg - eot;
            let (h, m) = ((noon_min / 60.0).floor(), noon_min % 60.0);
            t = utc(2024, 6, 20, h as u32, m.floor() as u32, (m % 1.0) * 60.0);
        }
        let sun = SunPosition::compute(&t, &place, Refraction::None).unwrap();
        assert!(sun.hour_angle_deg.abs() < 0.01, "{}", sun.hour_angle_deg);
        assert!(
            (sun.azimuth_deg - 180.0).abs() < 0.05,
            "{}",
            sun.azimuth_deg
        );
        let want = 90.0 - place.latitude_deg + 23.4362;
        assert!(
            (sun.elevation_deg() - want).abs() < 0.01,
            "{}",
            sun.elevation_deg()
        );
        // Refraction lifts it by about 0.3' at 73 deg (Saemundsson).
        let apparent = SunPosition::compute(&t, &place, Refraction::Saemundsson).unwrap();
        let lift_arcmin = (apparent.elevation_deg() - sun.elevation_deg()) * 60.0;
        assert!((lift_arcmin - 0.30).abs() < 0.03, "{lift_arcmin}");
    }

    /// Morning sun is in the east (azimuth below 180 deg), afternoon sun in the west; at an
    /// equinox sunrise the Sun rises nearly due east everywhere.
    #[test]
    fn azimuth_convention() {
        let place = GeoLocation::new(48.85, 2.35).unwrap(); // Paris
        let morning =
            SunPosition::compute(&utc(2024, 3, 20, 8, 0, 0.0), &place, Refraction::None).unwrap();
        let afternoon =
            SunPosition::compute(&utc(2024, 3, 20, 15, 0, 0.0), &place, Refraction::None).unwrap();
        assert!(
            (90.0..180.0).contains(&morning.azimuth_deg),
            "{}",
            morning.azimuth_deg
        );
        assert!(
            (180.0..270.0).contains(&afternoon.azimuth_deg),
            "{}",
            afternoon.azimuth_deg
        );
        assert!(morning.direction_enu().x > 0.0 && afternoon.direction_enu().x < 0.0);
        // At the equator the equinox Sun rises at azimuth 90 and culminates at the zenith.
        let equator = GeoLocation::new(0.0, 0.0).unwrap();
        let rise =
            SunPosition::compute(&utc(2024, 3, 20, 6, 7, 0.0), &equator, Refraction::None).unwrap();
        assert!(rise.elevation_deg().abs() < 0.5, "{}", rise.elevation_deg());
        assert!(
            (rise.azimuth_deg - 90.0).abs() < 0.1,
            "{}",
            rise.azimuth_deg
        );
    }

    /// The ENU vector matches zenith and azimuth, and rotated into the planet frame it is
    /// the observer-independent planet-frame vector.
    #[test]
    fn local_and_planet_directions_agree() {
        for (lat, lon, h) in [
            (40.0, -105.0, 17),
            (-33.9, 151.2, 2),
            (78.2, 15.6, 23),
            (0.0, 179.0, 9),
        ] {
            let place = GeoLocation::new(lat, lon).unwrap();
            let sun = SunPosition::compute(&utc(2024, 8, 14, h, 30, 0.0), &place, Refraction::None)
                .unwrap();
            let enu = sun.direction_enu();
            assert!((enu.length() - 1.0).abs() < 1e-12);
            assert!((enu.z - sun.zenith_deg.to_radians().cos()).abs() < 1e-12);
            let (phi, l) = (lat.to_radians(), lon.to_radians());
            let east = DVec3::new(-l.sin(), l.cos(), 0.0);
            let north = DVec3::new(-phi.sin() * l.cos(), -phi.sin() * l.sin(), phi.cos());
            let up = DVec3::new(phi.cos() * l.cos(), phi.cos() * l.sin(), phi.sin());
            let planet = east * enu.x + north * enu.y + up * enu.z;
            assert!(
                (planet - sun.direction_planet()).length() < 1e-9,
                "{lat} {lon}"
            );
        }
    }

    /// Saemundsson's formula: about 29' at the horizon, 0 at the zenith, continuous and
    /// fading to 0 below the horizon.
    #[test]
    fn refraction() {
        assert!((saemundsson_refraction_deg(0.0) * 60.0 - 28.98).abs() < 0.05);
        assert!(saemundsson_refraction_deg(90.0).abs() < 1e-6);
        assert!(
            (saemundsson_refraction_deg(-1.0 + 1e-9) - saemundsson_refraction_deg(-1.0 - 1e-9))
                .abs()
                < 1e-9
        );
        assert_eq!(saemundsson_refraction_deg(-6.0), 0.0);
    }

    /// Fields out of range are errors naming the field.
    #[test]
    fn bad_input_names_the_field() {
        let field = |r: Result<UtcDateTime, SunPositionError>| match r {
            Err(SunPositionError::Invalid { field, .. }) => field,
            Ok(t) => panic!("accepted {t:?}"),
        };
        assert_eq!(field(UtcDateTime::new(2024, 13, 1, 0, 0, 0.0)), "month");
        assert_eq!(field(UtcDateTime::new(2024, 0, 1, 0, 0, 0.0)), "month");
        assert_eq!(field(UtcDateTime::new(2023, 2, 29, 0, 0, 0.0)), "day");
        assert!(UtcDateTime::new(2024, 2, 29, 0, 0, 0.0).is_ok());
        assert_eq!(field(UtcDateTime::new(2024, 1, 1, 24, 0, 0.0)), "hour");
        assert_eq!(field(UtcDateTime::new(2024, 1, 1, 0, 60, 0.0)), "minute");
        assert_eq!(
            field(UtcDateTime::new(2024, 1, 1, 0, 0, f64::NAN)),
            "second"
        );
        assert_eq!(field(UtcDateTime::new(1200, 1, 1, 0, 0, 0.0)), "year");
        let e = GeoLocation::new(95.0, 0.0).unwrap_err();
        assert!(e.to_string().contains("latitude"), "{e}");
        let e = GeoLocation::new(0.0, f64::NAN).unwrap_err();
        assert!(e.to_string().contains("longitude"), "{e}");
        // compute validates structs built by hand too.
        let bad_time = UtcDateTime {
            month: 13,
            ..utc(2024, 1, 1, 0, 0, 0.0)
        };
        let place = GeoLocation {
            latitude_deg: 0.0,
            longitude_deg: 0.0,
        };
        let e = SunPosition::compute(&bad_time, &place, Refraction::None).unwrap_err();
        assert!(
            e.to_string().contains("month 13") || e.to_string().contains("month: 13"),
            "{e}"
        );
    }
}
