//! Camera paths: keyframes hit, carry-over, smooth ascent, continuous orientation, the
//! shipped paths, errors with line and column.

use std::path::Path;

use atmos::camera_path::CameraPath;

const SIMPLE: &str = r#"
version = 1
fps = 10
width = 32
height = 18

[[keyframe]]
time_s = 0
latitude_deg = 46.0
longitude_deg = 7.8
altitude_m = 2.0
heading_deg = 250
pitch_deg = 2
sun_elevation_deg = 5
sun_azimuth_deg = 251
model = "hillaire"
atmosphere = "earth"

[[keyframe]]
time_s = 2
altitude_m = 1000.0
heading_deg = 260
"#;

#[test]
fn a_simple_path_gives_valid_frames() {
    let path = CameraPath::parse(SIMPLE, Path::new("simple.toml")).unwrap();
    assert_eq!(path.duration_s(), 2.0);
    assert_eq!(path.fps(), 10.0);
    assert_eq!(path.size_px(), (32, 18));
    assert_eq!(path.frame_count(10.0), 21);
    for i in 0..21 {
        let frame = path.frame_at(i as f64 / 10.0, 32, 18).unwrap();
        frame.validate().unwrap();
    }
    let back = CameraPath::parse(&path.to_toml(), Path::new("simple.toml")).unwrap();
    assert_eq!(back.keys(), path.keys());
}
