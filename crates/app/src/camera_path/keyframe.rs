//! Keyframes with every field known: each one carries over what the file leaves out from
//! the keyframe before, and is checked field by field (errors name the keyframe's line).

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{Context, bail};
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::limits::MAX_ALTITUDE_M;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::registry::check_settings;
use atmosphere_core::models::sky_model::ModelSettings;
use atmosphere_core::sun_position::UtcDateTime;
use glam::{DQuat, DVec3};
use render_wgpu::Renderer;
use render_wgpu::frame::{LocalView, MAX_EXAGGERATION, location_rotation, terrain_fits};
use render_wgpu::terrain::geo_grid;
use toml::value::{Datetime, Offset};

use crate::camera_path::file::{Easing, KeyframeFile};
use crate::render::scene::{AZIMUTH_DEG, EXPOSURE_EV100};
use crate::viewer::sun_clock::seconds_of;

/// Keyframe times, s: up to about eleven and a half days.
pub const TIME_S: [f64; 2] = [0.0, 1e6];
/// Pitch, degrees above the horizon.
pub const PITCH_DEG: [f64; 2] = [-90.0, 90.0];
/// Roll, degrees (positive turns the image's top towards its right).
pub const ROLL_DEG: [f64; 2] = [-180.0, 180.0];
/// Sun elevation above the camera's horizon, degrees.
pub const SUN_ELEVATION_DEG: [f64; 2] = [-90.0, 90.0];
/// Factor on the atmosphere's aerosol (Mie) coefficients, as on the viewer's slider.
pub const AEROSOL_SCALE: [f64; 2] = [0.0, 10.0];

/// Where the sun is at a keyframe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SunKey {
    /// Elevation and azimuth (from north towards east) at the camera, degrees.
    Angles {
        elevation_deg: f64,
        azimuth_deg: f64,
    },
    /// UTC, seconds since 2000-01-01 00:00 UTC (the viewer's sun clock).
    Utc(f64),
}

/// A keyframe with every field known and checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Key {
    pub time_s: f64,
    /// Unit vector from the planet's centre towards the camera.
    pub up: DVec3,
    pub altitude_m: f64,
    /// Heading (from north towards east) and pitch, degrees, given or from a look-at target.
    pub heading_deg: f64,
    pub pitch_deg: f64,
    pub roll_deg: f64,
    /// The planet-fixed point the camera looks at, m, if it looks at one.
    pub target_m: Option<DVec3>,
    /// The camera's rotation in the local frame of its place (`location_rotation`).
    pub local_orientation: DQuat,
    pub fov_deg: f64,
    pub sun: SunKey,
    /// A preset name or a file path (relative ones resolved against the path file).
    pub atmosphere: String,
    pub aerosol_scale: f64,
    /// `None`: the atmosphere's own albedo.
    pub ground_albedo: Option<f64>,
    pub model: ModelId,
    pub set: Vec<String>,
    pub settings: ModelSettings,
    pub exposure_ev100: f64,
    /// Metered from each frame instead of `exposure_ev100` (`atmos record`).
    pub auto_exposure: bool,
    pub terrain: bool,
    pub exaggeration: f64,
    /// How parameters move from the keyframe before to this one.
    pub easing: Easing,
}

/// `v` if it is finite and within `[low, high]`, else an error naming `field`.
pub fn within(field: &str, v: f64, [low, high]: [f64; 2]) -> anyhow::Result<f64> {
    if !(v.is_finite() && (low..=high).contains(&v)) {
        bail!("{field} {v} must lie in [{low}, {high}]");
    }
    Ok(v)
}

/// UTC seconds since 2000-01-01 of a TOML date-time (an offset is taken off; none: UTC).
pub fn utc_seconds(t: &Datetime) -> anyhow::Result<f64> {
    let (Some(date), Some(time)) = (t.date, t.time) else {
        bail!("utc {t} must be a date and a time, e.g. 2024-06-21T04:30:00Z");
    };
    let utc = UtcDateTime::new(
        i32::from(date.year),
        u32::from(date.month),
        u32::from(date.day),
        u32::from(time.hour),
        u32::from(time.minute),
        f64::from(time.second.unwrap_or(0)) + f64::from(time.nanosecond.unwrap_or(0)) * 1e-9,
    )
    .with_context(|| format!("utc {t}"))?;
    let offset_min = match t.offset {
        Some(Offset::Custom { minutes }) => f64::from(minutes),
        _ => 0.0,
    };
    Ok(seconds_of(&utc) - offset_min * 60.0)
}

