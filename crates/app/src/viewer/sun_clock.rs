//! The sun's clock: where the panel's sun comes from (elevation and azimuth, or a date and
//! time), and the time-lapse that advances the time each frame.
//!
//! Time is UTC, kept as seconds since 2000-01-01 00:00 UTC with every day 86,400 s long
//! (no leap seconds, as the Julian Day of `atmosphere_core::sun_position` assumes), so the
//! time-lapse is one addition per frame and crosses midnights, months and years without
//! special cases. The calendar date of a time is Meeus's inverse of the Julian Day
//! (*Astronomical Algorithms*, chapter 7, "Calculation of the calendar date from the JD").
//! The panel also shows the local apparent (true) solar time at the camera, `12 h + H /
//! 15 deg per hour` with `H` the hour angle, which is 12:00 when the sun is highest.
//!
//! In date mode the sun's direction is fixed in the planet's axes for a given instant
//! ([`SunPosition::direction_planet`]: the sub-solar point at latitude = declination and
//! longitude = minus the Greenwich hour angle). Axes: x towards latitude 0 longitude 0, y
//! towards latitude 0 longitude 90 deg east, z towards the north pole, those of the
//! terrain (`render_wgpu::terrain::geo_grid`) and of the flight controller, so flying
//! round the planet crosses from the day side to the night side.

use atmosphere_core::sun_position::{
    GeoLocation, Refraction, SunPosition, SunPositionError, UtcDateTime,
};
use serde::{Deserialize, Serialize};

/// Seconds in a (UTC) day.
pub const SECONDS_PER_DAY: f64 = 86_400.0;

/// The Julian Day at 2000-01-01 00:00 UTC, the clock's zero.
const EPOCH_JD: f64 = 2_451_544.5;

/// The time-lapse speed's range on the panel's logarithmic slider: real time to
/// 10,000 times real time (a day in under 9 s).
pub const SPEED_RANGE: (f64, f64) = (1.0, 1e4);

/// The clock's range, seconds: the years `UtcDateTime` accepts, 1583 to 9999.
fn time_range_s() -> (f64, f64) {
    let first = UtcDateTime {
        year: 1583,
        month: 1,
        day: 1,
        hour: 0,
        minute: 0,
        second: 0.0,
    };
    let after_last = UtcDateTime {
        year: 9999,
        month: 12,
        day: 31,
        ..first
    };
    (
        seconds_of(&first),
        seconds_of(&after_last) + SECONDS_PER_DAY - 1.0,
    )
}

/// Where the sun comes from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum SunMode {
    /// Elevation and azimuth at the camera, whatever the camera's place.
    Angles,
    /// A UTC date and time: the sun moves with the camera's place and with the time.
    #[default]
    Date,
}

/// The clock; see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SunClock {
    pub mode: SunMode,
    /// UTC, seconds since 2000-01-01 00:00 UTC.
    pub utc_s: f64,
    /// Simulated seconds per real second while running, within [`SPEED_RANGE`].
    pub speed: f64,
    /// Whether the time-lapse advances the time (date mode only).
    pub running: bool,
}

impl Default for SunClock {
    /// Date mode, 2000-01-01 00:00 UTC, paused at 100 times real time.
    fn default() -> SunClock {
        SunClock {
            mode: SunMode::Date,
            utc_s: 0.0,
            speed: 100.0,
            running: false,
        }
    }
}

/// The UTC seconds since the clock's zero of a date and time.
pub fn seconds_of(time: &UtcDateTime) -> f64 {
    let midnight = UtcDateTime {
        hour: 0,
        minute: 0,
        second: 0.0,
        ..*time
    };
    // Julian Days at midnight are exact halves: the difference is a whole number of days.
    (midnight.julian_day() - EPOCH_JD) * SECONDS_PER_DAY + time.day_fraction() * SECONDS_PER_DAY
}

