//! Atmospheric refraction of the Sun's elevation (Meeus chapter 16).

/// Whether the zenith angle includes atmospheric refraction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refraction {
    /// The geometric (true) position.
    None,
    /// The apparent position, raised by Saemundsson's refraction (Meeus eq. 16.4) at
    /// 1010 hPa and 10 deg C.
    Saemundsson,
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