/// The camera's place (unit up vector and altitude) from the keyframe, or `before`'s.
fn place(f: &KeyframeFile, before: Option<&Key>, radius_m: f64) -> anyhow::Result<(DVec3, f64)> {
    if let Some(p) = f.position_m {
        if f.latitude_deg.is_some() || f.longitude_deg.is_some() || f.altitude_m.is_some() {
            bail!("position_m goes without latitude_deg, longitude_deg and altitude_m");
        }
        let p = DVec3::from_array(p);
        let up = p
            .try_normalize()
            .filter(|_| p.is_finite())
            .context("position_m must be finite and not the planet's centre")?;
        let altitude = p.length() - radius_m;
        if !(0.0..=MAX_ALTITUDE_M).contains(&altitude) {
            bail!(
                "position_m is {altitude} m above the ground; it must be 0 to {MAX_ALTITUDE_M:e} m"
            );
        }
        return Ok((up, altitude));
    }
    let up = match (f.latitude_deg, f.longitude_deg) {
        (Some(lat), Some(lon)) => {
            let lat = within("latitude_deg", lat, [-90.0, 90.0])?;
            let lon = within("longitude_deg", lon, [-180.0, 180.0])?;
            geo_grid::direction(lat.to_radians(), lon.to_radians())
        }
        (None, None) => before
            .map(|k| k.up)
            .context("the first keyframe needs latitude_deg and longitude_deg, or position_m")?,
        _ => bail!("latitude_deg and longitude_deg go together"),
    };
    let altitude = match f.altitude_m {
        Some(a) => within("altitude_m", a, [0.0, MAX_ALTITUDE_M])?,
        None => before
            .map(|k| k.altitude_m)
            .context("the first keyframe needs altitude_m (or position_m)")?,
    };
    Ok((up, altitude))
}

/// The rotation from a place's local frame (x north, y west, z up) to planet axes.
pub fn place_rotation(up: DVec3) -> DQuat {
    let (lat, lon) = geo_grid::lat_lon(up);
    location_rotation(lat.to_degrees(), lon.to_degrees())
}

/// The local orientation looking at heading and pitch (degrees) with roll.
pub fn local_orientation(heading_deg: f64, pitch_deg: f64, roll_deg: f64) -> DQuat {
    let view = LocalView {
        altitude_m: 0.0,
        view_zenith_deg: 90.0 - pitch_deg,
        view_azimuth_deg: -heading_deg,
        sun_zenith_deg: 0.0,
        sun_azimuth_deg: 0.0,
    };
    view.orientation() * DQuat::from_axis_angle(-DVec3::Z, roll_deg.to_radians())
}

/// Heading and pitch, degrees, of the direction from `camera_m` to `target_m`.
pub fn aim_at(up: DVec3, camera_m: DVec3, target_m: DVec3) -> anyhow::Result<(f64, f64)> {
    let forward = (target_m - camera_m)
        .try_normalize()
        .context("the look-at target is the camera's own position")?;
    let local = place_rotation(up).inverse() * forward;
    let pitch = local.z.atan2(local.x.hypot(local.y)).to_degrees();
    let heading = if local.x.hypot(local.y) < 1e-12 {
        0.0
    } else {
        -local.y.atan2(local.x).to_degrees()
    };
    Ok((heading, pitch))
}

