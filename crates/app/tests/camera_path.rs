//! Camera paths (docs/camera-paths.md): keyframes hit exactly, carry-over, a ground-to-orbit
//! ascent without speed spikes, continuous orientation, the sun by UTC, the shipped paths,
//! and malformed files named by line and column.

use std::path::{Path, PathBuf};

use atmos::camera_path::CameraPath;
use atmos::camera_path::keyframe::{SunKey, place_rotation};
use atmos::camera_path::position::log_altitude;
use glam::DVec3;
use render_wgpu::Frame;

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
model = "nishita"
set = ["samples=8"]
atmosphere = "earth"

[[keyframe]]
time_s = 2
altitude_m = 1000.0
heading_deg = 260
"#;

fn shipped() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/paths");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        // glTF paths (and their .gltf) have their own tests: camera_path_gltf.rs.
        .filter(|p| {
            p.extension().is_some_and(|e| e == "toml")
                && !p
                    .file_name()
                    .unwrap()
                    .to_string_lossy()
                    .starts_with("gltf_")
        })
        .collect();
    paths.sort();
    paths
}

fn shipped_path(name: &str) -> CameraPath {
    let file = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/paths")
        .join(name);
    CameraPath::load(&file).unwrap()
}

fn altitude(frame: &Frame) -> f64 {
    frame.camera_position_m.length() - frame.atmosphere.bottom_radius_m
}

fn error(text: &str) -> String {
    format!(
        "{:#}",
        CameraPath::parse(text, Path::new("bad.toml")).unwrap_err()
    )
}

#[test]
fn a_simple_path_carries_fields_over() {
    let path = CameraPath::parse(SIMPLE, Path::new("simple.toml")).unwrap();
    assert_eq!(path.duration_s(), 2.0);
    assert_eq!(path.fps(), 10.0);
    assert_eq!(path.size_px(), (32, 18));
    assert_eq!(path.frame_count(10.0), 21);
    assert_eq!(path.frame_count(3.0), 7);
    let [a, b] = path.keys() else { panic!() };
    // Carried over: the place, pitch, sun, model, settings, atmosphere.
    assert_eq!(
        (b.up, b.pitch_deg, b.sun, b.model),
        (a.up, a.pitch_deg, a.sun, a.model)
    );
    assert_eq!((&b.set, &b.atmosphere), (&a.set, &a.atmosphere));
    assert_eq!((b.altitude_m, b.heading_deg), (1000.0, 260.0));
    for i in 0..21 {
        path.frame_at(i as f64 / 10.0, 32, 18)
            .unwrap()
            .validate()
            .unwrap();
    }
    // Outside [0, duration] the ends hold.
    let end = path.frame_at(2.0, 32, 18).unwrap();
    assert_eq!(path.frame_at(99.0, 32, 18).unwrap(), end);
    assert_eq!(
        path.frame_at(-1.0, 32, 18).unwrap(),
        path.frame_at(0.0, 32, 18).unwrap()
    );
    // The text written back reads as the same path.
    let back = CameraPath::parse(&path.to_toml(), Path::new("simple.toml")).unwrap();
    assert_eq!(back.keys(), path.keys());
    // A new model starts from its own default settings.
    let text = format!("{SIMPLE}\n[[keyframe]]\ntime_s = 3\nmodel = \"riley\"\n");
    let path = CameraPath::parse(&text, Path::new("simple.toml")).unwrap();
    assert!(path.keys()[2].set.is_empty());
}

#[test]
fn keyframes_are_hit_exactly() {
    for file in shipped() {
        let path = CameraPath::load(&file).unwrap();
        for key in path.keys() {
            let frame = path.frame_at(key.time_s, 64, 36).unwrap();
            let radius = frame.atmosphere.bottom_radius_m + key.altitude_m;
            assert_eq!(
                frame.camera_position_m,
                key.up * radius,
                "{}",
                file.display()
            );
            let rotation = place_rotation(key.up) * key.local_orientation;
            assert!(frame.orientation.dot(rotation).abs() > 1.0 - 1e-15);
            assert_eq!(frame.vertical_fov_deg, key.fov_deg);
            assert_eq!(frame.exposure_ev100, key.exposure_ev100);
            assert_eq!((frame.model, &frame.settings), (key.model, &key.settings));
            assert_eq!(frame.terrain.is_some(), key.terrain);
            // The heading and pitch asked for.
            let local = place_rotation(key.up).inverse() * frame.axes()[2];
            let pitch = local.z.atan2(local.x.hypot(local.y)).to_degrees();
            assert!(
                (pitch - key.pitch_deg).abs() < 1e-9,
                "{pitch} {}",
                key.pitch_deg
            );
            if key.pitch_deg.abs() < 89.0 {
                let heading = -local.y.atan2(local.x).to_degrees();
                let off = (heading - key.heading_deg).rem_euclid(360.0);
                assert!(off.min(360.0 - off) < 1e-9, "{heading} {}", key.heading_deg);
            }
        }
    }
}

