//! `atmos render` end to end: the real binary renders tiny PNG and EXR files on the GPU
//! (lavapipe will do) and they are read back; bad flags fail with clear errors and write
//! nothing. Without an adapter the GPU cases fail with the message saying what to
//! install, unless `ATMOS_SKIP_GPU_TESTS=1`, when they record that they skipped; any
//! other failure fails.

mod common;

use std::path::Path;

use common::{atmos, skipped_without_adapter, stderr};
use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{FlatSamples, Levels};

const SCENE: &[&str] = &[
    "--model",
    "nishita",
    "--altitude-m",
    "10",
    "--sun-zenith-deg",
    "45",
    "--view-zenith-deg",
    "80",
    "--fov-deg",
    "60",
    "--width",
    "32",
    "--height",
    "18",
    "--set",
    "samples=16",
];

/// Runs `atmos render` with `SCENE`, `extra` and `--out out`; `false` when it skipped
/// for want of an adapter.
fn render(extra: &[&str], out: &Path) -> bool {
    let mut args = vec!["render"];
    args.extend(SCENE);
    args.extend(extra);
    args.extend(["--out", out.to_str().unwrap()]);
    let output = atmos(&args);
    if skipped_without_adapter(&output) {
        return false;
    }
    let err = stderr(&output);
    assert!(output.status.success(), "{err}");
    assert!(err.contains("32x18 nishita frame"), "{err}");
    true
}

#[test]
fn renders_a_png_with_sky_above_ground() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frame.png");
    if !render(&[], &out) {
        return;
    }
    let image = image::open(&out).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (32, 18));
    let sky = image.get_pixel(16, 1);
    let ground = image.get_pixel(16, 16);
    assert!(sky[2] > sky[0] && sky[2] > 60, "sky {sky:?}");
    assert!(ground[2] < sky[2], "ground {ground:?} sky {sky:?}");
    assert!(!dir.path().join("frame.png.partial").exists());
}

/// The Earth's terrain over the Alps from 8 km, looking down the valleys to the
/// south-west: the ground differs from the smooth sphere's (relief and the colour map
/// instead of one albedo) while the sky above the mountains is the same.
#[test]
fn renders_terrain_at_a_place() {
    let dir = tempfile::tempdir().unwrap();
    let render_at = |terrain: &str| {
        let out = dir.path().join(format!("alps_{terrain}.png"));
        let mut args = vec!["render".to_string()];
        args.extend(scene_with(&[
            ("--latitude-deg", "46.0"),
            ("--longitude-deg", "7.8"),
            ("--terrain", terrain),
            ("--altitude-m", "8000"),
            ("--view-zenith-deg", "100"),
            ("--view-azimuth-deg", "225"),
        ]));
        args.extend(["--out".to_string(), out.display().to_string()]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let output = atmos(&args);
        if skipped_without_adapter(&output) {
            return None;
        }
        assert!(output.status.success(), "{}", stderr(&output));
        Some(image::open(&out).unwrap().to_rgb8())
    };
    let Some(terrain) = render_at("true") else {
        return;
    };
    let sphere = render_at("false").expect("the terrain render found an adapter");
    let mean_difference = |rows: std::ops::Range<u32>| {
        let mut sum = 0.0;
        let mut count = 0.0;
        for y in rows {
            for x in 0..32 {
                for c in 0..3 {
                    sum += (f64::from(terrain.get_pixel(x, y)[c])
                        - f64::from(sphere.get_pixel(x, y)[c]))
                    .abs();
                    count += 1.0;
                }
            }
        }
        sum / count
    };
    let sky = terrain.get_pixel(16, 0);
    assert!(sky[2] > sky[0], "sky {sky:?}");
    assert!(mean_difference(0..2) < 1.0, "the sky changed");
    let ground = mean_difference(12..18);
    assert!(
        ground > 5.0,
        "terrain and sphere differ by {ground} levels only"
    );
}

#[test]
fn renders_an_exr_of_linear_radiance_from_a_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    // The scene file sets everything; the flags of SCENE override some of it.
    let scene = dir.path().join("scene.toml");
    std::fs::write(
        &scene,
        "model = \"nishita\"\naltitude_m = 2000.0\nsun_zenith_deg = 30.0\natmosphere = \"clear\"\nexposure = 13.0\n",
    )
    .unwrap();
    let out = dir.path().join("frame.exr");
    if !render(&["--scene", scene.to_str().unwrap()], &out) {
        return;
    }
    let image = exr::prelude::read_all_data_from_file(&out).unwrap();
    let layer = &image.layer_data[0];
    assert_eq!((layer.size.x(), layer.size.y()), (32, 18));
    let text = |name: &str| match layer.attributes.other.get(&Text::from(name)) {
        Some(AttributeValue::Text(t)) => t.to_string(),
        other => panic!("{name}: {other:?}"),
    };
    assert_eq!(text("atmos:model"), "nishita");
    assert_eq!(text("atmos:atmosphere_name"), "clear");
    assert!(text("atmos:camera").contains("vertical_fov_deg = 60"));
    // The flags won over the file; the file's other fields stayed.
    let scene_toml = text("atmos:scene");
    assert!(scene_toml.contains("altitude_m = 10.0"), "{scene_toml}");
    assert!(scene_toml.contains("exposure = 13.0"), "{scene_toml}");
    // Linear HDR: a daylight sky is thousands of cd/m^2.
    let green = layer
        .channel_data
        .list
        .iter()
        .find(|c| c.name.to_string() == "G")
        .unwrap();
    let Levels::Singular(FlatSamples::F32(samples)) = &green.sample_data else {
        panic!("G is not f32");
    };
    let sky = samples[32 + 16];
    assert!(sky > 1e3 && sky < 3e4, "sky {sky} cd/m^2");
}

