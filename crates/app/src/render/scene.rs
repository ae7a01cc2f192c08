//! A scene: everything one frame of `atmos render` needs, from the command line's flags
//! or a TOML file with the same fields (`--scene FILE.toml`; flags given as well override
//! the file's fields). Checked field by field, with errors naming the flag.

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::limits::MAX_ALTITUDE_M;
use atmosphere_core::atmosphere::presets;
use atmosphere_core::atmosphere::text_file::{TOML_LIMITS, read_text};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::registry::check_settings;
use atmosphere_core::models::sky_model::ModelSettings;
use atmosphere_core::optics::sea_surface::{DEFAULT_WIND_M_S, check_wind};
use clap::Args;
use glam::DQuat;
use render_wgpu::frame::{
    LocalView, MAX_EXAGGERATION, MAX_SIDE_PX, TerrainOptions, location_rotation,
};
use render_wgpu::{Frame, Renderer};
use serde::{Deserialize, Serialize};

use super::cloud_flags::CloudFlags;
use super::volume_flags::VolumeFlags;
use crate::location_flags::{LocationFlags, check_lat_lon};

/// Zenith angles (view and sun), degrees: beyond them an angle would be wrapped.
pub const ZENITH_DEG: [f64; 2] = [0.0, 180.0];

/// Azimuths (view and sun), degrees: one turn either way.
pub const AZIMUTH_DEG: [f64; 2] = [-360.0, 360.0];

/// Exposure values: from starlight (about -10) past the sun's disk (about 30), with the
/// scale 1 / (1.2 * 2^EV) well within f32 (1e-45 to 3e38).
pub const EXPOSURE_EV100: [f64; 2] = [-60.0, 100.0];

/// The fields of a scene; every one optional here, the required ones checked by
/// [`Scene::frame`].
#[derive(Clone, Debug, Default, PartialEq, Args, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Scattering model (every model but the reference is on the GPU); the flag is
    /// `RenderArgs::model`, which a beams scene reads as a beam method.
    #[arg(skip)]
    pub model: Option<ModelId>,
    /// Camera altitude above the ground, m, in [0, 1e10].
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub altitude_m: Option<f64>,
    /// Sun zenith angle, degrees, in [0, 180] (90 = on the horizon).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub sun_zenith_deg: Option<f64>,
    /// Sun azimuth, degrees, in [-360, 360] [default: 0]. With a location (--latitude-deg, --longitude-deg)
    /// the azimuths are geographic (from north towards east); without one the camera is
    /// above the north pole and azimuths are measured from longitude 0 towards 90 deg east.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub sun_azimuth_deg: Option<f64>,
    /// View zenith angle of the image's centre, degrees, in [0, 180] [default: 90, the
    /// horizon].
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub view_zenith_deg: Option<f64>,
    /// View azimuth of the image's centre, degrees, in [-360, 360] [default: 0].
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub view_azimuth_deg: Option<f64>,
    /// Vertical field of view, degrees, in (0, 180) [default: 60].
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub fov_deg: Option<f64>,
    /// Image width, px [default: 1280].
    #[arg(long, value_name = "PX")]
    pub width: Option<u32>,
    /// Image height, px [default: 720].
    #[arg(long, value_name = "PX")]
    pub height: Option<u32>,
    /// Atmosphere: a preset (earth, clear, hazy, mars) or a TOML file [default: earth].
    #[arg(long, value_name = "PRESET|FILE.toml")]
    pub atmosphere: Option<String>,
    /// Exposure value at ISO 100, in [-60, 100]: luminance is scaled by 1 / (1.2 * 2^EV)
    /// before the filmic curve [default: 14].
    #[arg(long, value_name = "EV100", allow_negative_numbers = true)]
    pub exposure: Option<f64>,
    /// Latitude of the camera, degrees north (the flag: [`LocationFlags`]).
    #[arg(skip)]
    pub latitude_deg: Option<f64>,
    /// Longitude of the camera, degrees east (the flag: [`LocationFlags`]).
    #[arg(skip)]
    pub longitude_deg: Option<f64>,
    /// Draw the Earth's terrain (assets/earth) over the planet, which must then be the
    /// Earth's size; the altitude is then above sea level and must clear the terrain
    /// [default: false].
    #[arg(long, value_name = "BOOL", num_args = 0..=1, default_missing_value = "true")]
    pub terrain: Option<bool>,
    /// Light shafts, the terrain's shadow in the air (`on` or `off`; with --terrain only)
    /// [default: on].
    #[arg(long, value_name = "ON_OFF", value_parser = parse_on_off)]
    pub shafts: Option<bool>,
    /// Vertical exaggeration of the terrain, in (0, 100] [default: 1].
    #[arg(long, value_name = "K")]
    pub exaggeration: Option<f64>,
    /// Wind speed over the sea, m/s, in [0, 20]: the roughness of the sun's glint on the
    /// water (Cox and Munk 1954) [default: 5].
    #[arg(long, value_name = "M_S")]
    pub wind_m_s: Option<f64>,
    /// A model setting as key=value (repeat the flag), e.g. `--set samples=32`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub set: Vec<String>,
    /// The cloud layer (`--clouds` and the `--cloud-*` flags; a `[clouds]` table in a
    /// scene file).
    #[command(flatten)]
    #[serde(default, skip_serializing_if = "CloudFlags::is_empty")]
    pub clouds: CloudFlags,
    /// Rain and ice volumes (`--rain`, `--cirrus` and their flags; a `[volumes]` table).
    #[command(flatten)]
    #[serde(default, skip_serializing_if = "VolumeFlags::is_empty")]
    pub volumes: VolumeFlags,
}

