//! The viewer's settings: everything the side panel sets, kept between runs (eframe
//! storage, serde), and their conversion into a [`Frame`]. No window here, so the mapping
//! is unit-tested.

use anyhow::Context;
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::sky_model::ModelSettings;
use atmosphere_core::optics::phase::PhaseFunction;
use atmosphere_core::optics::sea_surface::DEFAULT_WIND_M_S;
use glam::DVec3;
use render_wgpu::Frame;
use render_wgpu::frame::{TerrainOptions, look_orientation, terrain_fits};
use render_wgpu::terrain::geo_grid;
use serde::{Deserialize, Serialize};

use crate::viewer::cloud_settings::CloudSettings;
use crate::viewer::default_view;
use crate::viewer::exposure::ExposureMode;
use crate::viewer::flight::{FlightState, local_frame};
use crate::viewer::optics_settings::OpticsSettings;
use crate::viewer::sun_clock::{SunClock, SunMode};

/// The atmosphere presets of the panel's combo box.
pub const PRESETS: &[&str] = &["earth", "clear", "hazy", "mars"];

/// The altitude slider's range, metres: 1 m to 1e8 m on a logarithmic scale.
pub const ALTITUDE_RANGE_M: (f64, f64) = (1.0, 1e8);

/// A "go to" button: a label, an altitude and the pitch to look at from there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GoTo {
    pub label: &'static str,
    pub altitude_m: f64,
    /// Degrees above the horizon: level near the ground, down at the planet from orbit.
    pub pitch_deg: f64,
}

/// The "go to" buttons: the ground, an airliner, the edge of space, low orbit,
/// geostationary orbit and the Moon's distance.
pub const GO_TO: &[GoTo] = &[
    GoTo {
        label: "ground 2 m",
        altitude_m: 2.0,
        pitch_deg: 10.0,
    },
    GoTo {
        label: "10 km",
        altitude_m: 1e4,
        pitch_deg: 0.0,
    },
    GoTo {
        label: "100 km",
        altitude_m: 1e5,
        pitch_deg: -10.0,
    },
    GoTo {
        label: "400 km",
        altitude_m: 4e5,
        pitch_deg: -30.0,
    },
    GoTo {
        label: "36,000 km",
        altitude_m: 3.6e7,
        pitch_deg: -89.0,
    },
    GoTo {
        label: "400,000 km",
        altitude_m: 4e8,
        pitch_deg: -89.0,
    },
];

/// The panel's state. Angles in degrees; the camera as a planet-centred position and a
/// unit view direction (those of [`FlightState`]) in the planet-fixed axes (x towards
/// latitude 0 longitude 0, y towards latitude 0 longitude 90 deg east, z towards the north
/// pole). Fields missing from older stored settings take their default values.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ViewerSettings {
    /// Sun elevation above the horizon at the camera's position (angles mode).
    pub sun_elevation_deg: f64,
    /// Sun azimuth from north towards east at the camera's position (angles mode).
    pub sun_azimuth_deg: f64,
    /// The sun's mode, date and time-lapse.
    pub sun_clock: SunClock,
    pub camera_position_m: [f64; 3],
    pub camera_forward: [f64; 3],
    pub vertical_fov_deg: f64,
    /// One of [`PRESETS`].
    pub preset: String,
    /// Factor on the preset's aerosol (Mie) coefficients.
    pub aerosol_scale: f64,
    /// Asymmetry of the aerosol phase function (replaces the preset's g).
    pub mie_g: f64,
    pub ozone: bool,
    pub ground_albedo: f64,
    /// One of `render_wgpu::sky::registry::GPU_MODELS`.
    pub model: ModelId,
    /// The model's quality settings as `key=value` items separated by spaces (e.g.
    /// `samples=32` for nishita; each model's keys are in docs/models/); empty: the
    /// paper's values. Kept per model.
    pub model_options: std::collections::BTreeMap<String, String>,
    /// The exposure; in automatic mode the last adapted value.
    pub exposure_ev100: f64,
    pub exposure_mode: ExposureMode,
    /// Draw the Earth's terrain over the planet (an Earth-sized one only).
    pub terrain: bool,
    /// Light shafts: the terrain's shadow in the air (docs/shafts.md).
    pub shafts: bool,
    /// Vertical exaggeration of the terrain (1 = true scale).
    pub exaggeration: f64,
    /// Wind speed over the sea, m/s (the glint's roughness), in
    /// [`atmosphere_core::optics::sea_surface::WIND_RANGE_M_S`].
    pub wind_m_s: f64,
    /// The cloud layer (the panel's "Clouds" section).
    pub clouds: CloudSettings,
    /// The rain shaft and cirrus layer (the panel's "Rain and ice" section).
    pub optics: OpticsSettings,
}

