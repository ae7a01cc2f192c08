//! The Sun as seen from a place on Earth: hour angle, zenith angle, azimuth and
//! directions in the local and planet-fixed frames (Meeus chapter 13).

use glam::DVec3;

use crate::sun_position::calendar::UtcDateTime;
use crate::sun_position::error::SunPositionError;
use crate::sun_position::refraction::{Refraction, saemundsson_refraction_deg};
use crate::sun_position::solar_coordinates::SolarCoordinates;

/// A place on Earth: geodetic latitude and longitude in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeoLocation {
    /// -90 (south pole) to 90 (north pole).
    pub latitude_deg: f64,
    /// -180 to 180, positive east of Greenwich.
    pub longitude_deg: f64,
}

impl GeoLocation {
    /// A checked location: a field out of range (or not finite) is an error naming it.
    pub fn new(latitude_deg: f64, longitude_deg: f64) -> Result<GeoLocation, SunPositionError> {
        let location = GeoLocation {
            latitude_deg,
            longitude_deg,
        };
        location.validate()?;
        Ok(location)
    }

    /// Checks both fields; the error names the one out of range.
    pub fn validate(&self) -> Result<(), SunPositionError> {
        if !(-90.0..=90.0).contains(&self.latitude_deg) {
            return Err(SunPositionError::Invalid {
                field: "latitude",
                value: self.latitude_deg,
                expected: "-90 to 90 degrees".into(),
            });
        }
        if !(-180.0..=180.0).contains(&self.longitude_deg) {
            return Err(SunPositionError::Invalid {
                field: "longitude",
                value: self.longitude_deg,
                expected: "-180 to 180 degrees (east positive)".into(),
            });
        }
        Ok(())
    }
}

/// The Sun as seen from a place at an instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunPosition {
    /// The Sun's celestial coordinates at the instant.
    pub coordinates: SolarCoordinates,
    /// Local hour angle, degrees in [-180, 180): negative before local solar noon.
    pub hour_angle_deg: f64,
    /// Greenwich hour angle (the hour angle at longitude 0), degrees in [-180, 180).
    pub greenwich_hour_angle_deg: f64,
    /// Angle from the zenith, degrees in [0, 180]; apparent when refraction is applied.
    pub zenith_deg: f64,
    /// Azimuth from north towards east, degrees in [0, 360).
    pub azimuth_deg: f64,
    /// The refraction added to the elevation, degrees (0 without refraction).
    pub refraction_deg: f64,
}

impl SunPosition {
    /// The Sun's position at `time` seen from `location`. Both are validated first.
    pub fn compute(
        time: &UtcDateTime,
        location: &GeoLocation,
        refraction: Refraction,
    ) -> Result<SunPosition, SunPositionError> {
        time.validate()?;
        location.validate()?;
        let coordinates = SolarCoordinates::at_julian_day(time.julian_day());
        // NOAA: true solar time in minutes = UTC minutes + equation of time + 4 min per
        // degree of longitude east; the hour angle is 0 at true solar noon.
        let utc_min = time.day_fraction() * 1440.0;
        let greenwich_hour_angle_deg =
            wrap_180((utc_min + coordinates.equation_of_time_min) / 4.0 - 180.0);
        let hour_angle_deg = wrap_180(greenwich_hour_angle_deg + location.longitude_deg);

        let (phi, h, delta) = (
            location.latitude_deg.to_radians(),
            hour_angle_deg.to_radians(),
            coordinates.declination_deg.to_radians(),
        );
        // Meeus eq. 13.6: sin(elevation) = sin phi sin delta + cos phi cos delta cos H.
        let cos_zenith =
            (phi.sin() * delta.sin() + phi.cos() * delta.cos() * h.cos()).clamp(-1.0, 1.0);
        let true_elevation_deg = 90.0 - cos_zenith.acos().to_degrees();
        // Meeus eq. 13.5 measures from south towards west:
        // tan A_s = sin H / (cos H sin phi - tan delta cos phi). From north towards east,
        // A = A_s + 180 deg; written with cos delta so the poles of declination are safe.
        let south_west = (h.sin() * delta.cos())
            .atan2(h.cos() * phi.sin() * delta.cos() - delta.sin() * phi.cos());
        let azimuth_deg = (south_west.to_degrees() + 180.0).rem_euclid(360.0);
        let refraction_deg = match refraction {
            Refraction::None => 0.0,
            Refraction::Saemundsson => saemundsson_refraction_deg(true_elevation_deg),
        };
        Ok(SunPosition {
            coordinates,
            hour_angle_deg,
            greenwich_hour_angle_deg,
            zenith_deg: (90.0 - true_elevation_deg - refraction_deg).clamp(0.0, 180.0),
            azimuth_deg,
            refraction_deg,
        })
    }

    /// Elevation above the horizon, degrees (`90 - zenith`).
    pub fn elevation_deg(&self) -> f64 {
        90.0 - self.zenith_deg
    }

    /// Unit vector towards the Sun in the local east-north-up frame:
    /// `(sin z sin A, sin z cos A, cos z)` with zenith `z` and azimuth `A`.
    pub fn direction_enu(&self) -> DVec3 {
        let (z, a) = (self.zenith_deg.to_radians(), self.azimuth_deg.to_radians());
        DVec3::new(z.sin() * a.sin(), z.sin() * a.cos(), z.cos())
    }

    /// Unit vector towards the Sun in the planet-fixed frame (x to latitude 0 longitude 0,
    /// y to latitude 0 longitude 90 E, z to the north pole), from the declination and
    /// Greenwich hour angle: the sub-solar point is at latitude `delta`, longitude
    /// `-GHA`. Geometric (no refraction, which depends on the observer); the Earth's radius
    /// against the Sun's distance (parallax, 8.8") is neglected.
    pub fn direction_planet(&self) -> DVec3 {
        let delta = self.coordinates.declination_deg.to_radians();
        let lon = (-self.greenwich_hour_angle_deg).to_radians();
        DVec3::new(
            delta.cos() * lon.cos(),
            delta.cos() * lon.sin(),
            delta.sin(),
        )
    }
}

/// An angle wrapped into [-180, 180) degrees.
fn wrap_180(deg: f64) -> f64 {
    (deg + 180.0).rem_euclid(360.0) - 180.0
}