impl Scene {
    /// The scene of a TOML file; a relative atmosphere file is looked up next to it.
    pub fn load(path: &Path) -> anyhow::Result<Scene> {
        let text = read_text(path, TOML_LIMITS).context("--scene")?;
        Scene::parse(&text, path)
    }

    /// The scene of the TOML text of the file at `path` (named in errors; a relative
    /// atmosphere file is looked up next to it).
    pub fn parse(text: &str, path: &Path) -> anyhow::Result<Scene> {
        let mut scene: Scene =
            toml::from_str(text).with_context(|| format!("scene {}", path.display()))?;
        if let (Some(a), Some(dir)) = (&scene.atmosphere, path.parent())
            && Atmosphere::preset(a).is_err()
            && Path::new(a).is_relative()
        {
            scene.atmosphere = Some(dir.join(a).display().to_string());
        }
        Ok(scene)
    }

    /// This scene with the latitude and longitude of `location`: clap fills the other
    /// fields of the command line's scene, these two come from the shared place flags.
    pub fn at(self, location: &LocationFlags) -> Scene {
        Scene {
            latitude_deg: location.latitude_deg,
            longitude_deg: location.longitude_deg,
            ..self
        }
    }

    /// This scene with every field that `flags` sets replaced; settings are appended.
    pub fn overridden_by(self, flags: Scene) -> Scene {
        let mut set = self.set;
        set.extend(flags.set);
        Scene {
            model: flags.model.or(self.model),
            altitude_m: flags.altitude_m.or(self.altitude_m),
            sun_zenith_deg: flags.sun_zenith_deg.or(self.sun_zenith_deg),
            sun_azimuth_deg: flags.sun_azimuth_deg.or(self.sun_azimuth_deg),
            view_zenith_deg: flags.view_zenith_deg.or(self.view_zenith_deg),
            view_azimuth_deg: flags.view_azimuth_deg.or(self.view_azimuth_deg),
            fov_deg: flags.fov_deg.or(self.fov_deg),
            width: flags.width.or(self.width),
            height: flags.height.or(self.height),
            atmosphere: flags.atmosphere.or(self.atmosphere),
            exposure: flags.exposure.or(self.exposure),
            latitude_deg: flags.latitude_deg.or(self.latitude_deg),
            longitude_deg: flags.longitude_deg.or(self.longitude_deg),
            terrain: flags.terrain.or(self.terrain),
            shafts: flags.shafts.or(self.shafts),
            exaggeration: flags.exaggeration.or(self.exaggeration),
            wind_m_s: flags.wind_m_s.or(self.wind_m_s),
            set,
            clouds: self.clouds.overridden_by(flags.clouds),
            volumes: self.volumes.overridden_by(flags.volumes),
        }
    }