impl Default for ViewerSettings {
    fn default() -> ViewerSettings {
        let earth = Atmosphere::preset("earth").expect("the earth preset exists");
        let mut settings = ViewerSettings {
            sun_elevation_deg: 20.0,
            sun_azimuth_deg: 0.0,
            sun_clock: SunClock::default(),
            camera_position_m: [0.0; 3],
            camera_forward: [0.0; 3],
            vertical_fov_deg: 60.0,
            preset: "earth".into(),
            aerosol_scale: 1.0,
            mie_g: mie_g(&earth).unwrap_or(0.8),
            ozone: true,
            ground_albedo: earth.ground_albedo,
            model: ModelId::Hillaire,
            model_options: Default::default(),
            exposure_ev100: 14.0,
            exposure_mode: ExposureMode::default(),
            terrain: true,
            shafts: true,
            exaggeration: 1.0,
            wind_m_s: DEFAULT_WIND_M_S,
            clouds: CloudSettings::default(),
            optics: OpticsSettings::default(),
        };
        settings.reset_view();
        settings
    }
}

/// The asymmetry g of an aerosol phase function that has one.
fn mie_g(atmosphere: &Atmosphere) -> Option<f64> {
    match atmosphere.mie.phase {
        PhaseFunction::CornetteShanks { g } | PhaseFunction::HenyeyGreenstein { g } => Some(g),
        _ => None,
    }
}

/// Slider position (log10 of the altitude) of an altitude, clamped to the range.
pub fn altitude_to_slider(altitude_m: f64) -> f64 {
    altitude_m
        .clamp(ALTITUDE_RANGE_M.0, ALTITUDE_RANGE_M.1)
        .log10()
}

/// The altitude of a slider position (inverse of [`altitude_to_slider`]).
pub fn slider_to_altitude(slider: f64) -> f64 {
    10f64.powf(slider)
}

impl ViewerSettings {
    /// The atmosphere: the preset with the panel's changes, validated (the error names
    /// the field at fault).
    pub fn atmosphere(&self) -> anyhow::Result<Atmosphere> {
        let preset = Atmosphere::preset(&self.preset)
            .with_context(|| format!("atmosphere preset '{}'", self.preset))?;
        let mut atmosphere = preset.with_aerosol_scale(self.aerosol_scale);
        match &mut atmosphere.mie.phase {
            PhaseFunction::CornetteShanks { g } | PhaseFunction::HenyeyGreenstein { g } => {
                *g = self.mie_g
            }
            _ => {}
        }
        if !self.ozone {
            atmosphere.ozone.absorption_per_m = atmosphere.ozone.absorption_per_m.scaled(0.0);
        }
        atmosphere.ground_albedo = self.ground_albedo;
        atmosphere.validate()?;
        Ok(atmosphere)
    }

    /// Chooses preset `name`: its aerosol g and ground albedo, the aerosol scale 1 and
    /// ozone on; the camera keeps its altitude over the new planet's radius.
    pub fn set_preset(&mut self, name: &str) -> anyhow::Result<()> {
        let old_radius = self.atmosphere()?.bottom_radius_m;
        let preset = Atmosphere::preset(name).with_context(|| format!("preset '{name}'"))?;
        let altitude = self.altitude_m(old_radius);
        self.preset = name.to_string();
        self.aerosol_scale = 1.0;
        self.mie_g = mie_g(&preset).unwrap_or(self.mie_g);
        self.ozone = true;
        self.ground_albedo = preset.ground_albedo;
        self.set_altitude(altitude, preset.bottom_radius_m);
        Ok(())
    }

