//! What can be wrong with rain and ice volumes and their phase tables.

use thiserror::Error;

use crate::color::ColorError;
use crate::optics::ice::crystal::CrystalError;
use crate::optics::ice::phase_table::IcePhaseError;
use crate::optics::mie::error::MieError;

#[derive(Clone, Debug, Error, PartialEq)]
pub enum HydrometeorError {
    #[error("{what} {value} is outside {range}")]
    Setting {
        what: &'static str,
        value: f64,
        range: &'static str,
    },
    #[error("rain: {0}")]
    Rain(#[from] MieError),
    #[error("ice crystal: {0}")]
    Crystal(#[from] CrystalError),
    #[error("ice phase function: {0}")]
    Ice(#[from] IcePhaseError),
    #[error("colour: {0}")]
    Color(#[from] ColorError),
    #[error("the sky model lighting a volume: {0}")]
    Model(String),
    #[error("refractive index at {0} nm: outside the tables")]
    RefractiveIndex(f64),
}

/// `value` within `[lo, hi]`, or an error naming `what` and the range.
pub fn check_range(
    what: &'static str,
    value: f64,
    [lo, hi]: [f64; 2],
    range: &'static str,
) -> Result<f64, HydrometeorError> {
    if (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(HydrometeorError::Setting { what, value, range })
    }
}
