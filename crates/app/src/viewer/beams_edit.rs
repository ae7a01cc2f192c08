//! The viewer's beams scene (docs/beams.md) as the panel edits it, without a window: the
//! shipped scenes listed, a scene file loaded, and the panel's edits of its lights
//! (position, direction, cone, intensity, colour, light map) and of its medium's
//! density applied to the file and checked into a [`BeamScene`] exactly as
//! `atmos render --scene` checks a file, so a bad value or a light map that does not
//! load comes back as the scene's error naming the field.

use std::path::{Path, PathBuf};

use atmosphere_core::atmosphere::spectral::Spectral;
use atmosphere_core::atmosphere::text_file::{TOML_LIMITS, read_text};
use atmosphere_core::beams::light_map::channel_weights;
use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::beams::scene_file::{LightFile, SceneFile};
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;

/// Where the shipped beams scenes are, relative to the working directory.
pub const SHIPPED_SCENES: &str = "assets/scenes/beams";

/// The range of the medium's density factor (it multiplies the file's scattering and
/// absorption coefficients; 0 is a clear medium).
pub const DENSITY_RANGE: [f64; 2] = [0.0, 100.0];
/// The range of a light's intensity factor (it multiplies the file's emission).
pub const INTENSITY_RANGE: [f64; 2] = [0.0, 1e4];

/// The wavelengths a tinted emission is tabulated at, nm: every 5 nm over the visible
/// range, as the scene's checks sample spectra (680, 550 and 440 nm among them).
fn tint_grid_nm() -> impl Iterator<Item = f64> {
    (0..=94).map(|i| 360.0 + 5.0 * f64::from(i))
}

/// The `.toml` files of `dir`, sorted by name; none where `dir` cannot be read.
pub fn scene_list(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut scenes: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml") && p.is_file())
        .collect();
    scenes.sort();
    scenes
}

/// The panel's edits of one light, over what the file gives.
#[derive(Clone, Debug, PartialEq)]
pub struct LightEdit {
    /// The light's kind as written in the file (`point`, `spot`, `parallel`).
    pub kind: &'static str,
    pub position_m: [f64; 3],
    /// The beam's axis (a spot's, a parallel light's); none for a point light.
    pub direction: Option<[f64; 3]>,
    /// A spot's cone half-angle, degrees (the scene checks (0, 89)).
    pub cone_deg: Option<f64>,
    /// The file's emission times this, in [`INTENSITY_RANGE`].
    pub intensity: f64,
    /// A tint of the emission, red, green and blue in [0, 1]: a transmission at 680,
    /// 550 and 440 nm, linear between them, as a light map's texel is.
    pub colour: [f64; 3],
    /// The light map's path relative to the scene file; empty for none.
    pub light_map: String,
}

impl LightEdit {
    fn of(light: &LightFile) -> LightEdit {
        let (kind, position_m, direction, cone_deg, map) = match light {
            LightFile::Point {
                position_m,
                light_map,
                ..
            } => ("point", *position_m, None, None, light_map),
            LightFile::Spot {
                position_m,
                direction,
                cone_deg,
                light_map,
                ..
            } => (
                "spot",
                *position_m,
                Some(*direction),
                Some(*cone_deg),
                light_map,
            ),
            LightFile::Parallel {
                position_m,
                direction,
                light_map,
                ..
            } => ("parallel", *position_m, Some(*direction), None, light_map),
        };
        LightEdit {
            kind,
            position_m,
            direction,
            cone_deg,
            intensity: 1.0,
            colour: [1.0; 3],
            light_map: map.clone().unwrap_or_default(),
        }
    }

    /// `emission` with the intensity and colour applied: unchanged where both are 1,
    /// else tabulated every 5 nm from 360 to 830 nm.
    fn emission(&self, field: &str, emission: &Spectral) -> Result<Spectral, String> {
        let [lo, hi] = INTENSITY_RANGE;
        if !(self.intensity.is_finite() && (lo..=hi).contains(&self.intensity)) {
            return Err(format!(
                "{field} intensity: {} must be in [{lo}, {hi}]",
                self.intensity
            ));
        }
        if let Some(c) = self.colour.iter().find(|c| !(0.0..=1.0).contains(*c)) {
            return Err(format!("{field} colour: {c} must be in [0, 1]"));
        }
        if self.intensity == 1.0 && self.colour == [1.0; 3] {
            return Ok(emission.clone());
        }
        let wavelengths_nm: Vec<f64> = tint_grid_nm().collect();
        let values = wavelengths_nm
            .iter()
            .map(|&l| {
                let w = channel_weights(l);
                let tint: f64 = (0..3).map(|k| w[k] * self.colour[k]).sum();
                emission.at(l) * self.intensity * tint
            })
            .collect();
        Ok(Spectral::Table {
            wavelengths_nm,
            values,
        })
    }