    /// The camera's flight state (at rest).
    pub fn flight(&self) -> FlightState {
        FlightState {
            position_m: DVec3::from_array(self.camera_position_m),
            velocity_m_s: DVec3::ZERO,
            forward: DVec3::from_array(self.camera_forward),
        }
    }

    /// Takes the camera of a flight state.
    pub fn set_flight(&mut self, flight: &FlightState) {
        self.camera_position_m = flight.position_m.to_array();
        self.camera_forward = flight.forward.to_array();
    }

    /// Altitude above a planet of radius `radius_m`.
    pub fn altitude_m(&self, radius_m: f64) -> f64 {
        DVec3::from_array(self.camera_position_m).length() - radius_m
    }

    /// Moves the camera to `altitude_m` above the same point, keeping heading and pitch.
    pub fn set_altitude(&mut self, altitude_m: f64, radius_m: f64) {
        let flight = self.flight();
        let (heading, pitch) = (flight.heading_rad(), flight.pitch_rad());
        let up = flight.position_m.normalize();
        self.set_flight(&FlightState::new(
            up * (radius_m + altitude_m.max(0.0)),
            heading,
            pitch,
        ));
    }

    /// Turns the camera to heading and pitch (degrees), keeping its position.
    pub fn set_heading_pitch(&mut self, heading_deg: f64, pitch_deg: f64) {
        let position = self.flight().position_m;
        self.set_flight(&FlightState::new(
            position,
            heading_deg.to_radians(),
            pitch_deg.to_radians(),
        ));
    }

    /// A "go to" button: its altitude and pitch, the same heading.
    pub fn go_to(&mut self, target: &GoTo, radius_m: f64) {
        let heading_deg = self.flight().heading_rad().to_degrees();
        self.set_altitude(target.altitude_m, radius_m);
        self.set_heading_pitch(heading_deg, target.pitch_deg);
    }

    /// The bottom radius of the preset (the Earth's if the preset is unknown).
    pub fn bottom_radius_m(&self) -> f64 {
        Atmosphere::preset(&self.preset).map_or(6_360_000.0, |a| a.bottom_radius_m)
    }

    /// Camera and sun of the default view ([`default_view`]) over this preset's planet.
    pub fn reset_view(&mut self) {
        self.set_flight(&default_view::camera(self.bottom_radius_m()));
        self.sun_clock = default_view::sun_clock();
    }

    /// The camera's latitude and longitude (geocentric), degrees.
    pub fn camera_lat_lon_deg(&self) -> (f64, f64) {
        let (lat, lon) = geo_grid::lat_lon(DVec3::from_array(self.camera_position_m));
        (lat.to_degrees(), lon.to_degrees())
    }

    /// Moves the camera above latitude and longitude (degrees, clamped to their ranges),
    /// keeping its distance from the centre (its altitude), heading and pitch.
    pub fn set_lat_lon_deg(&mut self, latitude_deg: f64, longitude_deg: f64) {
        let flight = self.flight();
        let (heading, pitch) = (flight.heading_rad(), flight.pitch_rad());
        let up = geo_grid::direction(
            latitude_deg.clamp(-90.0, 90.0).to_radians(),
            longitude_deg.clamp(-180.0, 180.0).to_radians(),
        );
        self.set_flight(&FlightState::new(
            up * flight.position_m.length(),
            heading,
            pitch,
        ));
    }