    /// The scene with every default filled in, as written into EXR headers.
    pub fn resolved(&self) -> anyhow::Result<Scene> {
        let required = |value: Option<f64>, flag: &str| {
            value.with_context(|| format!("--{flag} is required (or its field in a --scene file)"))
        };
        Ok(Scene {
            model: Some(
                self.model
                    .context("--model is required (or `model = ...` in a --scene file)")?,
            ),
            altitude_m: Some(required(self.altitude_m, "altitude-m")?),
            sun_zenith_deg: Some(required(self.sun_zenith_deg, "sun-zenith-deg")?),
            sun_azimuth_deg: Some(self.sun_azimuth_deg.unwrap_or(0.0)),
            view_zenith_deg: Some(self.view_zenith_deg.unwrap_or(90.0)),
            view_azimuth_deg: Some(self.view_azimuth_deg.unwrap_or(0.0)),
            fov_deg: Some(self.fov_deg.unwrap_or(60.0)),
            width: Some(self.width.unwrap_or(1280)),
            height: Some(self.height.unwrap_or(720)),
            atmosphere: Some(self.atmosphere.clone().unwrap_or_else(|| "earth".into())),
            exposure: Some(self.exposure.unwrap_or(14.0)),
            latitude_deg: self.latitude_deg,
            longitude_deg: self.longitude_deg,
            terrain: Some(self.terrain.unwrap_or(false)),
            shafts: Some(self.shafts.unwrap_or(true)),
            exaggeration: Some(self.exaggeration.unwrap_or(1.0)),
            wind_m_s: Some(self.wind_m_s.unwrap_or(DEFAULT_WIND_M_S)),
            set: self.set.clone(),
            clouds: self.clouds.clone(),
            volumes: self.volumes.clone(),
        })
    }

    /// The frame of a [resolved](Scene::resolved) scene; errors name the flag at fault.
    pub fn frame(&self) -> anyhow::Result<Frame> {
        let s = self.resolved()?;
        let value = |v: Option<f64>| v.unwrap_or(f64::NAN);
        let finite = |v: f64, flag: &str| {
            if v.is_finite() {
                Ok(v)
            } else {
                bail!("--{flag} must be a finite number, got {v}")
            }
        };
        let altitude_m = finite(value(s.altitude_m), "altitude-m")?;
        if altitude_m < 0.0 {
            bail!("--altitude-m {altitude_m} is below the ground (must be >= 0)");
        }
        if altitude_m > MAX_ALTITUDE_M {
            bail!("--altitude-m {altitude_m:e} must be at most {MAX_ALTITUDE_M:e} m");
        }
        let fov_deg = finite(value(s.fov_deg), "fov-deg")?;
        if !(fov_deg > 0.0 && fov_deg < 180.0) {
            bail!("--fov-deg {fov_deg} must lie strictly between 0 and 180");
        }
        let within = |v: Option<f64>, flag: &str, [low, high]: [f64; 2], unit: &str| {
            let v = finite(value(v), flag)?;
            if !(low..=high).contains(&v) {
                bail!("--{flag} {v} must lie in [{low}, {high}]{unit}");
            }
            Ok(v)
        };
        let angle = |v, flag, range| within(v, flag, range, " degrees");
        let view = LocalView {
            altitude_m,
            view_zenith_deg: angle(s.view_zenith_deg, "view-zenith-deg", ZENITH_DEG)?,
            view_azimuth_deg: angle(s.view_azimuth_deg, "view-azimuth-deg", AZIMUTH_DEG)?,
            sun_zenith_deg: angle(s.sun_zenith_deg, "sun-zenith-deg", ZENITH_DEG)?,
            sun_azimuth_deg: angle(s.sun_azimuth_deg, "sun-azimuth-deg", AZIMUTH_DEG)?,
        };
        let (width, height) = (s.width.unwrap_or(0), s.height.unwrap_or(0));
        for (side, flag) in [(width, "width"), (height, "height")] {
            if !(1..=MAX_SIDE_PX).contains(&side) {
                bail!("--{flag} {side} must be 1 to {MAX_SIDE_PX} px");
            }
        }
        let name = s.atmosphere.unwrap_or_default();
        let atmosphere = Atmosphere::from_preset_or_file(&name)
            .and_then(|a| a.check_real_time_range().map(|()| a))
            .with_context(|| format!("--atmosphere {name}"))?;
        // Geographic azimuths turn the other way (`location_rotation`): `turn`.
        let (place, turn) = match (s.latitude_deg, s.longitude_deg) {
            (Some(lat), Some(lon)) => {
                let (lat, lon) = check_lat_lon(lat, lon)?;
                (location_rotation(lat, lon), -1.0)
            }
            (None, None) => (DQuat::IDENTITY, 1.0),
            _ => bail!("--latitude-deg and --longitude-deg go together"),
        };
        let view = LocalView {
            view_azimuth_deg: turn * view.view_azimuth_deg,
            sun_azimuth_deg: turn * view.sun_azimuth_deg,
            ..view
        };
        let terrain = match s.terrain {
            Some(true) => {
                let earth_m = presets::earth().bottom_radius_m;
                if atmosphere.bottom_radius_m != earth_m {
                    bail!(
                        "--terrain draws the Earth's relief, but --atmosphere {name} has a ground radius of {} m, not the Earth's {earth_m} m: leave out --terrain",
                        atmosphere.bottom_radius_m
                    );
                }
                let exaggeration = finite(value(s.exaggeration), "exaggeration")?;
                if !(exaggeration > 0.0 && exaggeration <= MAX_EXAGGERATION) {
                    bail!("--exaggeration {exaggeration} must lie in (0, {MAX_EXAGGERATION}]");
                }
                let wind_m_s = value(s.wind_m_s);
                check_wind(wind_m_s).map_err(|e| anyhow::anyhow!("--wind-m-s: {e}"))?;
                Some(TerrainOptions {
                    exaggeration,
                    wind_m_s,
                    shafts: s.shafts.unwrap_or(true),
                    ..TerrainOptions::default()
                })
            }
            _ => None,
        };
        // The rotation to a place may round a camera on the ground a hair below it.
        let mut camera_m = place * view.position_m(atmosphere.bottom_radius_m);
        let radius_m = atmosphere.bottom_radius_m + altitude_m;
        if camera_m.length() < radius_m {
            camera_m *= radius_m / camera_m.length() * (1.0 + 4.0 * f64::EPSILON);
        }
        let model = s
            .model
            .context("--model is required (or `model = ...` in a --scene file)")?;
        let settings = ModelSettings {
            options: ModelOptions::parse(&s.set)?,
            ..ModelSettings::default()
        };
        Renderer::check_model(model)?;
        check_settings(model, &settings)?;
        // A camera inside the terrain is refused by the renderer, which has the heights.
        Ok(Frame {
            camera_position_m: camera_m,
            orientation: place * view.orientation(),
            vertical_fov_deg: fov_deg,
            sun_direction: place * view.sun_direction(),
            atmosphere,
            model,
            settings,
            exposure_ev100: within(s.exposure, "exposure", EXPOSURE_EV100, "")?,
            width,
            height,
            terrain,
        })
    }
}

