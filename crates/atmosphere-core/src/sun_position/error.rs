//! The error of a date, time or place out of range.

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
