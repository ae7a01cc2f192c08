//! The ranges the Lorenz-Mie code computes right.

/// Below this the series is Rayleigh scattering to rounding and Q_sca underflows.
pub const MIN_SIZE_PARAMETER: f64 = 1e-3;

/// Wiscombe's (1980) number of terms holds to x = 2e4; past 1e5 (a 10 mm drop in blue
/// light) geometric optics is the better tool and the cost per angle grows with x.
pub const MAX_SIZE_PARAMETER: f64 = 1e5;

/// The largest real or imaginary part of a refractive index (metals in the visible stay
/// below 10).
pub const MAX_REFRACTIVE_PART: f64 = 10.0;