    /// The unit direction to the sun in planet axes: from the elevation and azimuth at
    /// the camera, or from the date, time and the camera's place.
    pub fn sun_direction(&self) -> anyhow::Result<DVec3> {
        match self.sun_clock.mode {
            SunMode::Angles => {
                let (east, north, up) = local_frame(DVec3::from_array(self.camera_position_m));
                let (elevation, azimuth) = (
                    self.sun_elevation_deg.to_radians(),
                    self.sun_azimuth_deg.to_radians(),
                );
                Ok(
                    (north * azimuth.cos() + east * azimuth.sin()) * elevation.cos()
                        + up * elevation.sin(),
                )
            }
            SunMode::Date => {
                let (lat, lon) = self.camera_lat_lon_deg();
                Ok(self.sun_clock.sun(lat, lon)?.direction_planet())
            }
        }
    }

    /// The sun's elevation and azimuth (from north towards east) at the camera, degrees.
    pub fn sun_angles_deg(&self) -> anyhow::Result<(f64, f64)> {
        let sun = self.sun_direction()?;
        let (east, north, up) = local_frame(DVec3::from_array(self.camera_position_m));
        let elevation = sun.dot(up).clamp(-1.0, 1.0).asin().to_degrees();
        let azimuth = sun.dot(east).atan2(sun.dot(north)).to_degrees();
        Ok((elevation, azimuth))
    }

    /// Chooses where the sun comes from; into angles mode the sun stays where it was.
    pub fn set_sun_mode(&mut self, mode: SunMode) {
        if mode == SunMode::Angles
            && let Ok((elevation, azimuth)) = self.sun_angles_deg()
        {
            self.sun_elevation_deg = elevation;
            self.sun_azimuth_deg = azimuth;
        }
        self.sun_clock.mode = mode;
    }

    /// The current model's quality settings, parsed; an error names the bad item.
    pub fn parsed_model_options(&self) -> anyhow::Result<ModelOptions> {
        let text = self
            .model_options
            .get(self.model.as_str())
            .map_or("", String::as_str);
        let items: Vec<&str> = text.split_whitespace().collect();
        ModelOptions::parse(&items).with_context(|| format!("{} settings '{text}'", self.model))
    }