#[test]
fn the_ascent_climbs_at_one_pace_in_log_altitude() {
    let path = shipped_path("ascent_alps.toml");
    let base = 2577.2;
    let steps = 6000;
    let logs: Vec<f64> = (0..=steps)
        .map(|i| {
            let t = path.duration_s() * i as f64 / steps as f64;
            log_altitude(altitude(&path.frame_at(t, 32, 18).unwrap()), base)
        })
        .collect();
    let first = altitude(&path.frame_at(0.0, 32, 18).unwrap());
    let last = altitude(&path.frame_at(path.duration_s(), 32, 18).unwrap());
    assert!(
        (first - base - 2.0).abs() < 1e-6 && (last - 4e7).abs() < 1e4,
        "{first} {last}"
    );
    let deltas: Vec<f64> = logs.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(
        deltas.iter().all(|&d| d > 0.0),
        "the climb never stops or dips"
    );
    let worst = deltas
        .windows(2)
        .map(|w| (w[1] / w[0]).max(w[0] / w[1]))
        .fold(1.0, f64::max);
    eprintln!("ascent: worst consecutive step ratio {worst}");
    assert!(
        worst < 1.5,
        "consecutive steps in log altitude differ by {worst}"
    );
    // One pace from end to end: no stretch much faster than the mean.
    let mean = (logs[steps] - logs[0]) / steps as f64;
    let fastest = deltas.iter().fold(0.0f64, |m, &d| m.max(d));
    eprintln!("ascent: fastest step / mean {}", fastest / mean);
    assert!(fastest < 1.6 * mean, "{fastest} vs mean {mean}");
}

#[test]
fn the_ascent_starts_2_m_above_the_shipped_terrain() {
    let path = shipped_path("ascent_alps.toml");
    let key = &path.keys()[0];
    let map = render_wgpu::terrain::EarthData::BuiltIn.heights().unwrap();
    let (lat, lon) = render_wgpu::terrain::geo_grid::lat_lon(key.up);
    let clearance = key.altitude_m - map.sample(lat, lon);
    assert!((1.0..=3.0).contains(&clearance), "{clearance} m");
}

#[test]
fn orientation_and_place_move_continuously() {
    for file in shipped() {
        let path = CameraPath::load(&file).unwrap();
        let steps = 3000;
        let frames: Vec<Frame> = (0..=steps)
            .map(|i| {
                path.frame_at(path.duration_s() * i as f64 / steps as f64, 32, 18)
                    .unwrap()
            })
            .collect();
        let turns: Vec<f64> = frames
            .windows(2)
            .map(|w| w[0].orientation.angle_between(w[1].orientation))
            .collect();
        let mean = turns.iter().sum::<f64>() / turns.len() as f64;
        let worst = turns.iter().fold(0.0f64, |m, &a| m.max(a));
        eprintln!("{}: turn max/mean {}", file.display(), worst / mean);
        assert!(
            worst <= 8.0 * mean + 1e-12,
            "{}: {worst} vs mean {mean}",
            file.display()
        );
        // The sun turns smoothly too.
        let sun_steps: Vec<f64> = frames
            .windows(2)
            .map(|w| w[0].sun_direction.angle_between(w[1].sun_direction))
            .collect();
        let mean = sun_steps.iter().sum::<f64>() / sun_steps.len() as f64;
        let worst = sun_steps.iter().fold(0.0f64, |m, &a| m.max(a));
        eprintln!("{}: sun max/mean {}", file.display(), worst / mean);
        assert!(
            worst <= 8.0 * mean + 1e-12,
            "{}: sun {worst} vs {mean}",
            file.display()
        );
    }
}