#[test]
fn clouds_from_an_image_cover_grey_the_blue_sky() {
    let dir = tempfile::tempdir().unwrap();
    let cover = dir.path().join("overcast.png");
    image::RgbaImage::from_pixel(8, 4, image::Rgba([0, 255, 0, 255]))
        .save(&cover)
        .unwrap();
    let clear = dir.path().join("clear.png");
    let cloudy = dir.path().join("cloudy.png");
    let cover_flag = format!("{}:g", cover.display());
    if !render(&[], &clear) || !render(&["--clouds", "--cloud-cover", &cover_flag], &cloudy) {
        return;
    }
    // Blue over red at the top of the frame, 40 degrees above the horizon.
    let blueness = |path: &Path| {
        let p = *image::open(path).unwrap().to_rgb8().get_pixel(16, 1);
        f64::from(p[2]) / f64::from(p[0]).max(1.0)
    };
    let (clear, cloudy) = (blueness(&clear), blueness(&cloudy));
    assert!(
        clear > 1.2 && cloudy < 0.85 * clear,
        "clear {clear}, cloudy {cloudy}"
    );
}

/// `SCENE` as `--flag=value` arguments, with `overrides` replacing values by flag.
fn scene_with(overrides: &[(&str, &str)]) -> Vec<String> {
    let mut args: Vec<String> = SCENE
        .chunks_exact(2)
        .map(|pair| {
            let value = overrides
                .iter()
                .find(|(flag, _)| *flag == pair[0])
                .map_or(pair[1], |(_, v)| *v);
            format!("{}={value}", pair[0])
        })
        .collect();
    for (flag, value) in overrides {
        if !SCENE.contains(flag) {
            args.push(format!("{flag}={value}"));
        }
    }
    args
}

