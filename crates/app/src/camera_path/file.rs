//! The path file as written (docs/camera-paths.md): `version = 1`, the frame rate and
//! image size, and `[[keyframe]]` tables whose fields are all optional (a field left out
//! carries over from the keyframe before). Errors name the file, line and column.

use std::ops::Range;
use std::path::Path;

use anyhow::anyhow;
use atmosphere_core::models::id::ModelId;
use serde::{Deserialize, Serialize};
use toml::Spanned;
use toml::value::Datetime;

/// The only version of the format so far.
pub const VERSION: u32 = 1;

/// A place given by latitude, longitude and altitude (a look-at target).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeoPoint {
    pub latitude_deg: f64,
    pub longitude_deg: f64,
    #[serde(default)]
    pub altitude_m: f64,
}

/// How a parameter moves from one keyframe to the next.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Easing {
    /// Constant rate.
    #[default]
    Linear,
    /// Starts and stops at rest (smoothstep, 3h^2 - 2h^3).
    Smooth,
    /// Starts at rest (h^2).
    EaseIn,
    /// Stops at rest (1 - (1 - h)^2).
    EaseOut,
    /// Keeps the earlier keyframe's value up to the later keyframe.
    Step,
}

impl Easing {
    /// The eased fraction of a segment at fraction `h` in [0, 1].
    pub fn apply(self, h: f64) -> f64 {
        match self {
            Easing::Linear => h,
            Easing::Smooth => h * h * (3.0 - 2.0 * h),
            Easing::EaseIn => h * h,
            Easing::EaseOut => 1.0 - (1.0 - h) * (1.0 - h),
            Easing::Step => {
                if h >= 1.0 {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }
}

/// One `[[keyframe]]` table as written.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeyframeFile {
    /// Time of the keyframe, s.
    pub time_s: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub latitude_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub longitude_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub altitude_m: Option<f64>,
    /// Planet-fixed camera position, m (instead of latitude, longitude and altitude).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub position_m: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heading_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pitch_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roll_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub look_at: Option<GeoPoint>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub look_at_m: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fov_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sun_elevation_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sun_azimuth_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub utc: Option<Datetime>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub atmosphere: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aerosol_scale: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ground_albedo: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model: Option<ModelId>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub set: Option<Vec<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exposure: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub auto_exposure: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub terrain: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exaggeration: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub easing: Option<Easing>,
}

/// The `[gltf]` table: the camera from a glTF file's animated camera node, its scene
/// placed on the planet (docs/camera-paths.md, "glTF camera").
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GltfFile {
    /// The .gltf or .glb file, relative to the path file.
    pub file: String,
    /// The camera node's name (default: the file's only camera node).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub camera: Option<String>,
    /// The animation's name (default: the only one that moves the camera).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub animation: Option<String>,
    /// The frame rate the animation was made at (the path's, unless it gives its own).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fps: Option<f64>,
    /// Where the scene's origin is on the planet, and where its -z points.
    pub latitude_deg: f64,
    pub longitude_deg: f64,
    pub altitude_m: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heading_deg: Option<f64>,
}

/// The whole file as written, each keyframe with where it stands in the text.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PathFile {
    pub version: u32,
    pub fps: Option<f64>,
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub log_altitude_base_m: Option<f64>,
    pub gltf: Option<Spanned<GltfFile>>,
    #[serde(default)]
    pub keyframe: Vec<Spanned<KeyframeFile>>,
}

/// The file again as TOML, keyframes without their places in the text.
#[derive(Debug, Serialize)]
pub struct PathFileOut<'a> {
    pub version: u32,
    pub fps: f64,
    pub width: u32,
    pub height: u32,
    pub log_altitude_base_m: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gltf: Option<&'a GltfFile>,
    pub keyframe: &'a [KeyframeFile],
}

/// The top-level fields of a path file other than its keyframes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathHeader {
    /// Frames per second.
    pub fps: f64,
    /// Image width and height, px.
    pub size_px: (u32, u32),
    pub log_altitude_base_m: f64,
}

impl Default for PathHeader {
    /// 30 fps, 1280x720, base 0 m.
    fn default() -> PathHeader {
        PathHeader {
            fps: 30.0,
            size_px: (1280, 720),
            log_altitude_base_m: 0.0,
        }
    }
}