    /// `light` with these edits.
    fn apply(&self, field: &str, light: &LightFile) -> Result<LightFile, String> {
        let mut light = light.clone();
        let map = (!self.light_map.trim().is_empty()).then(|| self.light_map.trim().to_string());
        match &mut light {
            LightFile::Point {
                position_m,
                intensity_w_sr_nm,
                light_map,
                ..
            } => {
                *position_m = self.position_m;
                *intensity_w_sr_nm = self.emission(field, intensity_w_sr_nm)?;
                *light_map = map;
            }
            LightFile::Spot {
                position_m,
                direction,
                cone_deg,
                intensity_w_sr_nm,
                light_map,
                ..
            } => {
                *position_m = self.position_m;
                *direction = self.direction.unwrap_or(*direction);
                *cone_deg = self.cone_deg.unwrap_or(*cone_deg);
                *intensity_w_sr_nm = self.emission(field, intensity_w_sr_nm)?;
                *light_map = map;
            }
            LightFile::Parallel {
                position_m,
                direction,
                irradiance_w_m2_nm,
                light_map,
                ..
            } => {
                *position_m = self.position_m;
                *direction = self.direction.unwrap_or(*direction);
                *irradiance_w_m2_nm = self.emission(field, irradiance_w_m2_nm)?;
                *light_map = map;
            }
        }
        Ok(light)
    }
}

/// A beams scene file with the panel's edits and the method that renders it.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamsEdit {
    pub path: PathBuf,
    /// The file as loaded.
    file: SceneFile,
    pub lights: Vec<LightEdit>,
    /// The medium's density factor, in [`DENSITY_RANGE`].
    pub density: f64,
    pub method: BeamMethodId,
    /// The method's settings, `key=value` separated by spaces (docs/beams/).
    pub settings: String,
}

impl BeamsEdit {
    /// The scene file at `path`, checked (an error names the file and field), with no
    /// edits and the `march` at its defaults.
    pub fn load(path: &Path) -> Result<BeamsEdit, String> {
        let text = read_text(path, TOML_LIMITS).map_err(|e| e.to_string())?;
        let name = path.display().to_string();
        BeamScene::from_toml(&text, &name, folder(path)).map_err(|e| e.to_string())?;
        let file: SceneFile = toml::from_str(&text).map_err(|e| format!("{name}: {e}"))?;
        Ok(BeamsEdit {
            path: path.to_path_buf(),
            lights: file.lights.iter().map(LightEdit::of).collect(),
            file,
            density: 1.0,
            method: BeamMethodId::March,
            settings: String::new(),
        })
    }

    /// The file with the edits applied.
    pub fn edited_file(&self) -> Result<SceneFile, String> {
        let [lo, hi] = DENSITY_RANGE;
        if !(self.density.is_finite() && (lo..=hi).contains(&self.density)) {
            return Err(format!(
                "medium density: {} must be in [{lo}, {hi}]",
                self.density
            ));
        }
        let mut file = self.file.clone();
        file.medium.scattering_per_m = file.medium.scattering_per_m.scaled(self.density);
        file.medium.absorption_per_m = file.medium.absorption_per_m.scaled(self.density);
        for (i, (light, edit)) in file.lights.iter_mut().zip(&self.lights).enumerate() {
            *light = edit.apply(&format!("lights[{i}]"), light)?;
        }
        Ok(file)
    }

    /// The edited scene, checked as a scene file is (light maps and meshes loaded).
    pub fn scene(&self) -> Result<BeamScene, String> {
        let file = self.edited_file()?;
        let name = self.path.display().to_string();
        BeamScene::from_file(&file, &name, folder(&self.path)).map_err(|e| e.to_string())
    }

    /// The method's settings at the renderer's three wavelengths.
    pub fn beam_settings(&self) -> Result<BeamSettings, String> {
        let items: Vec<&str> = self.settings.split_whitespace().collect();
        Ok(BeamSettings {
            wavelengths_nm: RGB_WAVELENGTHS_NM.to_vec(),
            options: ModelOptions::parse(&items).map_err(|e| e.to_string())?,
        })
    }
}

/// The folder a scene file's paths are relative to.
fn folder(path: &Path) -> &Path {
    path.parent().unwrap_or(Path::new("."))
}
