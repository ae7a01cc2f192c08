//! glTF camera paths (docs/camera-paths.md, "glTF camera"): a tiny animated camera, written
//! here as .gltf with a data-URI buffer, .gltf with an external .bin and .glb, drives the
//! frames as its keyframes say; bad files are named with what is wrong.

use std::path::{Path, PathBuf};

use atmos::camera_path::CameraPath;
use glam::DVec3;

const LAT_DEG: f64 = 46.0;
const LON_DEG: f64 = 7.8;
const ALTITUDE_M: f64 = 1000.0;
/// The camera's parent node lifts it this far, m.
const RIG_UP_M: f64 = 10.0;

/// The placement's east, north and up, planet-fixed.
fn enu() -> (DVec3, DVec3, DVec3) {
    let (lat, lon) = (LAT_DEG.to_radians(), LON_DEG.to_radians());
    let up = DVec3::new(lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin());
    let east = DVec3::new(-lon.sin(), lon.cos(), 0.0);
    (east, up.cross(east), up)
}

fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ABC[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// The buffer: times 0 and 2 s, translations 0 and 100 m along x (east), rotations from
/// none to 90 degrees about y (the view turns from north to east).
fn buffer() -> Vec<u8> {
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let floats: [f32; 16] = [
        0.0, 2.0, // times
        0.0, 0.0, 0.0, 100.0, 0.0, 0.0, // translations
        0.0, 0.0, 0.0, 1.0, 0.0, -s, 0.0, s, // rotations (x, y, z, w)
    ];
    floats.iter().flat_map(|f| f.to_le_bytes()).collect()
}

/// The glTF JSON; `buffer` is the buffer object's extra fields (`"uri": ...` or none).
fn json(buffer: &str, rotation: &str) -> String {
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0]}}],
  "nodes": [
    {{"name": "rig", "translation": [0, {RIG_UP_M}, 0], "children": [1]}},
    {{"name": "cam", "camera": 0}}
  ],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.8, "znear": 0.1}}}}],
  "buffers": [{{"byteLength": 64{buffer}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 8}},
    {{"buffer": 0, "byteOffset": 8, "byteLength": 24}},
    {{"buffer": 0, "byteOffset": 32, "byteLength": 32}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [2]}},
    {{"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC4"}}
  ],
  "animations": [{{
    "name": "fly",
    "channels": [
      {{"sampler": 0, "target": {{"node": 1, "path": "translation"}}}},
      {{"sampler": 1, "target": {{"node": 1, "path": "rotation"}}}}
    ],
    "samplers": [
      {{"input": 0, "output": 1, "interpolation": "LINEAR"}},
      {{"input": 0, "output": 2, "interpolation": "{rotation}"}}
    ]
  }}]
}}"#
    )
}

fn data_uri_gltf(rotation: &str) -> String {
    json(
        &format!(
            r#", "uri": "data:application/octet-stream;base64,{}""#,
            base64(&buffer())
        ),
        rotation,
    )
}

/// A .glb: header, JSON chunk (padded with spaces), binary chunk.
fn glb() -> Vec<u8> {
    let mut text = json("", "LINEAR").into_bytes();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let bin = buffer();
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let mut out = Vec::new();
    for word in [
        0x4654_6C67u32,
        2,
        total as u32,
        text.len() as u32,
        0x4E4F_534A,
    ] {
        out.extend(word.to_le_bytes());
    }
    out.extend(&text);
    for word in [bin.len() as u32, 0x004E_4942] {
        out.extend(word.to_le_bytes());
    }
    out.extend(&bin);
    out
}

fn path_text(file: &str, extra: &str) -> String {
    format!(
        r#"version = 1
width = 32
height = 18

[gltf]
file = "{file}"
fps = 24
latitude_deg = {LAT_DEG}
longitude_deg = {LON_DEG}
altitude_m = {ALTITUDE_M}
{extra}
[[keyframe]]
time_s = 0
sun_elevation_deg = 20
sun_azimuth_deg = 180
model = "nishita"
set = ["samples=8"]
"#
    )
}

/// Writes the path and its glTF into a new folder; the path file's name.
fn write(dir: &Path, gltf_name: &str, gltf: &[u8], extra: &str) -> PathBuf {
    std::fs::write(dir.join(gltf_name), gltf).unwrap();
    let path = dir.join("path.toml");
    std::fs::write(&path, path_text(gltf_name, extra)).unwrap();
    path
}

