//! Golden images: small tone-mapped renders (160x90) of every model on the GPU, the same
//! four scenes each (`tests/golden/MODEL_SCENE.png`), compared with the PNGs committed in
//! `tests/golden/`. Regenerate them after an intended change with
//!
//! ```sh
//! ATMOS_UPDATE_GOLDEN=1 ./scripts/test.sh --test golden_images
//! ```
//!
//! and look at the new images before committing them. A render matches when no channel
//! of any pixel differs by more than `MAX_LEVELS` 8-bit levels and at most
//! `MAX_DIFFERING_SHARE` of the pixels differ by more than one level: GPUs round f16
//! stores, `exp` and the sRGB encoding differently, by a level here and there, while a
//! wrong shader moves whole regions.
//!
//! Needs a GPU adapter (lavapipe will do), with the skip policy of the other GPU tests.

mod support;

use std::path::{Path, PathBuf};

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use render_wgpu::Renderer;
use render_wgpu::frame::LocalView;
use render_wgpu::sky::registry::GPU_MODELS;
use support::{frame_in, renderer_or_skip};

/// Largest allowed difference of one channel, 8-bit levels.
const MAX_LEVELS: i32 = 6;
/// Largest share of pixels allowed to differ by more than one level.
const MAX_DIFFERING_SHARE: f64 = 0.005;

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;

fn golden_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("golden")
        .join(format!("{name}.png"))
}

/// The golden scenes: name, camera and sun, field of view, atmosphere, exposure.
fn scenes() -> Vec<(&'static str, LocalView, f64, &'static str, f64)> {
    let view = |altitude_m, view_zenith_deg, sun_zenith_deg, sun_azimuth_deg| LocalView {
        altitude_m,
        view_zenith_deg,
        view_azimuth_deg: 0.0,
        sun_zenith_deg,
        sun_azimuth_deg,
    };
    vec![
        (
            "ground_afternoon",
            view(2.0, 80.0, 60.0, 20.0),
            70.0,
            "earth",
            14.0,
        ),
        (
            "sunset_hazy",
            view(500.0, 87.0, 89.0, 10.0),
            60.0,
            "hazy",
            11.0,
        ),
        (
            "limb_100km",
            view(100_000.0, 100.0, 70.0, 90.0),
            60.0,
            "earth",
            13.0,
        ),
        (
            "planet_1e8m",
            view(1e8, 180.0, 60.0, 0.0),
            9.0,
            "earth",
            13.0,
        ),
    ]
}

/// The bruneton scenes' table sizes (`--set` options): S at 16 x 64 x 16 x 8, an eighth
/// of the paper's texels, since the paper's sizes are slow to build on a software
/// rasteriser (docs/rendering.md, "Cost").
const BRUNETON_SIZES: [(&str, &str); 4] = [("r", "16"), ("mu", "64"), ("mu_s", "16"), ("nu", "8")];

fn render(
    renderer: &mut Renderer,
    model: ModelId,
    (view, fov, preset, ev): (LocalView, f64, &str, f64),
) -> Vec<u8> {
    let atmosphere = Atmosphere::preset(preset).unwrap();
    let mut frame = frame_in(atmosphere, model, view, fov, WIDTH, HEIGHT);
    frame.exposure_ev100 = ev;
    if model == ModelId::Bruneton {
        for (key, value) in BRUNETON_SIZES {
            frame.settings.options.set(key, value);
        }
    }
    renderer.render(&frame).unwrap();
    renderer
        .read_ldr()
        .unwrap()
        .iter()
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect()
}

#[test]
fn renders_match_the_golden_images() {
    let Some(mut renderer) = renderer_or_skip("golden images") else {
        return;
    };
    let update = std::env::var("ATMOS_UPDATE_GOLDEN").as_deref() == Ok("1");
    let mut failures = Vec::new();
    for (model, (scene, view, fov, preset, ev)) in GPU_MODELS
        .iter()
        .flat_map(|m| scenes().into_iter().map(move |s| (*m, s)))
    {
        let name = format!("{model}_{scene}");
        let pixels = render(&mut renderer, model, (view, fov, preset, ev));
        let path = golden_path(&name);
        if update {
            image::RgbImage::from_raw(WIDTH, HEIGHT, pixels)
                .unwrap()
                .save(&path)
                .unwrap();
            println!("wrote {}", path.display());
            continue;
        }
        let golden = image::open(&path)
            .unwrap_or_else(|e| {
                panic!(
                    "{}: {e} (regenerate: see this file's header)",
                    path.display()
                )
            })
            .to_rgb8();
        assert_eq!(golden.dimensions(), (WIDTH, HEIGHT), "{name}");
        let (mut worst, mut differing) = (0, 0usize);
        for (got, want) in pixels.chunks_exact(3).zip(golden.as_raw().chunks_exact(3)) {
            let d = (0..3)
                .map(|c| (i32::from(got[c]) - i32::from(want[c])).abs())
                .max()
                .unwrap();
            worst = worst.max(d);
            differing += usize::from(d > 1);
        }
        let share = differing as f64 / f64::from(WIDTH * HEIGHT);
        println!(
            "{name}: worst {worst} levels, {:.2} % of pixels off by more than 1",
            100.0 * share
        );
        if worst > MAX_LEVELS || share > MAX_DIFFERING_SHARE {
            failures.push(format!(
                "{name}: worst {worst} levels, {:.2} % differing",
                100.0 * share
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
