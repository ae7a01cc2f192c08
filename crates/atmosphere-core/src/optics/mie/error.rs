//! What makes a Lorenz-Mie computation impossible, named with the value at fault.

use thiserror::Error;

use super::limits::{MAX_REFRACTIVE_PART, MAX_SIZE_PARAMETER, MIN_SIZE_PARAMETER};

#[derive(Clone, Debug, Error, PartialEq)]
pub enum MieError {
    #[error(
        "size parameter x = 2 pi r / lambda = {0} is outside [{MIN_SIZE_PARAMETER}, \
         {MAX_SIZE_PARAMETER:e}] (smaller: Rayleigh scattering; larger: geometric optics)"
    )]
    SizeParameter(f64),
    #[error(
        "refractive index {re}{im:+}i must have a real part in (0, {MAX_REFRACTIVE_PART}] and \
         an imaginary (absorbing) part in [0, {MAX_REFRACTIVE_PART}], and differ from 1"
    )]
    RefractiveIndex { re: f64, im: f64 },
    #[error("wavelength {0} nm must be finite and positive")]
    Wavelength(f64),
    #[error("{what} = {value} is outside {range}")]
    Distribution {
        what: &'static str,
        value: f64,
        range: &'static str,
    },
    #[error(
        "the average over the size distribution still changed by {change:.1e} (relative; the \
         phase function's over 10) with {nodes} radii; it needs to settle below {tolerance:.0e}"
    )]
    NotConverged {
        change: f64,
        nodes: usize,
        tolerance: f64,
    },
}