fn near(a: DVec3, b: DVec3, what: &str) {
    assert!((a - b).length() < 1e-6, "{what}: {a} vs {b}");
}

/// Checks the camera at 0, 1 and 2 s; `turned_at_1` is the turn at 1 s, degrees.
fn check_flyby(path: &CameraPath, turned_at_1: f64) {
    let (east, north, up) = enu();
    let ground_m = 6_360_000.0;
    let origin = up * (ground_m + ALTITUDE_M);
    assert_eq!(path.duration_s(), 2.0);
    assert_eq!(path.fps(), 24.0);
    assert_eq!(path.frame_count(24.0), 49);
    for (t, moved_m, turn_deg) in [
        (0.0, 0.0, 0.0),
        (1.0, 50.0, turned_at_1),
        (2.0, 100.0, 90.0),
    ] {
        let frame = path.frame_at(t, 32, 18).unwrap();
        assert_eq!(frame.atmosphere.bottom_radius_m, ground_m);
        let offset = frame.camera_position_m - origin;
        near(
            offset,
            east * moved_m + up * RIG_UP_M,
            &format!("place at {t} s"),
        );
        let a = f64::to_radians(turn_deg);
        let [right, top, forward] = frame.axes();
        near(
            forward,
            north * a.cos() + east * a.sin(),
            &format!("forward at {t} s"),
        );
        near(
            right,
            east * a.cos() - north * a.sin(),
            &format!("right at {t} s"),
        );
        near(top, up, &format!("up at {t} s"));
        assert_eq!(frame.vertical_fov_deg, f64::from(0.8f32).to_degrees());
    }
}

#[test]
fn a_gltf_camera_moves_and_turns_as_its_keyframes_say() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(
        dir.path(),
        "cam.gltf",
        data_uri_gltf("LINEAR").as_bytes(),
        "",
    );
    let path = CameraPath::load(&file).unwrap();
    check_flyby(&path, 45.0);
    // The path written into each frame's header reads back to the same frames.
    let again = CameraPath::parse(&path.to_toml(), Path::new("again.toml")).unwrap();
    assert!(path.to_toml().contains("[gltf]"), "{}", path.to_toml());
    check_flyby(&again, 45.0);
    // A changed glTF file changes the path's TOML, and so the frames' fingerprints.
    std::fs::write(dir.path().join("cam.gltf"), data_uri_gltf("STEP")).unwrap();
    let changed = CameraPath::load(&file).unwrap().to_toml();
    assert_ne!(changed, path.to_toml());
}

#[test]
fn a_step_sampler_holds_until_the_next_keyframe() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "cam.gltf", data_uri_gltf("STEP").as_bytes(), "");
    check_flyby(&CameraPath::load(&file).unwrap(), 0.0);
}

#[test]
fn an_external_bin_and_a_glb_read_alike() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("cam.bin"), buffer()).unwrap();
    let file = write(
        dir.path(),
        "cam.gltf",
        json(r#", "uri": "cam.bin""#, "LINEAR").as_bytes(),
        "",
    );
    check_flyby(&CameraPath::load(&file).unwrap(), 45.0);
    let file = write(dir.path(), "cam.glb", &glb(), "");
    check_flyby(&CameraPath::load(&file).unwrap(), 45.0);
}

#[test]
fn the_heading_turns_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(
        dir.path(),
        "cam.gltf",
        data_uri_gltf("LINEAR").as_bytes(),
        "heading_deg = 90\n",
    );
    let path = CameraPath::load(&file).unwrap();
    let (_, north, up) = enu();
    let origin = up * (6_360_000.0 + ALTITUDE_M);
    let frame = path.frame_at(2.0, 32, 18).unwrap();
    // The scene's north is east: its east is south, and the camera ends looking south.
    near(
        frame.camera_position_m - origin,
        -north * 100.0 + up * RIG_UP_M,
        "place",
    );
    near(frame.axes()[2], -north, "forward");
    // Frames before 0 and after the animation hold its ends.
    near(
        path.frame_at(5.0, 32, 18).unwrap().camera_position_m,
        frame.camera_position_m,
        "after the end",
    );
    near(
        path.frame_at(-1.0, 32, 18).unwrap().camera_position_m,
        origin + up * RIG_UP_M,
        "before the start",
    );
}

