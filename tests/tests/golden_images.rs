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
//! A golden is the frame's HDR radiance through the tone map's CPU twin
//! (`render_wgpu::post::tone_map`), sRGB-encoded in 16 bits per channel: a picture to
//! look at that keeps radiance to far better than 1 %, which 8 bits do not (one 8-bit
//! level is 2 to 4 % of the radiance of a mid-tone). A render matches when
//! - the GPU's own 8-bit display image is within `MAX_LEVELS` levels of the golden in
//!   every channel of every pixel, and at most `MAX_DIFFERING_SHARE` of its pixels differ
//!   by more than one level: GPUs round f16 stores, `exp` and the sRGB encoding
//!   differently, by a level here and there, while a wrong shader moves whole regions;
//! - over the scene's crop, which holds the picture (the sky, the planet; not black
//!   space), each channel's summed radiance (the tone map inverted, saturated pixels left
//!   out) is within `MAX_RADIANCE_SHIFT` of the golden's: a uniform shift of 1 % fails.
//!
//! Needs a GPU adapter (lavapipe will do), with the skip policy of the other GPU tests;
//! the check itself is tested on the committed goldens without one.

mod support;

use std::ops::Range;
use std::path::{Path, PathBuf};

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::color::srgb::{srgb_decode, srgb_encode};
use atmosphere_core::models::id::ModelId;
use render_wgpu::Renderer;
use render_wgpu::frame::LocalView;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::post::tone_map::{ToneMap, aces_filmic};
use render_wgpu::sky::registry::GPU_MODELS;
use support::{frame_in, renderer_or_skip};

/// Largest allowed difference of one channel of the display image, 8-bit levels.
const MAX_LEVELS: i32 = 6;
/// Largest share of pixels allowed to differ by more than one 8-bit level.
const MAX_DIFFERING_SHARE: f64 = 0.005;
/// Largest allowed relative difference of a crop's summed radiance in one channel: half
/// the 1 % shift the check must catch, the other half left to GPUs that round otherwise.
const MAX_RADIANCE_SHIFT: f64 = 0.005;
/// Smallest share of a crop's pixels lit in the golden (display value above
/// `LIT_DISPLAY`): the crop holds the picture.
const MIN_LIT_SHARE: f64 = 0.6;
/// A lit pixel's smallest display value (linear, before sRGB encoding), any channel.
const LIT_DISPLAY: f64 = 0.01;

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;
/// The largest 16-bit level: the tone map's white, where radiance is lost.
const WHITE: u16 = u16::MAX;

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

/// A frame as the check sees it: the GPU's 8-bit display image and the 16-bit encoding
/// of its HDR radiance (what a golden holds).
struct Image {
    display: Vec<[u8; 3]>,
    encoded: Vec<[u16; 3]>,
}

impl Image {
    /// A golden as a candidate: its display image is its encoding rounded to 8 bits.
    fn from_encoded(encoded: Vec<[u16; 3]>) -> Image {
        let display = encoded
            .iter()
            .map(|p| p.map(|v| (f64::from(v) / 257.0).round() as u8))
            .collect();
        Image { display, encoded }
    }
}

fn golden_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("golden")
        .join(format!("{name}.png"))
}

fn read_golden(name: &str) -> Vec<[u16; 3]> {
    let path = golden_path(name);
    let image = image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "{}: {e} (regenerate: see this file's header)",
                path.display()
            )
        })
        .into_rgb16();
    assert_eq!(image.dimensions(), (WIDTH, HEIGHT), "{name}");
    image
        .as_raw()
        .chunks_exact(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect()
}

/// Writes the golden `name` whole (through a temporary file), so that the check of the
/// committed goldens running beside never reads half a file.
fn write_golden(name: &str, encoded: &[[u16; 3]]) {
    let path = golden_path(name);
    let partial = path.with_extension("png.partial");
    let raw = encoded.iter().flatten().copied().collect();
    image::ImageBuffer::<image::Rgb<u16>, Vec<u16>>::from_raw(WIDTH, HEIGHT, raw)
        .unwrap()
        .save_with_format(&partial, image::ImageFormat::Png)
        .unwrap();
    std::fs::rename(&partial, &path).unwrap();
    println!("wrote {}", path.display());
}

/// The 16-bit level of a display value in [0, 1] (before sRGB encoding).
fn encode(display: f64) -> u16 {
    (srgb_encode(display) * f64::from(WHITE)).round() as u16
}

/// The exposed linear value (the tone curve's input) of a 16-bit level, `None` at white:
/// the sRGB decoding, then Narkowicz's ACES fit y = x (2.51 x + 0.03) / (x (2.43 x +
/// 0.59) + 0.14) solved for its positive root x.
fn exposed(level: u16) -> Option<f64> {
    if level == WHITE {
        return None;
    }
    let y = srgb_decode(f64::from(level) / f64::from(WHITE));
    let (a, b, c) = (2.43 * y - 2.51, 0.59 * y - 0.03, 0.14 * y);
    Some((-b - (b * b - 4.0 * a * c).sqrt()) / (2.0 * a))
}

