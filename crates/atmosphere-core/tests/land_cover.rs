//! The land's cover (`geo::land_cover`): snow above a snow line that follows latitude and
//! season, never at the sea; rock on steep slopes. Seasons from the sun's declination of
//! dates (`sun_position`), as a frame's planet-fixed sun direction gives it.

use atmosphere_core::geo::land_cover::{
    ROCK_ALBEDO, SNOW_ALBEDO, SnowLine, land_albedo, rock_share, snow_share,
};
use atmosphere_core::sun_position::{GeoLocation, Refraction, SunPosition, UtcDateTime};

/// A green-brown colour map's albedo, neither rock nor snow.
const MEADOW: [f64; 3] = [0.08, 0.10, 0.05];

/// The snow line of noon UTC on `month`/`day` of 2026, from the sun's planet-fixed
/// direction (its z component is the sine of the declination).
fn snow_line(month: u32, day: u32) -> SnowLine {
    let time = UtcDateTime::new(2026, month, day, 12, 0, 0.0).unwrap();
    let sun = SunPosition::compute(
        &time,
        &GeoLocation::new(0.0, 0.0).unwrap(),
        Refraction::None,
    )
    .unwrap()
    .direction_planet();
    SnowLine::for_declination(sun.z.clamp(-1.0, 1.0).asin())
}

fn albedo(lat_deg: f64, height_m: f64, slope_deg: f64, line: &SnowLine) -> [f64; 3] {
    land_albedo(
        MEADOW,
        lat_deg.to_radians(),
        height_m,
        slope_deg.to_radians().cos(),
        line,
    )
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
}

#[test]
fn the_alps_in_january_are_white_at_4500_m_and_green_at_500_m() {
    let january = snow_line(1, 15);
    let alps = 46.0;
    assert!(close(albedo(alps, 4500.0, 10.0, &january), SNOW_ALBEDO));
    assert!(close(albedo(alps, 500.0, 10.0, &january), MEADOW));
    let line = january.height_m(alps.to_radians());
    assert!((1000.0..1800.0).contains(&line), "{line}");
}

#[test]
fn the_snow_line_rises_in_summer_and_in_the_tropics() {
    let (january, july) = (snow_line(1, 15), snow_line(7, 15));
    let alps = 46f64.to_radians();
    let summer = july.height_m(alps);
    assert!((2600.0..3400.0).contains(&summer), "{summer}");
    assert!(close(albedo(46.0, 2000.0, 10.0, &july), MEADOW));
    assert!(close(albedo(46.0, 3800.0, 10.0, &july), SNOW_ALBEDO));
    // The southern Alps (New Zealand, 43.5 S) have their winter in July.
    assert!(july.height_m(-43.5f64.to_radians()) < january.height_m(-43.5f64.to_radians()));
    // No snow at 3000 m on the equator in any season; the tropical line lies near 5 km.
    for line in [january, july, snow_line(3, 20), snow_line(9, 22)] {
        assert!(close(albedo(0.0, 3000.0, 10.0, &line), MEADOW));
        let tropics = line.height_m(0.0);
        assert!((4500.0..5200.0).contains(&tropics), "{tropics}");
    }
}

#[test]
fn snow_never_lies_at_the_sea() {
    // At 80 N in January the line is below sea level: snow down to the coast, not on it.
    let january = snow_line(1, 15);
    assert!(january.height_m(80f64.to_radians()) < 0.0);
    assert!(close(albedo(80.0, 1.0, 0.0, &january), SNOW_ALBEDO));
    assert_eq!(snow_share(0.0, -2000.0), 0.0);
    assert_eq!(snow_share(-50.0, -2000.0), 0.0);
}

#[test]
fn steep_ground_is_rock_and_sheds_its_snow() {
    let january = snow_line(1, 15);
    // 45 deg: all rock, on a meadow and above the snow line alike.
    assert!(close(albedo(0.0, 1000.0, 45.0, &january), ROCK_ALBEDO));
    assert!(close(albedo(46.0, 4500.0, 45.0, &january), ROCK_ALBEDO));
    // Below 30 deg none; between, some.
    assert_eq!(rock_share(25f64.to_radians().cos()), 0.0);
    let some = rock_share(35f64.to_radians().cos());
    assert!(some > 0.2 && some < 0.8, "{some}");
    // Level ground is never rock.
    assert_eq!(rock_share(1.0), 0.0);
}