    /// The frame these settings show at `width` x `height` pixels.
    pub fn frame(&self, width: u32, height: u32) -> anyhow::Result<Frame> {
        let atmosphere = self.atmosphere()?;
        let flight = self.flight();
        let (_, north, up) = local_frame(flight.position_m);
        let sun_direction = self.sun_direction()?;
        let orientation = look_orientation(flight.forward, up)
            .or_else(|| look_orientation(flight.forward, north))
            .context("the camera's view direction is not a direction")?;
        Ok(Frame {
            camera_position_m: flight.position_m,
            orientation,
            vertical_fov_deg: self.vertical_fov_deg,
            sun_direction,
            model: self.model,
            settings: ModelSettings {
                options: self.parsed_model_options()?,
                ..ModelSettings::default()
            },
            exposure_ev100: self.exposure_ev100,
            width,
            height,
            terrain: (self.terrain && terrain_fits(&atmosphere)).then_some(TerrainOptions {
                exaggeration: self.exaggeration,
                wind_m_s: self.wind_m_s,
                // A frame of the viewer never waits for terrain work.
                wait_for_chunks: false,
                shafts: self.shafts,
            }),
            atmosphere,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quality_settings_reach_the_frame_per_model_and_bad_ones_are_named() {
        let mut s = ViewerSettings {
            model: ModelId::Nishita,
            ..ViewerSettings::default()
        };
        s.model_options
            .insert("nishita".into(), " samples=32  ".into());
        let frame = s.frame(4, 2).unwrap();
        let nishita = atmosphere_core::models::nishita::NishitaSettings::from_options(
            &frame.settings.options,
        )
        .unwrap();
        assert_eq!(nishita.view_samples, 32);
        // Another model keeps its own (none: the paper's values).
        s.model = ModelId::Hillaire;
        assert_eq!(
            s.frame(4, 2).unwrap().settings.options,
            ModelOptions::default()
        );
        s.model_options
            .insert("hillaire".into(), "ms_samples".into());
        let err = format!("{:#}", s.frame(4, 2).unwrap_err());
        assert!(err.contains("ms_samples"), "{err}");
    }

    #[test]
    fn the_altitude_slider_is_logarithmic_and_round_trips() {
        assert_eq!(altitude_to_slider(1.0), 0.0);
        assert_eq!(altitude_to_slider(1e8), 8.0);
        assert_eq!(altitude_to_slider(0.1), 0.0, "clamped to 1 m");
        for altitude in [1.0, 2.0, 1e4, 4e5, 3.6e7, 1e8] {
            let back = slider_to_altitude(altitude_to_slider(altitude));
            assert!(
                (back / altitude - 1.0).abs() < 1e-12,
                "{altitude} -> {back}"
            );
        }
    }

    #[test]
    fn go_to_buttons_set_altitude_and_pitch_and_keep_heading() {
        let mut settings = ViewerSettings::default();
        let radius = settings.atmosphere().unwrap().bottom_radius_m;
        let heading = settings.flight().heading_rad();
        for target in GO_TO {
            settings.go_to(target, radius);
            let frame = settings.frame(64, 32).unwrap();
            frame.validate().unwrap();
            let altitude = frame.camera_position_m.length() - radius;
            assert!(
                (altitude / target.altitude_m - 1.0).abs() < 1e-9,
                "{}",
                target.label
            );
            let flight = settings.flight();
            assert!((flight.pitch_rad().to_degrees() - target.pitch_deg).abs() < 1e-6);
            assert!(
                (flight.heading_rad() - heading).abs() < 1e-6,
                "{}",
                target.label
            );
            // The frame looks where the flight state looks.
            assert!((frame.axes()[2] - flight.forward).length() < 1e-9);
        }
    }

    #[test]
    fn presets_set_their_values_and_keep_the_altitude() {
        let mut settings = ViewerSettings::default();
        settings.go_to(&GO_TO[1], 6_360_000.0);
        for name in PRESETS {
            settings.set_preset(name).unwrap();
            let preset = Atmosphere::preset(name).unwrap();
            let atmosphere = settings.atmosphere().unwrap();
            assert_eq!(
                atmosphere, preset,
                "{name}: untouched settings give the preset"
            );
            let altitude = settings.altitude_m(preset.bottom_radius_m);
            assert!((altitude - 1e4).abs() < 1e-6, "{name}: {altitude}");
            // The Earth's relief is drawn on Earth-sized planets only, never on Mars.
            let frame = settings.frame(8, 4).unwrap();
            assert_eq!(frame.terrain.is_some(), *name != "mars", "{name}");
            frame.validate().unwrap();
        }
    }

    #[test]
    fn panel_changes_reach_the_frame_and_bad_values_are_reported() {
        let mut settings = ViewerSettings {
            aerosol_scale: 2.0,
            mie_g: 0.5,
            ozone: false,
            ground_albedo: 0.3,
            sun_elevation_deg: 90.0,
            sun_clock: SunClock {
                mode: SunMode::Angles,
                ..SunClock::default()
            },
            ..ViewerSettings::default()
        };
        let frame = settings.frame(8, 4).unwrap();
        let earth = Atmosphere::preset("earth").unwrap();
        assert_eq!(
            frame.atmosphere.mie.phase,
            PhaseFunction::CornetteShanks { g: 0.5 }
        );
        assert_eq!(frame.atmosphere.ground_albedo, 0.3);
        assert_eq!(frame.atmosphere.ozone.absorption_per_m.at(600.0), 0.0);
        let ratio =
            frame.atmosphere.mie.scattering_per_m.at(550.0) / earth.mie.scattering_per_m.at(550.0);
        assert!((ratio - 2.0).abs() < 1e-12);
        let up = frame.camera_position_m.normalize();
        assert!((frame.sun_direction - up).length() < 1e-12, "sun overhead");
        settings.ground_albedo = 1.5;
        let err = settings.frame(8, 4).unwrap_err().to_string();
        assert!(err.contains("ground_albedo"), "{err}");
    }

    #[test]
    fn latitude_and_longitude_round_trip_and_keep_altitude_and_view() {
        let mut settings = ViewerSettings::default();
        let radius = 6_360_000.0;
        settings.go_to(&GO_TO[1], radius);
        settings.set_heading_pitch(30.0, -5.0);
        for (lat, lon) in [(0.0, 0.0), (46.0, 7.7), (-33.9, 151.2), (60.0, -179.5)] {
            settings.set_lat_lon_deg(lat, lon);
            let (lat2, lon2) = settings.camera_lat_lon_deg();
            assert!((lat2 - lat).abs() < 1e-9 && (lon2 - lon).abs() < 1e-9);
            assert!((settings.altitude_m(radius) - 1e4).abs() < 1e-6);
            let flight = settings.flight();
            assert!((flight.heading_rad().to_degrees() - 30.0).abs() < 1e-6);
            assert!((flight.pitch_rad().to_degrees() + 5.0).abs() < 1e-6);
        }
        // The axes: latitude 0 longitude 90 E is +y, the north pole +z.
        settings.set_lat_lon_deg(0.0, 90.0);
        let up = DVec3::from_array(settings.camera_position_m).normalize();
        assert!((up - DVec3::Y).length() < 1e-12);
        settings.set_lat_lon_deg(95.0, 0.0);
        assert!(
            (settings.camera_lat_lon_deg().0 - 90.0).abs() < 1e-9,
            "clamped"
        );
    }

    /// The default view: date mode, the sun 3 to 7 deg up near the Alps, in the frame; a
    /// switch to angles mode keeps the sun where it is.
    #[test]
    fn the_default_view_is_near_sunset_and_modes_switch_smoothly() {
        let mut settings = ViewerSettings::default();
        assert_eq!(settings.sun_clock.mode, SunMode::Date);
        let (lat, lon) = settings.camera_lat_lon_deg();
        assert!((lat - 46.0).abs() < 0.5 && (lon - 7.7).abs() < 0.5);
        let (elevation, azimuth) = settings.sun_angles_deg().unwrap();
        assert!((3.0..=7.0).contains(&elevation), "{elevation}");
        let frame = settings.frame(64, 32).unwrap();
        frame.validate().unwrap();
        let before = frame.sun_direction;
        settings.set_sun_mode(SunMode::Angles);
        assert_eq!(
            (settings.sun_elevation_deg, settings.sun_azimuth_deg),
            (elevation, azimuth)
        );
        let after = settings.frame(64, 32).unwrap().sun_direction;
        assert!((after - before).length() < 1e-12);
        // Flying a quarter of the way round the planet in date mode changes the sun's
        // elevation; in angles mode it does not.
        settings.set_lat_lon_deg(lat, lon + 90.0);
        assert!((settings.sun_angles_deg().unwrap().0 - elevation).abs() < 1e-9);
        settings.set_sun_mode(SunMode::Date);
        let night = settings.sun_angles_deg().unwrap().0;
        assert!(night < -30.0, "{night}: 90 deg east it is night");
        // Reset view returns to the default camera and time.
        settings.reset_view();
        let default = ViewerSettings::default();
        assert_eq!(settings.camera_position_m, default.camera_position_m);
        assert_eq!(settings.camera_forward, default.camera_forward);
        assert_eq!(settings.sun_clock, default.sun_clock);
    }

    /// Settings stored before a field existed load, the missing fields at their defaults.
    #[test]
    fn older_settings_load_with_defaults() {
        let mut settings = ViewerSettings {
            model: ModelId::Riley,
            ..ViewerSettings::default()
        };
        settings.sun_clock.utc_s = 1e6;
        let mut table: toml::Table = toml::from_str(&toml::to_string(&settings).unwrap()).unwrap();
        table.remove("sun_clock").unwrap();
        table.remove("exposure_mode").unwrap();
        let loaded: ViewerSettings = table.try_into().unwrap();
        assert_eq!(loaded.model, ModelId::Riley);
        assert_eq!(loaded.sun_clock, ViewerSettings::default().sun_clock);
        assert_eq!(loaded.exposure_mode, ExposureMode::Auto);
        let back: ViewerSettings = toml::from_str(&toml::to_string(&settings).unwrap()).unwrap();
        assert_eq!(back, settings);
    }
}