/// Where a frame goes: the output file and its kind, from the extension.
#[derive(Clone, Debug, PartialEq)]
pub enum Output {
    /// Linear HDR radiance (linear sRGB in cd/m^2, f32) with the scene in the header.
    Exr(PathBuf),
    /// The tone-mapped 8-bit sRGB image.
    Png(PathBuf),
}

impl Output {
    /// The output of `path`, by its extension (`.exr` or `.png`, any case).
    pub fn from_path(path: &Path) -> anyhow::Result<Output> {
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match extension.as_deref() {
            Some("exr") => Ok(Output::Exr(path.to_path_buf())),
            Some("png") => Ok(Output::Png(path.to_path_buf())),
            _ => bail!(
                "--out {}: unknown image type; the file name must end in .exr (linear HDR) or .png (tone-mapped)",
                path.display()
            ),
        }
    }
}

/// `on` or `off` (also `true` or `false`) as a switch, for `--shafts`.
fn parse_on_off(text: &str) -> Result<bool, String> {
    match text {
        "on" | "true" => Ok(true),
        "off" | "false" => Ok(false),
        _ => Err(format!("{text:?} is not a switch: use on or off")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        Scene {
            model: Some(ModelId::Nishita),
            altitude_m: Some(10.0),
            sun_zenith_deg: Some(45.0),
            ..Scene::default()
        }
    }

    #[test]
    fn flags_override_the_file_and_defaults_fill_the_rest() {
        let file: Scene = toml::from_str(
            "model = \"riley\"\naltitude_m = 5.0\nsun_zenith_deg = 30.0\nset = [\"a=1\"]\n",
        )
        .unwrap();
        let merged = file.overridden_by(Scene {
            model: Some(ModelId::Nishita),
            set: vec!["b=2".into()],
            ..Scene::default()
        });
        assert_eq!(merged.model, Some(ModelId::Nishita));
        assert_eq!(merged.altitude_m, Some(5.0));
        assert_eq!(merged.set, ["a=1", "b=2"]);
        let resolved = merged.resolved().unwrap();
        assert_eq!((resolved.width, resolved.height), (Some(1280), Some(720)));
        // The resolved scene reads back as the same scene.
        let text = toml::to_string(&resolved).unwrap();
        assert_eq!(toml::from_str::<Scene>(&text).unwrap(), resolved);
        assert!(toml::from_str::<Scene>("colour = 1").is_err());
    }

    #[test]
    fn shipped_scenes_are_frames_of_models_on_the_gpu() {
        // The planet's scenes; beams scenes (their own format) live in a folder of theirs.
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes");
        let mut count = 0;
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                continue;
            }
            let frame = Scene::load(&path).unwrap().frame().unwrap();
            assert!(
                render_wgpu::Renderer::check_model(frame.model).is_ok(),
                "{}",
                path.display()
            );
            count += 1;
        }
        assert!(count >= 2);
    }

    #[test]
    fn bad_fields_are_named() {
        let err = |s: Scene| s.frame().unwrap_err().to_string();
        assert!(err(Scene::default()).contains("--model is required"));
        assert!(
            err(Scene {
                fov_deg: Some(180.0),
                ..scene()
            })
            .contains("--fov-deg")
        );
        assert!(
            err(Scene {
                altitude_m: Some(-1.0),
                ..scene()
            })
            .contains("below the ground")
        );
        assert!(
            err(Scene {
                width: Some(0),
                ..scene()
            })
            .contains("--width")
        );
        assert!(
            err(Scene {
                atmosphere: Some("venus".into()),
                ..scene()
            })
            .contains("venus")
        );
        let windy = err(Scene {
            terrain: Some(true),
            wind_m_s: Some(30.0),
            ..scene()
        });
        assert!(
            windy.contains("--wind-m-s") && windy.contains("[0, 20]"),
            "{windy}"
        );
        for (field, flag) in [
            (
                Scene {
                    exposure: Some(200.0),
                    ..scene()
                },
                "--exposure 200 must lie in [-60, 100]",
            ),
            (
                Scene {
                    altitude_m: Some(1.7e308),
                    ..scene()
                },
                "--altitude-m 1.7e308 must be at most 1e10 m",
            ),
            (
                Scene {
                    view_zenith_deg: Some(-5.0),
                    ..scene()
                },
                "--view-zenith-deg -5 must lie in [0, 180]",
            ),
            (
                Scene {
                    view_zenith_deg: Some(1000.0),
                    ..scene()
                },
                "--view-zenith-deg 1000 must lie in [0, 180]",
            ),
            (
                Scene {
                    sun_zenith_deg: Some(181.0),
                    ..scene()
                },
                "--sun-zenith-deg 181 must lie in [0, 180]",
            ),
            (
                Scene {
                    sun_azimuth_deg: Some(720.0),
                    ..scene()
                },
                "--sun-azimuth-deg 720 must lie in [-360, 360]",
            ),
            (
                Scene {
                    view_azimuth_deg: Some(-361.0),
                    ..scene()
                },
                "--view-azimuth-deg -361 must lie in [-360, 360]",
            ),
            (
                Scene {
                    latitude_deg: Some(0.0),
                    longitude_deg: Some(1000.0),
                    ..scene()
                },
                "--longitude-deg 1000 must lie in [-180, 180]",
            ),
            (
                Scene {
                    terrain: Some(true),
                    atmosphere: Some("mars".into()),
                    ..scene()
                },
                "--terrain draws the Earth's relief, but --atmosphere mars has a ground radius of 3389500 m",
            ),
        ] {
            let e = err(field);
            assert!(e.contains(flag), "{e}");
        }
        assert!(
            Scene {
                terrain: Some(true),
                atmosphere: Some("hazy".into()),
                ..scene()
            }
            .frame()
            .is_ok()
        );
        assert!(scene().frame().is_ok());
        // On the ground at a place: the rotation must not put the camera below it.
        for (lat, lon) in [(46.0, 7.8), (-33.9, -160.0), (0.1, 179.9)] {
            let frame = Scene {
                altitude_m: Some(0.0),
                latitude_deg: Some(lat),
                longitude_deg: Some(lon),
                ..scene()
            }
            .frame()
            .unwrap();
            frame.validate().unwrap();
        }
        assert!(
            Output::from_path(Path::new("a.jpg"))
                .unwrap_err()
                .to_string()
                .contains(".png")
        );
        assert_eq!(
            Output::from_path(Path::new("a.EXR")).unwrap(),
            Output::Exr("a.EXR".into())
        );
    }

    #[test]
    fn the_shafts_switch_reads_on_and_off_and_names_anything_else() {
        assert_eq!(parse_on_off("on"), Ok(true));
        assert_eq!(parse_on_off("off"), Ok(false));
        let e = parse_on_off("maybe").unwrap_err();
        assert!(
            e.contains("\"maybe\" is not a switch: use on or off"),
            "{e}"
        );
    }
}
