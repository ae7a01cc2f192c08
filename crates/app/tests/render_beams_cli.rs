//! `atmos render --scene` with a beams scene end to end: the real binary renders the
//! sphere under a spotlight (Dobashi et al. 2002 Fig. 4) on the GPU (lavapipe will do)
//! into a small PNG that is read back; flags that do not apply to beams, methods not on
//! the GPU and bad values fail with clear errors and write nothing. Without an adapter
//! the GPU case fails with the message saying what to install, unless
//! `ATMOS_SKIP_GPU_TESTS=1`, when it records that it skipped.

mod common;

use common::{atmos, skipped_without_adapter, stderr};

const SPHERE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/scenes/beams/sphere_spotlight.toml"
);
const PLANET: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/scenes/default.toml"
);

#[test]
fn a_beams_scene_renders_its_beam_and_the_dark_around_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("beams.png");
    let output = atmos(&[
        "render",
        "--scene",
        SPHERE,
        "--model",
        "march",
        "--width",
        "40",
        "--height",
        "60",
        "--set",
        "shadow_map_px=128",
        "--out",
        out.to_str().unwrap(),
    ]);
    if skipped_without_adapter(&output) {
        return;
    }
    let err = stderr(&output);
    assert!(output.status.success(), "{err}");
    assert!(err.contains("40x60 beams march frame"), "{err}");
    let image = image::open(&out).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (40, 60));
    let grey = |x: u32, y: u32| {
        let p = image.get_pixel(x, y);
        (u32::from(p[0]) + u32::from(p[1]) + u32::from(p[2])) / 3
    };
    // The cone under the light, between the light and the sphere, is bright; the fog
    // outside the cone, at the top corners, gets no light.
    assert!(grey(20, 12) > 100, "beam {}", grey(20, 12));
    assert!(
        grey(1, 1) < 5 && grey(38, 1) < 5,
        "corners {} {}",
        grey(1, 1),
        grey(38, 1)
    );
}

#[test]
fn beams_flags_that_do_not_apply_fail_clearly_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // (flags, output file, expected message)
    let cases: &[(&[&str], &str, &str)] = &[
        (&["--model", "reference"], "a.png", "not on the GPU"),
        (
            &["--model", "nishita"],
            "a.png",
            "a beams scene takes a beam method",
        ),
        (
            &["--altitude-m", "10"],
            "a.png",
            "--altitude-m do not apply",
        ),
        (&[], "a.jpg", "must end in .exr"),
        (&["--width", "0"], "a.png", "--width 0 must be 1 to 8192"),
        (&["--exposure", "500"], "a.png", "--exposure 500 is outside"),
        (&["--set", "steps=0"], "a.png", "steps"),
        // 4 loop trips a step and 3 more in this scene: 8191 steps fit in 32768, 8192
        // do not.
        (
            &["--set", "steps=8192", "--set", "shadow_map_px=16"],
            "a.png",
            "32771 loop trips",
        ),
        (&["--set", "colour=1"], "a.png", "colour"),
    ];
    for (flags, name, message) in cases {
        let out = dir.path().join(name);
        let mut args = vec!["render", "--scene", SPHERE];
        args.extend(*flags);
        args.extend(["--out", out.to_str().unwrap()]);
        let output = atmos(&args);
        let err = stderr(&output);
        assert!(!output.status.success(), "{flags:?}");
        assert!(err.contains(message), "{flags:?}: {err}");
        assert!(!out.exists(), "{flags:?}");
    }
    // A beam method with a planet scene.
    let out = dir.path().join("planet.png");
    let output = atmos(&[
        "render",
        "--scene",
        PLANET,
        "--model",
        "march",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = stderr(&output);
    assert!(!output.status.success());
    assert!(err.contains("--model march is a beam method"), "{err}");
    assert!(!out.exists());
}

#[test]
fn a_beams_scene_renders_to_an_exr_of_luminance_with_its_method() {
    for (method, settings) in [
        ("march", "steps=128"),
        ("planes2000", "planes=40"),
        ("qtable2002", "table_u=32"),
    ] {
        renders_with(method, settings);
    }
}

fn renders_with(method: &str, settings: &str) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("beams.exr");
    let output = atmos(&[
        "render",
        "--scene",
        SPHERE,
        "--model",
        method,
        "--width",
        "20",
        "--height",
        "30",
        "--set",
        "shadow_map_px=64",
        "--set",
        settings,
        "--out",
        out.to_str().unwrap(),
    ]);
    if skipped_without_adapter(&output) {
        return;
    }
    assert!(output.status.success(), "{}", stderr(&output));
    let image = exr::prelude::read_first_rgba_layer_from_file(
        &out,
        |size, _| vec![[0f32; 3]; size.width() * size.height()],
        |pixels: &mut Vec<[f32; 3]>, p, (r, g, b, _): (f32, f32, f32, f32)| {
            pixels[p.y() * 20 + p.x()] = [r, g, b];
        },
    )
    .unwrap();
    let layer = &image.layer_data;
    let written = layer
        .attributes
        .other
        .get(&exr::meta::attribute::Text::from("atmos:beam_method"));
    assert!(
        matches!(written, Some(exr::meta::attribute::AttributeValue::Text(t)) if t == method),
        "{written:?}"
    );
    // Linear values in cd/m^2: the beam between the light and the sphere is bright, the
    // corners outside the cone are black.
    let pixels = &layer.channel_data.pixels;
    assert!(
        pixels[6 * 20 + 10][1] > 100.0,
        "{method}: beam {:?}",
        pixels[6 * 20 + 10]
    );
    assert_eq!(pixels[0], [0.0; 3], "{method}");
}