/// Refused before the GPU is opened: each case fails the same with or without an adapter.
#[test]
fn bad_flags_fail_clearly_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // (flags replaced, output file, expected message)
    type Case<'a> = (&'a [(&'a str, &'a str)], &'a str, &'a str);
    let cases: &[Case] = &[
        (&[], "frame.jpg", "must end in .exr"),
        (&[("--fov-deg", "200")], "frame.png", "--fov-deg 200"),
        (&[("--altitude-m", "-5")], "frame.png", "below the ground"),
        (
            &[("--model", "reference")],
            "frame.png",
            "not yet on the GPU",
        ),
        (&[("--set", "colour=1")], "frame.png", "colour"),
        (
            &[("--latitude-deg", "95"), ("--longitude-deg", "0")],
            "frame.png",
            "--latitude-deg 95",
        ),
        (
            &[("--terrain", "true"), ("--exaggeration", "500")],
            "frame.png",
            "--exaggeration 500",
        ),
        (
            &[("--terrain", "true"), ("--wind-m-s", "30")],
            "frame.png",
            "--wind-m-s: wind_m_s 30 is outside [0, 20] m/s",
        ),
        (
            &[("--terrain", "true"), ("--shafts", "maybe")],
            "frame.png",
            "\"maybe\" is not a switch: use on or off",
        ),
        (
            &[("--clouds", "true"), ("--cloud-base-m", "-1")],
            "frame.png",
            "--cloud-base-m -1 must lie in [0, 20000]",
        ),
        (
            &[("--clouds", "true"), ("--cloud-method", "slices")],
            "frame.png",
            "--cloud-method: cloud method \"slices\" is not one of riley, octaves",
        ),
        (
            &[("--clouds", "true"), ("--cloud-form", "volume")],
            "frame.png",
            "--cloud-form: cloud form \"volume\" is not one of auto, layer, spheres",
        ),
        (
            &[
                ("--clouds", "true"),
                ("--cloud-cover", "/nonexistent/c.png:g"),
            ],
            "frame.png",
            "--cloud-cover /nonexistent/c.png:g",
        ),
        (
            &[("--rain", "true"), ("--rain-rate-mm-h", "0")],
            "frame.png",
            "--rain: rain: rain rate (mm/h) = 0 is outside [0.1, 300]",
        ),
        (
            &[("--rain", "true"), ("--rain-radius-m", "5")],
            "frame.png",
            "rain shaft radius (m) 5 is outside [10, 50000] m",
        ),
        (
            &[("--cirrus", "true"), ("--cirrus-optical-depth", "20")],
            "frame.png",
            "--cirrus: cirrus optical depth 20 is outside [0, 10]",
        ),
        (
            &[("--cirrus", "true"), ("--cirrus-rays", "5")],
            "frame.png",
            "ice rays per wavelength 5 is outside [1e4, 1e8]",
        ),
        (
            &[("--cirrus", "true"), ("--cirrus-tilt-deg", "2")],
            "frame.png",
            "--cirrus-tilt-deg is the falling plates' tilt: it needs --cirrus-plates",
        ),
        (
            &[
                ("--cirrus", "true"),
                ("--cirrus-plates", "true"),
                ("--cirrus-tilt-deg", "40"),
            ],
            "frame.png",
            "tilt spread 40 deg is outside [0, 30] deg",
        ),
        (
            &[("--rain", "true"), ("--rain-small-drop-radius-um", "1000")],
            "frame.png",
            "--rain: small drop radius (um) 1000 is outside [50, 600] um",
        ),
        (
            &[("--deck", "true"), ("--deck-droplet-radius-um", "60")],
            "frame.png",
            "--deck: deck droplet radius (um) 60 is outside [2, 50] um",
        ),
        (
            &[("--deck", "true"), ("--deck-optical-depth", "-1")],
            "frame.png",
            "--deck: deck optical depth -1 is outside [0, 10]",
        ),
        (
            &[("--rain", "true"), ("--optics-wavelengths", "1000")],
            "frame.png",
            "--optics-wavelengths 1000 must lie in [3, 128]",
        ),
        (
            &[("--rain", "true"), ("--optics-forward-peak", "lost")],
            "frame.png",
            "invalid value 'lost' for '--optics-forward-peak <PEAK>'",
        ),
        (
            &[("--rain", "true"), ("--optics-sky-light", "dome")],
            "frame.png",
            "invalid value 'dome' for '--optics-sky-light <SKY>'",
        ),
        (
            &[("--rain", "true"), ("--optics-multiple-scattering", "many")],
            "frame.png",
            "invalid value 'many' for '--optics-multiple-scattering <ORDERS>'",
        ),
        (
            &[("--rain", "true"), ("--optics-resolution-divisor", "9")],
            "frame.png",
            "--optics-resolution-divisor: volumes resolution divisor 9",
        ),
    ];
    for (overrides, name, message) in cases {
        let out = dir.path().join(name);
        let mut args = vec!["render".to_string()];
        args.extend(scene_with(overrides));
        args.extend(["--out".to_string(), out.display().to_string()]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let output = atmos(&args);
        let err = stderr(&output);
        assert!(!output.status.success(), "{overrides:?}");
        assert!(err.contains(message), "{overrides:?}: {err}");
        assert!(!out.exists(), "{overrides:?}");
    }
    let output = atmos(&["render", "--altitude-m", "1", "--out", "x.png"]);
    assert!(
        stderr(&output).contains("--model is required"),
        "{}",
        stderr(&output)
    );
}

/// The terrain's heights come with its first frame, so this refusal needs an adapter.
#[test]
fn a_camera_inside_the_terrain_is_refused_with_the_ground_height() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frame.png");
    let mut args = vec!["render".to_string()];
    // 10 m above sea level in the Alps is inside the mountains.
    args.extend(scene_with(&[
        ("--latitude-deg", "46.0"),
        ("--longitude-deg", "7.8"),
        ("--terrain", "true"),
    ]));
    args.extend(["--out".to_string(), out.display().to_string()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let output = atmos(&args);
    if skipped_without_adapter(&output) {
        return;
    }
    let err = stderr(&output);
    assert!(!output.status.success());
    assert!(
        err.contains("is not above the terrain: the ground there is at"),
        "{err}"
    );
    assert!(!out.exists());
}
