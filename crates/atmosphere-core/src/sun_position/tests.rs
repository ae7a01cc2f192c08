//! The Sun's position against Meeus's worked examples, almanac values and the
//! conventions of NOAA's calculator.

use glam::DVec3;

use crate::sun_position::calendar::UtcDateTime;
use crate::sun_position::error::SunPositionError;
use crate::sun_position::position::{GeoLocation, SunPosition};
use crate::sun_position::refraction::{Refraction, saemundsson_refraction_deg};
use crate::sun_position::solar_coordinates::SolarCoordinates;

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
    let delta = |t: UtcDateTime| SolarCoordinates::at_julian_day(t.julian_day()).declination_deg;
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
        let sun =
            SunPosition::compute(&utc(2024, 8, 14, h, 30, 0.0), &place, Refraction::None).unwrap();
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
        (saemundsson_refraction_deg(-1.0 + 1e-9) - saemundsson_refraction_deg(-1.0 - 1e-9)).abs()
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