fn load_error(dir: &Path, gltf: &str, extra: &str) -> String {
    let file = write(dir, "bad.gltf", gltf.as_bytes(), extra);
    format!("{:#}", CameraPath::load(&file).unwrap_err())
}

#[test]
fn bad_files_are_named_with_what_is_wrong() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let good = data_uri_gltf("LINEAR");
    let cases = [
        (
            good.replace(r#", "camera": 0"#, ""),
            "",
            "no node has a camera",
        ),
        (
            good.clone(),
            r#"camera = "rig""#,
            r#"node "rig" has no camera"#,
        ),
        (
            good.replace("\"animations\"", "\"unused\""),
            "",
            "no animation moves the camera",
        ),
        (good.replace("LINEAR", "BEZIER"), "", "interpolation"),
        (
            good.clone(),
            r#"camera = "lens""#,
            r#"no node named "lens""#,
        ),
        (
            good.clone(),
            "heading_deg = 400",
            "heading_deg 400 must lie in",
        ),
    ];
    for (gltf, extra, expected) in cases {
        let e = load_error(d, &gltf, extra);
        assert!(e.contains(expected), "{e}");
        assert!(e.contains("path.toml"), "{e}");
        if !expected.contains("heading") {
            assert!(e.contains("bad.gltf"), "{e}");
        }
    }
    // A missing file, and a keyframe that aims the camera itself.
    let e = format!(
        "{:#}",
        CameraPath::parse(&path_text("gone.gltf", ""), &d.join("p.toml")).unwrap_err()
    );
    assert!(e.contains("gone.gltf"), "{e}");
    let text = path_text("bad.gltf", "").replace("time_s = 0", "time_s = 0\nheading_deg = 10");
    std::fs::write(d.join("bad.gltf"), &good).unwrap();
    let e = format!(
        "{:#}",
        CameraPath::parse(&text, &d.join("p.toml")).unwrap_err()
    );
    assert!(
        e.contains("keyframe 1") && e.contains("heading_deg is given by the [gltf] camera"),
        "{e}"
    );
}

#[test]
fn the_shipped_gltf_flyby_reads() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/paths/gltf_flyby.toml");
    let path = CameraPath::load(&file).unwrap();
    assert!(path.duration_s() > 0.0);
    let frames = path.frame_count(path.fps());
    let mut last: Option<DVec3> = None;
    for i in 0..frames {
        let frame = path.frame_at(i as f64 / path.fps(), 32, 18).unwrap();
        if let Some(p) = last {
            // A flyby: no jumps between frames.
            assert!((frame.camera_position_m - p).length() < 200.0, "frame {i}");
        }
        last = Some(frame.camera_position_m);
    }
}

#[test]
fn a_cubic_spline_follows_its_tangents() {
    // Times 0 and 2 s; in-tangent, value, out-tangent per time: 0 to 100 m east, at rest
    // at both ends, so the camera follows smoothstep: 15.625 m at 0.5 s, 50 m at 1 s.
    let mut floats: Vec<f32> = vec![0.0, 2.0];
    for value in [0.0, 100.0] {
        floats.extend([0.0, 0.0, 0.0, value, 0.0, 0.0, 0.0, 0.0, 0.0]);
    }
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}},
  "nodes": [{{"name": "cam", "camera": 0}}],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.8, "znear": 0.1}}}}],
  "buffers": [{{"byteLength": 80, "uri": "data:application/octet-stream;base64,{}"}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 8}}, {{"buffer": 0, "byteOffset": 8, "byteLength": 72}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [2]}},
    {{"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC3"}}
  ],
  "animations": [{{"channels": [{{"sampler": 0, "target": {{"node": 0, "path": "translation"}}}}],
    "samplers": [{{"input": 0, "output": 1, "interpolation": "CUBICSPLINE"}}]}}]}}"#,
        base64(&bytes)
    );
    let dir = tempfile::tempdir().unwrap();
    let path = CameraPath::load(&write(dir.path(), "cam.gltf", gltf.as_bytes(), "")).unwrap();
    let (east, _, up) = enu();
    let origin = up * (6_360_000.0 + ALTITUDE_M);
    for (t, moved_m) in [(0.0, 0.0), (0.5, 15.625), (1.0, 50.0), (2.0, 100.0)] {
        let frame = path.frame_at(t, 32, 18).unwrap();
        near(
            frame.camera_position_m - origin,
            east * moved_m,
            &format!("at {t} s"),
        );
    }
}
