//! The view `atmos` opens with no saved settings, and "reset view" returns to: 3 km above
//! the Pennine Alps east of the Matterhorn (46.0 N, 7.8 E, above the Saas valley), an
//! October evening with the sun about 5 deg above the horizon in the west-south-west,
//! looking towards the Matterhorn (about 11 km away) with the sun a little to the right.
//!
//! The camera's height is fixed here rather than read from the map at startup: the
//! terrain under the camera in `assets/earth/height.png` (10 arc-minute ETOPO5 averages,
//! which smooth the 4.5 km peaks to under 3 km) is [`GROUND_M`], checked by a test, and
//! the camera is [`ABOVE_GROUND_M`] higher. Without terrain the same view is a sunset sky
//! over a smooth planet from 5.5 km.

use glam::DVec3;
use render_wgpu::terrain::geo_grid;

use crate::viewer::flight::FlightState;
use crate::viewer::sun_clock::{SunClock, SunMode, seconds_of};
use atmosphere_core::sun_position::UtcDateTime;

/// The camera's place, degrees.
pub const LATITUDE_DEG: f64 = 46.0;
pub const LONGITUDE_DEG: f64 = 7.8;

/// The height of the terrain under the camera in the shipped height map (bilinear),
/// rounded up to 100 m.
pub const GROUND_M: f64 = 2_600.0;

/// The camera's height above [`GROUND_M`].
pub const ABOVE_GROUND_M: f64 = 3_000.0;

/// View direction: west-south-west, the sun (azimuth 251 deg) and the Matterhorn (256
/// deg) a little right of the centre, looking a little below the horizon so the sky
/// fills the upper half and the ground the lower.
pub const HEADING_DEG: f64 = 240.0;
pub const PITCH_DEG: f64 = -3.0;

/// The evening: 2024-10-15 16:05 UTC (18:05 in Zermatt), the sun 5.4 deg high at the
/// camera.
pub const UTC: UtcDateTime = UtcDateTime {
    year: 2024,
    month: 10,
    day: 15,
    hour: 16,
    minute: 5,
    second: 0.0,
};

/// The camera above a planet of reference radius `radius_m`, at rest.
pub fn camera(radius_m: f64) -> FlightState {
    let up: DVec3 = geo_grid::direction(LATITUDE_DEG.to_radians(), LONGITUDE_DEG.to_radians());
    FlightState::new(
        up * (radius_m + GROUND_M + ABOVE_GROUND_M),
        HEADING_DEG.to_radians(),
        PITCH_DEG.to_radians(),
    )
}

/// The sun's clock: date mode at [`UTC`], the time-lapse paused.
pub fn sun_clock() -> SunClock {
    SunClock {
        mode: SunMode::Date,
        utc_s: seconds_of(&UTC),
        ..SunClock::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use render_wgpu::terrain::EarthData;

    #[test]
    fn the_camera_is_above_the_terrain_near_sunset_facing_the_sun() {
        let map = EarthData::BuiltIn.heights().unwrap();
        let (lat, lon) = (LATITUDE_DEG.to_radians(), LONGITUDE_DEG.to_radians());
        let ground = map.sample(lat, lon);
        assert!(ground <= GROUND_M && ground > GROUND_M - 100.0, "{ground}");
        // Nothing within about 30 km reaches within 2 km of the camera.
        let mut highest = f64::MIN;
        for i in -10..=10 {
            for j in -10..=10 {
                let d = f64::from(i) * 0.003;
                let e = f64::from(j) * 0.004;
                highest = highest.max(map.sample(lat + d, lon + e));
            }
        }
        assert!(highest < GROUND_M + ABOVE_GROUND_M - 2000.0, "{highest}");

        let radius = 6_360_000.0;
        let flight = camera(radius);
        let (lat2, lon2) = geo_grid::lat_lon(flight.position_m);
        assert!((lat2.to_degrees() - LATITUDE_DEG).abs() < 1e-9);
        assert!((lon2.to_degrees() - LONGITUDE_DEG).abs() < 1e-9);
        let altitude = flight.position_m.length() - radius;
        assert!((altitude - GROUND_M - ABOVE_GROUND_M).abs() < 1e-6);

        let sun = sun_clock().sun(LATITUDE_DEG, LONGITUDE_DEG).unwrap();
        assert!(
            (3.0..=7.0).contains(&sun.elevation_deg()),
            "{}",
            sun.elevation_deg()
        );
        let off = (sun.azimuth_deg - HEADING_DEG.rem_euclid(360.0)).abs();
        assert!(off < 40.0, "the sun {off} deg from the view");
    }
}
