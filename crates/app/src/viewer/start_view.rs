//! The flags of `atmos view` that set where and how the viewer starts (place, altitude,
//! heading and pitch, the sun's UTC time, model, terrain), applied over the saved or
//! default settings; each bad value is an error naming its flag.

use anyhow::bail;
use atmosphere_core::atmosphere::limits::MAX_ALTITUDE_M;
use render_wgpu::frame::MAX_EXAGGERATION;

use crate::cli::StartView;
use crate::location_flags::check_lat_lon;
use crate::viewer::settings::ViewerSettings;
use crate::viewer::sun_clock::SunMode;

/// Applies `start` to `settings`.
pub fn apply(start: &StartView, settings: &mut ViewerSettings) -> anyhow::Result<()> {
    let finite = |value: f64, flag: &str| {
        if value.is_finite() {
            Ok(value)
        } else {
            bail!("--{flag} must be a finite number, got {value}")
        }
    };
    if let Some(model) = &start.model {
        settings.model = *model;
    }
    if let (Some(lat), Some(lon)) = (start.location.latitude_deg, start.location.longitude_deg) {
        let (lat, lon) = check_lat_lon(lat, lon)?;
        settings.set_lat_lon_deg(lat, lon);
    }
    if let Some(altitude) = start.altitude_m {
        let altitude = finite(altitude, "altitude-m")?;
        if altitude < 0.0 {
            bail!("--altitude-m {altitude} is below sea level");
        }
        if altitude > MAX_ALTITUDE_M {
            bail!("--altitude-m {altitude:e} must be at most {MAX_ALTITUDE_M:e} m");
        }
        let radius = settings.atmosphere()?.bottom_radius_m;
        settings.set_altitude(altitude, radius);
    }
    if start.heading_deg.is_some() || start.pitch_deg.is_some() {
        let flight = settings.flight();
        let heading = finite(
            start
                .heading_deg
                .unwrap_or(flight.heading_rad().to_degrees()),
            "heading-deg",
        )?;
        let pitch = finite(
            start.pitch_deg.unwrap_or(flight.pitch_rad().to_degrees()),
            "pitch-deg",
        )?;
        if pitch.abs() > 89.0 {
            bail!("--pitch-deg {pitch} must lie within [-89, 89]");
        }
        settings.set_heading_pitch(heading, pitch);
    }
    if let Some(utc) = &start.utc {
        settings.sun_clock.set_date_time(utc)?;
        settings.sun_clock.mode = SunMode::Date;
    }
    if let Some(k) = start.exaggeration {
        if !(k.is_finite() && (1.0..=MAX_EXAGGERATION).contains(&k)) {
            bail!("--exaggeration {k} must lie in [1, {MAX_EXAGGERATION}]");
        }
        settings.exaggeration = k;
    }
    if start.clouds {
        settings.clouds.on = true;
    }
    if start.no_terrain {
        settings.terrain = false;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use atmosphere_core::models::id::ModelId;
    use atmosphere_core::sun_position::UtcDateTime;

    use crate::location_flags::LocationFlags;

    #[test]
    fn flags_set_the_place_view_sun_and_terrain() {
        let mut s = ViewerSettings::default();
        let start = StartView {
            model: Some(ModelId::Hillaire),
            location: LocationFlags {
                latitude_deg: Some(-33.9),
                longitude_deg: Some(-160.0),
            },
            altitude_m: Some(20_000.0),
            heading_deg: Some(90.0),
            pitch_deg: Some(-10.0),
            utc: Some(UtcDateTime::new(2024, 6, 21, 12, 0, 0.0).unwrap()),
            exaggeration: Some(5.0),
            no_terrain: true,
            clouds: true,
        };
        assert!(!s.clouds.on);
        apply(&start, &mut s).unwrap();
        assert!(s.clouds.on);
        let (lat, lon) = s.camera_lat_lon_deg();
        assert!(
            (lat + 33.9).abs() < 1e-9 && (lon + 160.0).abs() < 1e-9,
            "{lat} {lon}"
        );
        assert!((s.altitude_m(s.atmosphere().unwrap().bottom_radius_m) - 20_000.0).abs() < 1e-6);
        let flight = s.flight();
        assert!((flight.heading_rad().to_degrees() - 90.0).abs() < 1e-9);
        assert!((flight.pitch_rad().to_degrees() + 10.0).abs() < 1e-9);
        assert_eq!(s.sun_clock.mode, SunMode::Date);
        assert_eq!(s.sun_clock.date_time().month, 6);
        assert_eq!(
            (s.model, s.exaggeration, s.terrain),
            (ModelId::Hillaire, 5.0, false)
        );
    }

    #[test]
    fn bad_flags_are_named() {
        let err = |start: StartView| {
            apply(&start, &mut ViewerSettings::default())
                .unwrap_err()
                .to_string()
        };
        let e = err(StartView {
            altitude_m: Some(-5.0),
            ..StartView::default()
        });
        assert!(e.contains("--altitude-m"), "{e}");
        let e = err(StartView {
            altitude_m: Some(1e300),
            ..StartView::default()
        });
        assert!(
            e.contains("--altitude-m 1e300 must be at most 1e10 m"),
            "{e}"
        );
        let e = err(StartView {
            location: LocationFlags {
                latitude_deg: Some(95.0),
                longitude_deg: Some(0.0),
            },
            ..StartView::default()
        });
        assert!(e.contains("--latitude-deg"), "{e}");
        let e = err(StartView {
            location: LocationFlags {
                latitude_deg: Some(0.0),
                longitude_deg: Some(200.0),
            },
            ..StartView::default()
        });
        assert!(
            e.contains("--longitude-deg 200 must lie in [-180, 180]"),
            "{e}"
        );
        let e = err(StartView {
            pitch_deg: Some(f64::NAN),
            ..StartView::default()
        });
        assert!(e.contains("--pitch-deg"), "{e}");
        let e = err(StartView {
            exaggeration: Some(0.5),
            ..StartView::default()
        });
        assert!(e.contains("--exaggeration"), "{e}");
    }
}