#[test]
fn shipped_paths_give_valid_frames() {
    let names: Vec<String> = shipped()
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "ascent_alps.toml",
            "day_at_one_place.toml",
            "flight_sea_to_orbit.toml",
            "sunrise_from_orbit.toml"
        ]
    );
    for file in shipped() {
        let path = CameraPath::load(&file).unwrap();
        assert!(path.duration_s() > 0.0);
        for k in 0..=20 {
            let t = path.duration_s() * k as f64 / 20.0;
            let frame = path.frame_at(t, 32, 18).unwrap();
            frame.validate().unwrap();
            assert!(render_wgpu::Renderer::check_model(frame.model).is_ok());
        }
        let back = CameraPath::parse(&path.to_toml(), &file).unwrap();
        assert_eq!(back.keys(), path.keys(), "{}", file.display());
    }
}

#[test]
fn the_sun_follows_the_utc_clock() {
    let path = shipped_path("day_at_one_place.toml");
    let elevation = |t: f64| {
        let frame = path.frame_at(t, 32, 18).unwrap();
        let up = frame.camera_position_m.normalize();
        frame.sun_direction.dot(up).asin().to_degrees()
    };
    // Solstice noon at 46 N: 90 - 46 + 23.44 degrees.
    assert!((elevation(20.0) - 67.4).abs() < 0.5, "{}", elevation(20.0));
    assert!((-6.0..0.0).contains(&elevation(0.0)), "{}", elevation(0.0));
    assert!(
        (-6.0..0.0).contains(&elevation(40.0)),
        "{}",
        elevation(40.0)
    );
    assert!(matches!(path.keys()[1].sun, SunKey::Utc(_)));
    // The clock runs at one rate: halfway between keyframes is halfway in time.
    let [a, b, ..] = path.keys() else { panic!() };
    let (SunKey::Utc(s0), SunKey::Utc(s1)) = (a.sun, b.sun) else {
        panic!()
    };
    assert_eq!(s1 - s0, 99.0 * 60.0);
}

#[test]
fn malformed_files_are_named_with_line_and_column() {
    let head = "version = 1\n[[keyframe]]\ntime_s = 0\nlatitude_deg = 1\nlongitude_deg = 2\naltitude_m = 10\nsun_elevation_deg = 5\nsun_azimuth_deg = 0\nmodel = \"nishita\"\n";
    assert!(CameraPath::parse(head, Path::new("ok.toml")).is_ok());
    for (text, expected) in [
        ("version = 1\nfps = \"x\"\n", "bad.toml:2:7"),
        (&format!("{head}colour = 1\n"), "bad.toml:10:1"),
        (
            &format!("{head}[[keyframe]]\ntime_s = 1\nlatitude_deg = 95\nlongitude_deg = 0\n"),
            "bad.toml:10:1: keyframe 2 (time_s 1): latitude_deg 95 must lie in [-90, 90]",
        ),
        (
            &format!("{head}[[keyframe]]\ntime_s = 0\n"),
            "bad.toml:10:1: keyframe 2 (time_s 0): time_s 0 must be after",
        ),
        (&format!("{head}utc = 2024-01-01T00:00:00Z\n"), "not both"),
        (
            &format!("{head}[[keyframe]]\ntime_s = 1\nutc = 1500-01-01T00:00:00Z\n"),
            "bad.toml:10:1: keyframe 2 (time_s 1): utc 1500-01-01T00:00:00Z",
        ),
        (
            &format!("{head}[[keyframe]]\ntime_s = 1\nlatitude_deg = 1\nlongitude_deg = 170\n"),
            "degrees apart round the planet",
        ),
        (
            &format!("{head}terrain = true\natmosphere = \"mars\"\n"),
            "terrain draws the Earth's relief",
        ),
        (&format!("{head}set = [\"samples=0\"]\n"), "samples"),
        (
            &format!("{head}exposure = 1000\n"),
            "exposure 1000 must lie in [-60, 100]",
        ),
        (&format!("{head}fov_deg = 180\n"), "fov_deg 180"),
        (
            &format!("{head}look_at_m = [0.0, 0.0, 0.0]\nheading_deg = 3\n"),
            "without heading_deg",
        ),
        (
            "version = 1\n[[keyframe]]\ntime_s = 0\nlatitude_deg = 1\nlongitude_deg = 2\n",
            "bad.toml:2:1: keyframe 1 (time_s 0): the first keyframe needs altitude_m",
        ),
        ("version = 1\n", "1 to 10000 [[keyframe]] tables"),
        ("version = 1\nwidth = 0\n", "width 0 must be 1 to 8192 px"),
        (
            &format!("log_altitude_base_m = 100\n{head}"),
            "below log_altitude_base_m 100",
        ),
        ("version = 1\n[[keyframe]\n", "bad.toml:2:"),
    ] {
        let e = error(text);
        assert!(e.contains(expected), "{e}\n  does not contain {expected}");
        assert!(e.starts_with("camera path bad.toml"), "{e}");
    }
}

