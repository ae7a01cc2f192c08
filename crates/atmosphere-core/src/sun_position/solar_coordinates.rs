//! The Sun's coordinates on the celestial sphere at an instant (Meeus chapters 22, 25
//! and 28).

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
