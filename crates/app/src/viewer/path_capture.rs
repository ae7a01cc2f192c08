//! A camera-path keyframe from the viewer's current view: the camera's place, altitude,
//! heading and pitch (roll 0), field of view, the sun (angles, or UTC when the sun clock
//! is on a date), preset, aerosol scale, ground albedo, model and its settings, exposure
//! and terrain. The aerosol asymmetry g and the ozone switch have no keyframe field: a
//! path uses the preset's.

use anyhow::bail;
use atmosphere_core::atmosphere::limits::MAX_ALTITUDE_M;
use render_wgpu::frame::terrain_fits;
use toml::value::{Date, Datetime, Offset, Time};

use crate::camera_path::file::KeyframeFile;
use crate::viewer::exposure::ExposureMode;
use crate::viewer::settings::ViewerSettings;
use crate::viewer::sun_clock::{SunMode, date_time_of};

/// The keyframe at `time_s` of what `settings` show; an error names what a path cannot
/// hold (an invalid setting, a camera below the ground sphere).
pub fn keyframe_of(settings: &ViewerSettings, time_s: f64) -> anyhow::Result<KeyframeFile> {
    let atmosphere = settings.atmosphere()?;
    let altitude_m = settings.altitude_m(atmosphere.bottom_radius_m);
    if !(0.0..=MAX_ALTITUDE_M).contains(&altitude_m) {
        bail!(
            "the camera is {altitude_m:.1} m above the ground sphere; a keyframe's altitude_m is 0 to {MAX_ALTITUDE_M:e} m"
        );
    }
    let (latitude_deg, longitude_deg) = settings.camera_lat_lon_deg();
    let flight = settings.flight();
    let (sun_elevation_deg, sun_azimuth_deg, utc) = match settings.sun_clock.mode {
        SunMode::Angles => {
            let (elevation, azimuth) = settings.sun_angles_deg()?;
            (Some(elevation), Some(azimuth), None)
        }
        SunMode::Date => (None, None, Some(utc_datetime(settings.sun_clock.utc_s))),
    };
    let set: Vec<String> = settings
        .model_options
        .get(settings.model.as_str())
        .map(|s| s.split_whitespace().map(str::to_string).collect())
        .unwrap_or_default();
    Ok(KeyframeFile {
        time_s,
        latitude_deg: Some(latitude_deg),
        longitude_deg: Some(longitude_deg),
        altitude_m: Some(altitude_m),
        heading_deg: Some(flight.heading_rad().to_degrees()),
        pitch_deg: Some(flight.pitch_rad().to_degrees()),
        roll_deg: Some(0.0),
        fov_deg: Some(settings.vertical_fov_deg),
        sun_elevation_deg,
        sun_azimuth_deg,
        utc,
        atmosphere: Some(settings.preset.clone()),
        aerosol_scale: Some(settings.aerosol_scale),
        ground_albedo: Some(settings.ground_albedo),
        model: Some(settings.model),
        set: Some(set),
        exposure: Some(settings.exposure_ev100),
        auto_exposure: Some(settings.exposure_mode == ExposureMode::Auto),
        terrain: Some(settings.terrain && terrain_fits(&atmosphere)),
        exaggeration: Some(settings.exaggeration),
        ..KeyframeFile::default()
    })
}

/// The sun clock's UTC seconds since 2000-01-01 as a TOML date-time (to the nanosecond).
pub fn utc_datetime(utc_s: f64) -> Datetime {
    let t = date_time_of(utc_s);
    let whole = t.second.floor();
    let nanosecond = (((t.second - whole) * 1e9).round() as u32).min(999_999_999);
    Datetime {
        date: Some(Date {
            year: t.year as u16,
            month: t.month as u8,
            day: t.day as u8,
        }),
        time: Some(Time {
            hour: t.hour as u8,
            minute: t.minute as u8,
            second: Some(whole as u8),
            nanosecond: Some(nanosecond),
        }),
        offset: Some(Offset::Z),
    }
}
