//! A volume scene as written in TOML (docs/clouds.md, "A local volume by half-angle
//! slicing"): the voxel grid's file and its placement, the sun, the camera and the
//! render settings. Unknown keys are errors; every value is checked against its range
//! and a bad one named.
//!
//! ```toml
//! [volume]
//! grid = "cumulus.u8"        # relative to this file; raw densities, x fastest
//! format = "u8"              # or "f32le"
//! dims = [96, 96, 64]
//! voxel_m = 20.0
//! origin_m = [-960.0, -960.0, 600.0]   # the lowest corner, z up
//! extinction_per_m = 0.05    # at density 1
//! albedo = 1.0
//! [sun]
//! elevation_deg = 35.0
//! azimuth_deg = 150.0        # from +x towards +y
//! irradiance_w_m2_nm = [1.474, 1.8504, 1.91198]   # at 680, 550, 440 nm
//! [camera]
//! position_m = [-5000.0, -1500.0, 1000.0]
//! look_at_m = [0.0, 0.0, 1200.0]
//! vertical_fov_deg = 30.0
//! width_px = 320
//! height_px = 240
//! [render]                   # optional, each key too
//! light = "riley"            # or "octaves"
//! slices = 256
//! light_buffer_px = 256
//! steps = 256
//! shadow_steps = 32
//! backscatter_xi = 0.05
//! octaves = 4
//! ```

use std::path::Path;

use glam::DVec3;
use serde::Deserialize;

use super::camera::{VolumeCamera, VolumeSun};
use super::cloud::VoxelCloud;
use super::raw_file::{VoxelFormat, read_grid};
use super::settings::VolumeSettings;
use crate::atmosphere::text_file::{TOML_LIMITS, read_text};
use crate::clouds::error::CloudError;
use crate::clouds::phase::CloudPhase;

/// The wavelengths of a volume scene's light and tables, nm.
pub const WAVELENGTHS_NM: [f64; 3] = [680.0, 550.0, 440.0];

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    volume: VolumeFile,
    sun: SunFile,
    camera: CameraFile,
    #[serde(default)]
    render: RenderFile,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct VolumeFile {
    grid: String,
    format: String,
    dims: [usize; 3],
    voxel_m: f64,
    origin_m: [f64; 3],
    extinction_per_m: f64,
    albedo: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SunFile {
    elevation_deg: f64,
    azimuth_deg: f64,
    irradiance_w_m2_nm: Vec<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraFile {
    position_m: [f64; 3],
    look_at_m: [f64; 3],
    vertical_fov_deg: f64,
    width_px: u32,
    height_px: u32,
}

#[derive(Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RenderFile {
    light: Option<String>,
    slices: Option<u32>,
    light_buffer_px: Option<u32>,
    steps: Option<u32>,
    shadow_steps: Option<u32>,
    backscatter_xi: Option<f64>,
    octaves: Option<u32>,
}

/// A loaded, checked volume scene.
#[derive(Clone, Debug)]
pub struct VolumeScene {
    pub cloud: VoxelCloud,
    pub sun: VolumeSun,
    pub camera: VolumeCamera,
    pub settings: VolumeSettings,
}

impl VolumeScene {
    /// The scene in the TOML file at `path`, its grid read from the file it names;
    /// `phase` is the droplets' phase function for the path tracer.
    pub fn load(path: &Path, phase: CloudPhase) -> Result<VolumeScene, CloudError> {
        let text = read_text(path, TOML_LIMITS).map_err(|e| CloudError(e.to_string()))?;
        let name = path.display();
        let file: SceneFile =
            toml::from_str(&text).map_err(|e| CloudError(format!("{name}: {e}")))?;
        let v = &file.volume;
        let format: VoxelFormat = v.format.parse()?;
        let grid_path = path.parent().unwrap_or(Path::new(".")).join(&v.grid);
        let grid = read_grid(&grid_path, v.dims, format)?;
        let cloud = VoxelCloud::new(
            grid,
            DVec3::from_array(v.origin_m),
            v.voxel_m,
            v.extinction_per_m,
            v.albedo,
            phase,
        )?;
        if file.sun.irradiance_w_m2_nm.len() != WAVELENGTHS_NM.len() {
            return Err(CloudError(format!(
                "{name}: sun irradiance_w_m2_nm holds {} values; give one at each of {WAVELENGTHS_NM:?} nm",
                file.sun.irradiance_w_m2_nm.len()
            )));
        }
        let sun = VolumeSun::new(
            file.sun.elevation_deg,
            file.sun.azimuth_deg,
            file.sun.irradiance_w_m2_nm,
        )?;
        let c = &file.camera;
        let camera = VolumeCamera::looking_at(
            DVec3::from_array(c.position_m),
            DVec3::from_array(c.look_at_m),
            c.vertical_fov_deg,
            c.width_px,
            c.height_px,
        )?;
        let r = file.render;
        let base = VolumeSettings::default();
        let settings = VolumeSettings {
            light: match r.light {
                Some(light) => light.parse()?,
                None => base.light,
            },
            slices: r.slices.unwrap_or(base.slices),
            light_buffer_px: r.light_buffer_px.unwrap_or(base.light_buffer_px),
            steps: r.steps.unwrap_or(base.steps),
            shadow_steps: r.shadow_steps.unwrap_or(base.shadow_steps),
            backscatter_xi: r.backscatter_xi.unwrap_or(base.backscatter_xi),
            octaves: r.octaves.unwrap_or(base.octaves),
        };
        settings.check()?;
        Ok(VolumeScene {
            cloud,
            sun,
            camera,
            settings,
        })
    }
}