#[test]
fn look_at_targets_are_in_the_middle_of_the_image() {
    let text = r#"
version = 1
[[keyframe]]
time_s = 0
latitude_deg = 0
longitude_deg = 0
altitude_m = 400000
look_at_m = [0.0, 0.0, 0.0]
sun_elevation_deg = 10
sun_azimuth_deg = 0
model = "hillaire"
[[keyframe]]
time_s = 1
look_at = { latitude_deg = 0.0, longitude_deg = 5.0 }
[[keyframe]]
time_s = 3
latitude_deg = 3
longitude_deg = 1
altitude_m = 900000
roll_deg = 20
[[keyframe]]
time_s = 4
pitch_deg = -30
"#;
    let path = CameraPath::parse(text, Path::new("look.toml")).unwrap();
    let frame = path.frame_at(0.0, 32, 18).unwrap();
    assert!((frame.axes()[2] + DVec3::X).length() < 1e-12);
    let frame = path.frame_at(1.0, 32, 18).unwrap();
    let radius = frame.atmosphere.bottom_radius_m;
    let lon = 5f64.to_radians();
    let target = DVec3::new(lon.cos(), lon.sin(), 0.0) * radius;
    let towards = (target - frame.camera_position_m).normalize();
    assert!(frame.axes()[2].angle_between(towards) < 1e-9);
    // The target carries over, and the camera tracks it between keyframes that share it.
    assert_eq!(path.keys()[2].target_m, Some(target));
    for t in [1.5, 2.0, 2.7, 3.0] {
        let frame = path.frame_at(t, 32, 18).unwrap();
        let towards = (target - frame.camera_position_m).normalize();
        assert!(frame.axes()[2].angle_between(towards) < 1e-9, "{t}");
    }
    // Heading or pitch drops it; the heading carries over from the target's.
    let last = &path.keys()[3];
    assert_eq!(last.target_m, None);
    assert_eq!(last.heading_deg, path.keys()[2].heading_deg);
}

#[test]
fn utc_offsets_are_converted_and_mixed_suns_turn_between() {
    let text = |utc: &str| {
        format!(
            "version = 1\n[[keyframe]]\ntime_s = 0\nlatitude_deg = 46\nlongitude_deg = 7.8\naltitude_m = 10\nutc = {utc}\nmodel = \"riley\"\n[[keyframe]]\ntime_s = 10\nsun_elevation_deg = 30\nsun_azimuth_deg = 180\n"
        )
    };
    let a = CameraPath::parse(&text("2024-06-21T05:15:00+02:00"), Path::new("a.toml")).unwrap();
    let b = CameraPath::parse(&text("2024-06-21T03:15:00Z"), Path::new("b.toml")).unwrap();
    let c = CameraPath::parse(&text("2024-06-21T03:15:00"), Path::new("c.toml")).unwrap();
    assert_eq!(a.keys()[0].sun, b.keys()[0].sun);
    assert_eq!(c.keys()[0].sun, b.keys()[0].sun);
    // From the clock's sun to angles: the end is the angles' sun exactly.
    let end = b.frame_at(10.0, 16, 9).unwrap();
    let up = end.camera_position_m.normalize();
    assert!((end.sun_direction.dot(up).asin().to_degrees() - 30.0).abs() < 1e-9);
    let mid = b.frame_at(5.0, 16, 9).unwrap();
    let start = b.frame_at(0.0, 16, 9).unwrap();
    let (whole, half) = (
        start.sun_direction.angle_between(end.sun_direction),
        start.sun_direction.angle_between(mid.sun_direction),
    );
    assert!((half - whole / 2.0).abs() < 1e-9, "{half} {whole}");
}

#[test]
fn the_documented_example_reads() {
    let doc = include_str!("../../../docs/camera-paths.md");
    let start = doc.find("```toml\n").unwrap() + "```toml\n".len();
    let text = &doc[start..start + doc[start..].find("```").unwrap()];
    let path = CameraPath::parse(text, Path::new("example.toml")).unwrap();
    assert_eq!(path.keys().len(), 2);
    path.frame_at(5.0, 32, 18).unwrap();
}
