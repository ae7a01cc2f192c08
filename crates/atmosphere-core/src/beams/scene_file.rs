//! A beams scene as written in TOML (docs/beams.md): the medium, the lights, the
//! occluders and the camera. Unknown keys are errors; `scene.rs` checks the values and
//! loads the files they name.

use serde::{Deserialize, Serialize};

use crate::atmosphere::spectral::Spectral;
use crate::optics::phase::PhaseFunction;

/// The whole file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub medium: MediumFile,
    pub camera: CameraFile,
    #[serde(default)]
    pub lights: Vec<LightFile>,
    #[serde(default)]
    pub occluders: Vec<OccluderFile>,
}

/// The homogeneous medium filling the scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MediumFile {
    /// Scattering coefficient, m^-1.
    pub scattering_per_m: Spectral,
    /// Absorption coefficient, m^-1.
    pub absorption_per_m: Spectral,
    pub phase: PhaseFunction,
}

/// The camera of the scene's pictures (and of the `planes2000` method's planes).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraFile {
    pub position_m: [f64; 3],
    pub look_at_m: [f64; 3],
    #[serde(default = "y_up")]
    pub up: [f64; 3],
    pub vertical_fov_deg: f64,
    pub width_px: u32,
    pub height_px: u32,
}

fn y_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

/// One light. `up` orients a light map around the light's axis (default +y, or +z for
/// an axis along y).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum LightFile {
    /// Radiates in every direction; a light map is its intensity distribution I(theta,
    /// phi) about `axis` (Dobashi et al. 2000 Appendix A), theta down the image, phi
    /// across it.
    Point {
        position_m: [f64; 3],
        intensity_w_sr_nm: Spectral,
        #[serde(default)]
        radius_m: Option<f64>,
        #[serde(default)]
        axis: Option<[f64; 3]>,
        #[serde(default)]
        up: Option<[f64; 3]>,
        #[serde(default)]
        light_map: Option<String>,
    },
    /// A cone of half-angle `cone_deg` about `direction`, intensity
    /// `intensity_w_sr_nm cos^falloff_exponent(theta)` inside it; a light map is
    /// projected like a slide over the cone's square of tangents.
    Spot {
        position_m: [f64; 3],
        direction: [f64; 3],
        cone_deg: f64,
        #[serde(default)]
        falloff_exponent: f64,
        intensity_w_sr_nm: Spectral,
        #[serde(default)]
        radius_m: Option<f64>,
        #[serde(default)]
        up: Option<[f64; 3]>,
        #[serde(default)]
        light_map: Option<String>,
    },
    /// Light travelling along `direction` from the plane through `position_m` across it
    /// (a window, the top of a fog bank); with `size_m` the beam is that rectangle of
    /// the plane, and a light map covers it.
    Parallel {
        position_m: [f64; 3],
        direction: [f64; 3],
        irradiance_w_m2_nm: Spectral,
        #[serde(default)]
        size_m: Option<[f64; 2]>,
        #[serde(default)]
        up: Option<[f64; 3]>,
        #[serde(default)]
        light_map: Option<String>,
    },
}

/// One occluder: a primitive or the triangles of a glTF file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum OccluderFile {
    Sphere {
        center_m: [f64; 3],
        radius_m: f64,
    },
    /// An axis-aligned box.
    Box {
        min_m: [f64; 3],
        max_m: [f64; 3],
    },
    /// The parallelogram `corner_m + a edge_u_m + b edge_v_m`, a and b in [0, 1].
    Quad {
        corner_m: [f64; 3],
        edge_u_m: [f64; 3],
        edge_v_m: [f64; 3],
    },
    /// The infinite plane through `point_m` with normal `normal`.
    Plane {
        point_m: [f64; 3],
        normal: [f64; 3],
    },
    /// Every triangle of a glTF 2.0 file's default scene (path relative to the scene
    /// file), scaled, then moved by `translation_m`.
    Gltf {
        file: String,
        #[serde(default)]
        translation_m: [f64; 3],
        #[serde(default = "unit_scale")]
        scale: f64,
    },
}

fn unit_scale() -> f64 {
    1.0
}