/// The date and time of UTC seconds since the clock's zero (clamped to the years 1583 to
/// 9999): Meeus's calendar date of a Julian Day, Gregorian calendar.
pub fn date_time_of(utc_s: f64) -> UtcDateTime {
    let (first, last) = time_range_s();
    let utc_s = utc_s.clamp(first, last);
    let days = (utc_s / SECONDS_PER_DAY).floor();
    let second_of_day = (utc_s - days * SECONDS_PER_DAY).clamp(0.0, SECONDS_PER_DAY - 1e-6);
    // Z: the Julian Day number of the day (its noon); Meeus chapter 7 with F = 0.
    let z = EPOCH_JD + 0.5 + days;
    let alpha = ((z - 1_867_216.25) / 36_524.25).floor();
    let a = z + 1.0 + alpha - (alpha / 4.0).floor();
    let b = a + 1524.0;
    let c = ((b - 122.1) / 365.25).floor();
    let d = (365.25 * c).floor();
    let e = ((b - d) / 30.6001).floor();
    let day = b - d - (30.6001 * e).floor();
    let month = if e < 14.0 { e - 1.0 } else { e - 13.0 };
    let year = if month > 2.0 { c - 4716.0 } else { c - 4715.0 };
    let hour = (second_of_day / 3600.0).floor();
    let minute = ((second_of_day - hour * 3600.0) / 60.0).floor();
    UtcDateTime {
        year: year as i32,
        month: month as u32,
        day: day as u32,
        hour: hour as u32,
        minute: minute as u32,
        second: second_of_day - hour * 3600.0 - minute * 60.0,
    }
}

impl SunClock {
    /// The clock's date and time.
    pub fn date_time(&self) -> UtcDateTime {
        date_time_of(self.utc_s)
    }

    /// Sets the date and time (validated; the error names the field).
    pub fn set_date_time(&mut self, time: &UtcDateTime) -> Result<(), SunPositionError> {
        time.validate()?;
        self.utc_s = seconds_of(time);
        Ok(())
    }

    /// Advances the time by `dt_s` real seconds of time-lapse; true when the time moved
    /// (date mode, running, speed above 0).
    pub fn tick(&mut self, dt_s: f64) -> bool {
        if self.mode != SunMode::Date || !self.running || dt_s <= 0.0 {
            return false;
        }
        let speed = self.speed.clamp(SPEED_RANGE.0, SPEED_RANGE.1);
        let (first, last) = time_range_s();
        self.utc_s = (self.utc_s + dt_s * speed).clamp(first, last);
        true
    }

    /// The sun seen from latitude and longitude (degrees) at the clock's time, without
    /// refraction (the renderer bends no rays).
    pub fn sun(
        &self,
        latitude_deg: f64,
        longitude_deg: f64,
    ) -> Result<SunPosition, SunPositionError> {
        let place = GeoLocation::new(latitude_deg, longitude_deg)?;
        SunPosition::compute(&self.date_time(), &place, Refraction::None)
    }
}

/// The local apparent solar time of a sun position, hours in [0, 24): 12 at the sun's
/// highest.
pub fn solar_time_h(sun: &SunPosition) -> f64 {
    (12.0 + sun.hour_angle_deg / 15.0).rem_euclid(24.0)
}