/// A version-1 path file of `keyframes` (and the camera from `gltf`, if any) as TOML
/// text (read back by [`parse_file`]).
pub fn write_file(
    header: &PathHeader,
    gltf: Option<&GltfFile>,
    keyframes: &[KeyframeFile],
) -> anyhow::Result<String> {
    let out = PathFileOut {
        version: VERSION,
        fps: header.fps,
        width: header.size_px.0,
        height: header.size_px.1,
        log_altitude_base_m: header.log_altitude_base_m,
        gltf,
        keyframe: keyframes,
    };
    toml::to_string(&out).map_err(|e| anyhow!("camera path not written: {e}"))
}

/// `file:line:column` of byte `offset` of `text` (both counted from 1, columns in
/// characters).
pub fn location(origin: &Path, text: &str, offset: usize) -> String {
    let mut end = offset.min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    let before = &text[..end];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().unwrap_or("").chars().count() + 1;
    format!("{}:{line}:{column}", origin.display())
}

/// Reads the TOML text of a path file; errors name the file, line and column.
pub fn parse_file(text: &str, origin: &Path) -> anyhow::Result<PathFile> {
    let file: PathFile = toml::from_str(text).map_err(|e| {
        let at = e.span().map_or(0, |s: Range<usize>| s.start);
        anyhow!(
            "camera path {}: {}",
            location(origin, text, at),
            e.message().trim_end()
        )
    })?;
    if file.version != VERSION {
        let at = text.find("version").unwrap_or(0);
        anyhow::bail!(
            "camera path {}: version {} is not known; this atmos reads version {VERSION}",
            location(origin, text, at),
            file.version
        );
    }
    Ok(file)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_line_and_column() {
        let origin = Path::new("p.toml");
        let err = |t: &str| parse_file(t, origin).unwrap_err().to_string();
        let e = err("version = 1\n[[keyframe]]\ntime_s = 0\nlatitude_deg = \"x\"\n");
        assert!(e.starts_with("camera path p.toml:4:16: "), "{e}");
        let e = err("version = 1\n[[keyframe]]\ntime_s = 0\ncolour = 1\n");
        assert!(e.contains("p.toml:4:1") && e.contains("colour"), "{e}");
        let e = err("version = 2\n");
        assert!(e.contains("p.toml:1:1") && e.contains("version 2"), "{e}");
        let e = err("version = 1\n[[keyframe]]\ntime_s = 0\nmodel = \"venus\"\n");
        assert!(e.contains("p.toml:4:9") && e.contains("venus"), "{e}");
        assert!(err("").contains("version"));
    }

    #[test]
    fn written_files_read_back_the_same() {
        let header = PathHeader {
            fps: 24.0,
            size_px: (320, 200),
            log_altitude_base_m: 2577.2,
        };
        let keyframes = vec![
            KeyframeFile {
                time_s: 0.0,
                latitude_deg: Some(46.0),
                longitude_deg: Some(7.8),
                altitude_m: Some(5600.0),
                utc: Some("2024-06-21T03:15:00.25Z".parse().unwrap()),
                model: Some(ModelId::Hillaire),
                set: Some(vec!["samples=32".into()]),
                ..KeyframeFile::default()
            },
            KeyframeFile {
                time_s: 0.1 + 0.2,
                heading_deg: Some(1.0 / 3.0),
                easing: Some(Easing::Smooth),
                ..KeyframeFile::default()
            },
        ];
        let text = write_file(&header, None, &keyframes).unwrap();
        let file = parse_file(&text, Path::new("p.toml")).unwrap();
        assert_eq!(file.version, VERSION);
        assert_eq!(
            (file.fps, file.width, file.height, file.log_altitude_base_m),
            (Some(24.0), Some(320), Some(200), Some(2577.2))
        );
        let back: Vec<KeyframeFile> = file.keyframe.into_iter().map(|k| k.into_inner()).collect();
        assert_eq!(back, keyframes);
    }

    #[test]
    fn easings_start_at_0_and_end_at_1() {
        for e in [
            Easing::Linear,
            Easing::Smooth,
            Easing::EaseIn,
            Easing::EaseOut,
            Easing::Step,
        ] {
            assert_eq!((e.apply(0.0), e.apply(1.0)), (0.0, 1.0), "{e:?}");
            assert!((0.0..=1.0).contains(&e.apply(0.5)));
        }
    }
}