/// The keyframe `f` with what it leaves out taken from `before`; `origin` resolves a
/// relative atmosphere file; `atmospheres` caches the atmospheres read.
pub fn resolve(
    f: &KeyframeFile,
    before: Option<&Key>,
    origin: &Path,
    atmospheres: &mut BTreeMap<String, Atmosphere>,
) -> anyhow::Result<Key> {
    let time_s = within("time_s", f.time_s, TIME_S)?;
    if let Some(b) = before
        && time_s <= b.time_s
    {
        bail!(
            "time_s {time_s} must be after the keyframe before's {}",
            b.time_s
        );
    }
    let atmosphere = match &f.atmosphere {
        Some(a) if Atmosphere::preset(a).is_err() && Path::new(a).is_relative() => origin
            .parent()
            .map_or_else(|| a.clone(), |d| d.join(a).display().to_string()),
        Some(a) => a.clone(),
        None => before.map_or_else(|| "earth".into(), |k| k.atmosphere.clone()),
    };
    if !atmospheres.contains_key(&atmosphere) {
        let a = Atmosphere::from_preset_or_file(&atmosphere)
            .and_then(|a| a.check_real_time_range().map(|()| a))
            .with_context(|| format!("atmosphere {atmosphere}"))?;
        atmospheres.insert(atmosphere.clone(), a);
    }
    let planet = &atmospheres[&atmosphere];
    let radius_m = planet.bottom_radius_m;
    let (up, altitude_m) = place(f, before, radius_m)?;
    let camera_m = up * (radius_m + altitude_m);
    let roll_deg = match f.roll_deg {
        Some(r) => within("roll_deg", r, ROLL_DEG)?,
        None => before.map_or(0.0, |k| k.roll_deg),
    };
    let target = match (f.look_at, f.look_at_m) {
        (Some(_), Some(_)) => bail!("look_at and look_at_m cannot both be given"),
        (Some(g), None) => {
            let lat = within("look_at.latitude_deg", g.latitude_deg, [-90.0, 90.0])?;
            let lon = within("look_at.longitude_deg", g.longitude_deg, [-180.0, 180.0])?;
            let alt = within(
                "look_at.altitude_m",
                g.altitude_m,
                [-radius_m, MAX_ALTITUDE_M],
            )?;
            Some(geo_grid::direction(lat.to_radians(), lon.to_radians()) * (radius_m + alt))
        }
        (None, Some(p)) => {
            let p = DVec3::from_array(p);
            if !p.is_finite() || p.length() > radius_m + MAX_ALTITUDE_M {
                bail!("look_at_m must be finite and within {MAX_ALTITUDE_M:e} m of the ground");
            }
            Some(p)
        }
        // A target carries over until heading or pitch is given.
        (None, None) if f.heading_deg.is_none() && f.pitch_deg.is_none() => {
            before.and_then(|k| k.target_m)
        }
        (None, None) => None,
    };
    let (heading_deg, pitch_deg) = match target {
        Some(t) => {
            if f.heading_deg.is_some() || f.pitch_deg.is_some() {
                bail!("a look-at target goes without heading_deg and pitch_deg");
            }
            aim_at(up, camera_m, t)?
        }
        None => (
            match f.heading_deg {
                Some(h) => within("heading_deg", h, AZIMUTH_DEG)?,
                None => before.map_or(0.0, |k| k.heading_deg),
            },
            match f.pitch_deg {
                Some(p) => within("pitch_deg", p, PITCH_DEG)?,
                None => before.map_or(0.0, |k| k.pitch_deg),
            },
        ),
    };
    let fov_deg = match f.fov_deg {
        Some(v) if v.is_finite() && v > 0.0 && v < 180.0 => v,
        Some(v) => bail!("fov_deg {v} must lie strictly between 0 and 180"),
        None => before.map_or(60.0, |k| k.fov_deg),
    };
    let sun = match (f.sun_elevation_deg, f.sun_azimuth_deg, &f.utc) {
        (None, None, Some(t)) => SunKey::Utc(utc_seconds(t)?),
        (_, _, Some(_)) => {
            bail!("the sun is given by utc or by sun_elevation_deg and sun_azimuth_deg, not both")
        }
        (None, None, None) => before.map(|k| k.sun).context(
            "the first keyframe needs the sun: sun_elevation_deg and sun_azimuth_deg, or utc",
        )?,
        (e, a, None) => {
            let (e0, a0) = match before.map(|k| k.sun) {
                Some(SunKey::Angles {
                    elevation_deg,
                    azimuth_deg,
                }) => (Some(elevation_deg), Some(azimuth_deg)),
                _ => (None, None),
            };
            let e = e
                .or(e0)
                .context("sun_azimuth_deg needs sun_elevation_deg")?;
            let a = a
                .or(a0)
                .context("sun_elevation_deg needs sun_azimuth_deg")?;
            SunKey::Angles {
                elevation_deg: within("sun_elevation_deg", e, SUN_ELEVATION_DEG)?,
                azimuth_deg: within("sun_azimuth_deg", a, AZIMUTH_DEG)?,
            }
        }
    };
    let aerosol_scale = match f.aerosol_scale {
        Some(v) => within("aerosol_scale", v, AEROSOL_SCALE)?,
        None => before.map_or(1.0, |k| k.aerosol_scale),
    };
    let ground_albedo = match f.ground_albedo {
        Some(v) => Some(within("ground_albedo", v, [0.0, 1.0])?),
        None => before.and_then(|k| k.ground_albedo),
    };
    let model = match (f.model, before) {
        (Some(m), _) => m,
        (None, Some(k)) => k.model,
        (None, None) => bail!("the first keyframe needs model"),
    };
    Renderer::check_model(model)?;
    let set = match &f.set {
        Some(s) => s.clone(),
        None if f.model.is_some() => Vec::new(),
        None => before.map(|k| k.set.clone()).unwrap_or_default(),
    };
    let settings = ModelSettings {
        options: ModelOptions::parse(&set)?,
        ..ModelSettings::default()
    };
    check_settings(model, &settings)?;
    let exposure_ev100 = match f.exposure {
        Some(v) => within("exposure", v, EXPOSURE_EV100)?,
        None => before.map_or(14.0, |k| k.exposure_ev100),
    };
    let auto_exposure = f
        .auto_exposure
        .or(before.map(|k| k.auto_exposure))
        .unwrap_or(false);
    let terrain = f.terrain.or(before.map(|k| k.terrain)).unwrap_or(false);
    if terrain && !terrain_fits(planet) {
        bail!(
            "terrain draws the Earth's relief, but atmosphere {atmosphere} has a ground radius of {radius_m} m: set terrain = false"
        );
    }
    let exaggeration = match f.exaggeration {
        Some(v) if v.is_finite() && v > 0.0 && v <= MAX_EXAGGERATION => v,
        Some(v) => bail!("exaggeration {v} must lie in (0, {MAX_EXAGGERATION}]"),
        None => before.map_or(1.0, |k| k.exaggeration),
    };
    Ok(Key {
        time_s,
        up,
        altitude_m,
        heading_deg,
        pitch_deg,
        roll_deg,
        target_m: target,
        local_orientation: local_orientation(heading_deg, pitch_deg, roll_deg),
        fov_deg,
        sun,
        atmosphere,
        aerosol_scale,
        ground_albedo,
        model,
        set,
        settings,
        exposure_ev100,
        auto_exposure,
        terrain,
        exaggeration,
        easing: f.easing.or(before.map(|k| k.easing)).unwrap_or_default(),
    })
}
