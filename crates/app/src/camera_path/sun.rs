//! The sun between keyframes: angles at the camera eased from one keyframe to the next,
//! a UTC time running at a steady rate (a clock is never eased) and turned into the sun's
//! planet-fixed direction as the viewer's sun clock does, or, between a keyframe of each
//! kind, the eased arc between the two directions.

use anyhow::Context;
use glam::{DQuat, DVec3};
use render_wgpu::frame::LocalView;

use crate::camera_path::keyframe::SunKey;
use crate::viewer::sun_clock::{SunClock, SunMode};

/// The sun's unit direction in the local frame (x north, y west, z up) of a place.
fn local_direction(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    LocalView {
        altitude_m: 0.0,
        view_zenith_deg: 90.0,
        view_azimuth_deg: 0.0,
        sun_zenith_deg: 90.0 - elevation_deg,
        sun_azimuth_deg: -azimuth_deg,
    }
    .sun_direction()
}

/// The sun's planet-fixed direction at UTC seconds since 2000-01-01.
pub fn utc_direction(utc_s: f64) -> anyhow::Result<DVec3> {
    let clock = SunClock {
        mode: SunMode::Date,
        utc_s,
        ..SunClock::default()
    };
    Ok(clock.sun(0.0, 0.0).context("sun clock")?.direction_planet())
}

/// The sun of one keyframe seen from a place (`place` carries the local frame to planet
/// axes).
pub fn direction(sun: SunKey, place: DQuat) -> anyhow::Result<DVec3> {
    match sun {
        SunKey::Angles {
            elevation_deg,
            azimuth_deg,
        } => Ok(place * local_direction(elevation_deg, azimuth_deg)),
        SunKey::Utc(s) => utc_direction(s),
    }
}

/// The sun at fraction `h` (eased: `e`) from `a` (seen from `place_a`) to `b` (from
/// `place_b`), seen from `place`.
pub fn between(
    (a, place_a): (SunKey, DQuat),
    (b, place_b): (SunKey, DQuat),
    (h, e): (f64, f64),
    place: DQuat,
) -> anyhow::Result<DVec3> {
    let lerp = |x: f64, y: f64| x + (y - x) * e;
    match (a, b) {
        (
            SunKey::Angles {
                elevation_deg: e0,
                azimuth_deg: a0,
            },
            SunKey::Angles {
                elevation_deg: e1,
                azimuth_deg: a1,
            },
        ) => {
            // The short way round: at most half a turn.
            let a1 = a0 + (a1 - a0 + 180.0).rem_euclid(360.0) - 180.0;
            Ok(place * local_direction(lerp(e0, e1), lerp(a0, a1)))
        }
        (SunKey::Utc(s0), SunKey::Utc(s1)) => utc_direction(s0 + (s1 - s0) * h),
        _ => {
            let (d0, d1) = (direction(a, place_a)?, direction(b, place_b)?);
            let arc = DQuat::from_rotation_arc(d0, d1);
            Ok(DQuat::IDENTITY.slerp(arc, e) * d0)
        }
    }
}
