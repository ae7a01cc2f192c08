//! Golden images: small renders (160x90) of every model on the GPU, the same four scenes
//! each, compared with the PNGs committed in `tests/golden/` (`MODEL_SCENE.png`).
//! Regenerate them after an intended change with
//!
//! ```sh
//! ATMOS_UPDATE_GOLDEN=1 ./scripts/test.sh --test golden_images
//! ```
//!
//! and look at the new images before committing them.
//!
//! A golden is the frame's HDR radiance through the tone map's CPU twin, sRGB-encoded in
//! 16 bits per channel, checked as `support/golden.rs` says: within a few 8-bit levels
//! per pixel, and a uniform shift of 1 % of the radiance fails.
//!
//! Needs a GPU adapter (lavapipe will do), with the skip policy of the other GPU tests;
//! the check itself is tested on the committed goldens without one.

mod support;

use std::ops::Range;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use render_wgpu::Renderer;
use render_wgpu::frame::LocalView;
use render_wgpu::sky::registry::GPU_MODELS;
use support::golden::{Framing, Image, check_fails_shifted, check_or_update};
use support::{frame_in, renderer_or_skip};

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;

/// A golden scene: camera and sun, field of view, atmosphere preset, exposure, and the
/// crop (columns, rows) whose radiance is compared.
struct Scene {
    name: &'static str,
    view: LocalView,
    fov_deg: f64,
    preset: &'static str,
    ev100: f64,
    crop: (Range<u32>, Range<u32>),
}

impl Scene {
    fn framing(&self) -> Framing {
        Framing {
            width: WIDTH,
            height: HEIGHT,
            crop: self.crop.clone(),
        }
    }
}

fn scenes() -> Vec<Scene> {
    let view = |altitude_m, view_zenith_deg, sun_zenith_deg, sun_azimuth_deg| LocalView {
        altitude_m,
        view_zenith_deg,
        view_azimuth_deg: 0.0,
        sun_zenith_deg,
        sun_azimuth_deg,
    };
    vec![
        Scene {
            name: "ground_afternoon",
            view: view(2.0, 80.0, 60.0, 20.0),
            fov_deg: 70.0,
            preset: "earth",
            ev100: 14.0,
            crop: (0..WIDTH, 0..HEIGHT),
        },
        Scene {
            name: "sunset_hazy",
            view: view(500.0, 87.0, 89.0, 10.0),
            fov_deg: 60.0,
            preset: "hazy",
            ev100: 11.0,
            crop: (0..WIDTH, 0..48),
        },
        // The atmosphere and the planet below it; above is space.
        Scene {
            name: "limb_100km",
            view: view(100_000.0, 100.0, 70.0, 90.0),
            fov_deg: 60.0,
            preset: "earth",
            ev100: 13.0,
            crop: (0..WIDTH, 42..HEIGHT),
        },
        // The planet's lit side.
        Scene {
            name: "planet_1e8m",
            view: view(1e8, 180.0, 60.0, 0.0),
            fov_deg: 9.0,
            preset: "earth",
            ev100: 13.0,
            crop: (45..115, 10..64),
        },
    ]
}

/// The bruneton scenes' table sizes (`--set` options): S at 16 x 64 x 16 x 8, an eighth
/// of the paper's texels, since the paper's sizes are slow to build on a software
/// rasteriser (docs/rendering.md, "Cost").
const BRUNETON_SIZES: [(&str, &str); 4] = [("r", "16"), ("mu", "64"), ("mu_s", "16"), ("nu", "8")];

fn render(renderer: &mut Renderer, model: ModelId, scene: &Scene) -> Image {
    let atmosphere = Atmosphere::preset(scene.preset).unwrap();
    let mut frame = frame_in(atmosphere, model, scene.view, scene.fov_deg, WIDTH, HEIGHT);
    frame.exposure_ev100 = scene.ev100;
    if model == ModelId::Bruneton {
        for (key, value) in BRUNETON_SIZES {
            frame.settings.options.set(key, value);
        }
    }
    renderer.render(&frame).unwrap();
    Image::captured(renderer, scene.ev100)
}

#[test]
fn renders_match_the_golden_images() {
    let Some(mut renderer) = renderer_or_skip("golden images") else {
        return;
    };
    let mut failures = Vec::new();
    for model in GPU_MODELS {
        for scene in scenes() {
            let name = format!("{model}_{}", scene.name);
            let image = render(&mut renderer, model, &scene);
            check_or_update(&name, &image, &scene.framing(), &mut failures);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The check on the committed goldens: each matches itself, and fails once its radiance
/// is 1 % higher or lower.
#[test]
fn every_golden_matches_itself_and_fails_shifted_by_one_percent() {
    for model in GPU_MODELS {
        for scene in scenes() {
            check_fails_shifted(&format!("{model}_{}", scene.name), &scene.framing());
        }
    }
}
