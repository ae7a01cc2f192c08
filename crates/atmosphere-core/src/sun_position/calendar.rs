//! UTC dates and times of the Gregorian calendar, and their Julian Day (Meeus chapter 7).

use crate::sun_position::error::SunPositionError;

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