/// `encoded` with every radiance scaled by `factor`: the tone map's input is linear in
/// radiance, so each channel's exposed value scales alike; white stays white.
fn scaled(encoded: &[[u16; 3]], factor: f64) -> Vec<[u16; 3]> {
    encoded
        .iter()
        .map(|p| p.map(|v| exposed(v).map_or(WHITE, |x| encode(aces_filmic(factor * x)))))
        .collect()
}

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
    let tone_map = ToneMap::new(RGB_WAVELENGTHS_NM, scene.ev100).unwrap();
    let encoded = renderer
        .read_hdr()
        .unwrap()
        .iter()
        .map(|p| {
            let radiance = std::array::from_fn(|w| f64::from(p[w]));
            tone_map.display_linear(radiance).map(encode)
        })
        .collect();
    let display = renderer
        .read_ldr()
        .unwrap()
        .iter()
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    Image { display, encoded }
}

/// The indices of the pixels of `crop`.
fn crop_pixels((columns, rows): &(Range<u32>, Range<u32>)) -> impl Iterator<Item = usize> {
    rows.clone()
        .flat_map(move |y| columns.clone().map(move |x| (y * WIDTH + x) as usize))
}

/// How `got` differs from `golden`, one line; `Err` with that line where the check fails.
fn compare(got: &Image, golden: &[[u16; 3]], scene: &Scene) -> Result<String, String> {
    let (mut worst, mut differing) = (0, 0usize);
    for (g, want) in got.display.iter().zip(golden) {
        let d = (0..3)
            .map(|c| (i32::from(g[c]) - (f64::from(want[c]) / 257.0).round() as i32).abs())
            .max()
            .unwrap();
        worst = worst.max(d);
        differing += usize::from(d > 1);
    }
    let share = differing as f64 / f64::from(WIDTH * HEIGHT);
    let (mut sums, mut lit, mut count) = ([[0.0; 2]; 3], 0usize, 0usize);
    for i in crop_pixels(&scene.crop) {
        count += 1;
        lit += usize::from(golden[i].iter().any(|v| *v >= encode(LIT_DISPLAY)));
        for (c, sum) in sums.iter_mut().enumerate() {
            if let (Some(g), Some(w)) = (exposed(got.encoded[i][c]), exposed(golden[i][c])) {
                sum[0] += g;
                sum[1] += w;
            }
        }
    }
    let shift = sums.map(|[g, w]| g / w - 1.0);
    let lit_share = lit as f64 / count as f64;
    let line = format!(
        "worst {worst} levels, {:.2} % of pixels off by more than 1; radiance over the crop \
         ({:.0} % lit) {:+.3} / {:+.3} / {:+.3} % (R/G/B)",
        100.0 * share,
        100.0 * lit_share,
        100.0 * shift[0],
        100.0 * shift[1],
        100.0 * shift[2],
    );
    let fails = worst > MAX_LEVELS
        || share > MAX_DIFFERING_SHARE
        || lit_share < MIN_LIT_SHARE
        || shift
            .iter()
            .any(|s| s.abs() > MAX_RADIANCE_SHIFT || s.is_nan());
    if fails { Err(line) } else { Ok(line) }
}

#[test]
fn renders_match_the_golden_images() {
    let Some(mut renderer) = renderer_or_skip("golden images") else {
        return;
    };
    let update = std::env::var("ATMOS_UPDATE_GOLDEN").as_deref() == Ok("1");
    let mut failures = Vec::new();
    for model in GPU_MODELS {
        for scene in scenes() {
            let name = format!("{model}_{}", scene.name);
            let image = render(&mut renderer, model, &scene);
            if update {
                write_golden(&name, &image.encoded);
                continue;
            }
            match compare(&image, &read_golden(&name), &scene) {
                Ok(line) => println!("{name}: {line}"),
                Err(line) => failures.push(format!("{name}: {line}")),
            }
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
            let name = format!("{model}_{}", scene.name);
            let golden = read_golden(&name);
            let itself = compare(&Image::from_encoded(golden.clone()), &golden, &scene);
            assert!(itself.is_ok(), "{name} against itself: {itself:?}");
            for factor in [1.01, 0.99] {
                let shifted = Image::from_encoded(scaled(&golden, factor));
                let result = compare(&shifted, &golden, &scene);
                println!("{name} x {factor}: {result:?}");
                assert!(result.is_err(), "{name} x {factor} passed: {result:?}");
            }
        }
    }
}