/// "14:05:09".
pub fn format_hms(hours: f64) -> String {
    let total = (hours * 3600.0).floor() as u64 % 86_400;
    format!(
        "{:02}:{:02}:{:02}",
        total / 3600,
        total / 60 % 60,
        total % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use render_wgpu::terrain::geo_grid;

    fn utc(y: i32, mo: u32, d: u32, h: u32, mi: u32, s: f64) -> UtcDateTime {
        UtcDateTime::new(y, mo, d, h, mi, s).unwrap()
    }

    #[test]
    fn dates_and_seconds_round_trip() {
        assert_eq!(seconds_of(&utc(2000, 1, 1, 0, 0, 0.0)), 0.0);
        assert_eq!(seconds_of(&utc(2000, 1, 2, 0, 0, 1.5)), 86_401.5);
        assert_eq!(date_time_of(-1.0), utc(1999, 12, 31, 23, 59, 59.0));
        // Leap days, century rules, both ends of the range.
        for t in [
            utc(2024, 2, 29, 12, 0, 0.0),
            utc(2100, 3, 1, 0, 0, 0.0),
            utc(1900, 2, 28, 23, 59, 59.25),
            utc(1583, 1, 1, 0, 0, 0.0),
            utc(9999, 12, 31, 23, 59, 59.0),
            utc(1987, 6, 19, 12, 0, 0.0),
        ] {
            let s = seconds_of(&t);
            let back = date_time_of(s);
            assert_eq!(
                (back.year, back.month, back.day, back.hour, back.minute),
                (t.year, t.month, t.day, t.hour, t.minute),
                "{t:?}"
            );
            assert!((back.second - t.second).abs() < 1e-6, "{t:?} {back:?}");
        }
        assert_eq!(date_time_of(time_range_s().0), utc(1583, 1, 1, 0, 0, 0.0));
        assert_eq!(date_time_of(1e300).year, 9999, "clamped");
        // Meeus Example 7.c: JD 2436116.31 is 1957 October 4.81.
        let t = date_time_of((2_436_116.31 - EPOCH_JD) * SECONDS_PER_DAY);
        assert_eq!((t.year, t.month, t.day), (1957, 10, 4));
        assert!((t.day_fraction() - 0.81).abs() < 1e-6);
    }

    #[test]
    fn the_time_lapse_runs_only_when_asked() {
        let mut clock = SunClock::default();
        assert!(!clock.tick(1.0), "paused by default");
        clock.running = true;
        clock.speed = 3600.0;
        assert!(clock.tick(0.5));
        assert_eq!(clock.utc_s, 1800.0);
        clock.mode = SunMode::Angles;
        assert!(!clock.tick(0.5));
        assert_eq!(clock.utc_s, 1800.0);
    }

    /// At the sub-solar point the sun is at the zenith, in planet axes and in the
    /// observer's elevation.
    #[test]
    fn the_sun_is_overhead_at_the_subsolar_point() {
        let mut clock = SunClock::default();
        for t in [
            utc(2024, 6, 20, 20, 51, 0.0),
            utc(2024, 12, 21, 9, 20, 0.0),
            utc(2025, 4, 2, 3, 0, 0.0),
        ] {
            clock.set_date_time(&t).unwrap();
            let direction = clock.sun(0.0, 0.0).unwrap().direction_planet();
            let (lat, lon) = geo_grid::lat_lon(direction);
            let below = clock.sun(lat.to_degrees(), lon.to_degrees()).unwrap();
            assert!(
                below.elevation_deg() > 89.99,
                "{t:?}: {}",
                below.elevation_deg()
            );
            assert!((direction.length() - 1.0).abs() < 1e-12);
        }
    }

    /// At the March equinox, at local solar noon, the sun stands 90 deg - latitude high
    /// (declination within 0.5 deg of 0) and due south in the north; the planet-axes
    /// direction agrees with the elevation seen from there.
    #[test]
    fn equinox_noon_elevation_is_ninety_minus_latitude() {
        let mut clock = SunClock::default();
        clock.set_date_time(&utc(2024, 3, 20, 3, 6, 0.0)).unwrap();
        for (lat, lon) in [(46.0, 7.7), (-33.9, 151.2), (0.0, -60.0), (70.0, -150.0)] {
            // Local solar noon at this longitude: move the clock until the hour angle is 0
            // (twice, as the equation of time drifts a little).
            let mut at_noon = clock;
            for _ in 0..2 {
                let hour_angle = at_noon.sun(lat, lon).unwrap().hour_angle_deg;
                at_noon.utc_s -= hour_angle / 15.0 * 3600.0;
            }
            let sun = at_noon.sun(lat, lon).unwrap();
            assert!(
                sun.hour_angle_deg.abs() < 0.01,
                "{lat} {lon}: {}",
                sun.hour_angle_deg
            );
            assert!((solar_time_h(&sun) - 12.0).abs() < 1e-3);
            assert!(
                (sun.elevation_deg() - (90.0 - f64::abs(lat))).abs() < 0.5,
                "{lat}: {}",
                sun.elevation_deg()
            );
            let up = geo_grid::direction(f64::to_radians(lat), f64::to_radians(lon));
            let elevation = sun.direction_planet().dot(up).asin().to_degrees();
            assert!((elevation - sun.elevation_deg()).abs() < 1e-6);
            if lat > 1.0 {
                assert!((sun.azimuth_deg - 180.0).abs() < 0.5, "{}", sun.azimuth_deg);
            }
        }
        // Half a day later the same places are on the night side.
        let mut midnight = clock;
        midnight.utc_s += SECONDS_PER_DAY / 2.0;
        let noon_dir = clock.sun(0.0, 0.0).unwrap().direction_planet();
        let night_dir = midnight.sun(0.0, 0.0).unwrap().direction_planet();
        assert!(noon_dir.dot(night_dir) < -0.99);
        assert!(
            noon_dir.dot(DVec3::Z).abs() < 0.01,
            "equinox: in the equator's plane"
        );
    }

    #[test]
    fn clock_text() {
        assert_eq!(format_hms(14.086), "14:05:09");
        assert_eq!(format_hms(0.0), "00:00:00");
    }
}
