//! What the golden-image tests share: a frame captured as a golden holds it (the HDR
//! radiance through the tone map's CPU twin, `render_wgpu::post::tone_map`, sRGB-encoded
//! in 16 bits per channel, beside the GPU's own 8-bit display image), the committed PNGs
//! of `tests/golden/`, and the check of a render against its golden.
//!
//! A render matches when
//! - the GPU's own 8-bit display image is within `MAX_LEVELS` levels of the golden in
//!   every channel of every pixel, and at most `MAX_DIFFERING_SHARE` of its pixels differ
//!   by more than one level: GPUs round f16 stores, `exp` and the sRGB encoding
//!   differently, by a level here and there, while a wrong shader moves whole regions;
//! - over the scene's crop, which holds the picture (the sky, the planet, the ground; not
//!   black space), each channel's summed radiance (the tone map inverted, saturated
//!   pixels left out) is within `MAX_RADIANCE_SHIFT` of the golden's: a uniform shift of
//!   1 % fails.

use std::ops::Range;
use std::path::{Path, PathBuf};

use atmosphere_core::color::srgb::{srgb_decode, srgb_encode};
use render_wgpu::Renderer;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::post::tone_map::{ToneMap, aces_filmic};

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
/// The largest 16-bit level: the tone map's white, where radiance is lost.
const WHITE: u16 = u16::MAX;

/// An image's size and the crop (columns, rows) whose radiance is compared.
#[derive(Clone, Debug)]
pub struct Framing {
    pub width: u32,
    pub height: u32,
    pub crop: (Range<u32>, Range<u32>),
}

/// A frame as the check sees it: the GPU's 8-bit display image and the 16-bit encoding
/// of its HDR radiance (what a golden holds).
pub struct Image {
    pub display: Vec<[u8; 3]>,
    pub encoded: Vec<[u16; 3]>,
}

impl Image {
    /// A golden as a candidate: its display image is its encoding rounded to 8 bits.
    pub fn from_encoded(encoded: Vec<[u16; 3]>) -> Image {
        let display = encoded
            .iter()
            .map(|p| p.map(|v| (f64::from(v) / 257.0).round() as u8))
            .collect();
        Image { display, encoded }
    }

    /// The frame `renderer` rendered last, exposed at `ev100`.
    pub fn captured(renderer: &Renderer, ev100: f64) -> Image {
        let tone_map = ToneMap::new(RGB_WAVELENGTHS_NM, ev100).unwrap();
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
}

/// Whether this run writes the goldens instead of checking them (`ATMOS_UPDATE_GOLDEN=1`).
pub fn updating() -> bool {
    std::env::var("ATMOS_UPDATE_GOLDEN").as_deref() == Ok("1")
}

fn golden_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("golden")
        .join(format!("{name}.png"))
}

/// The committed golden `name`, which must be `framing`'s size.
pub fn read_golden(name: &str, framing: &Framing) -> Vec<[u16; 3]> {
    let path = golden_path(name);
    let image = image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "{}: {e} (regenerate: see the test file's header)",
                path.display()
            )
        })
        .into_rgb16();
    assert_eq!(
        image.dimensions(),
        (framing.width, framing.height),
        "{name}"
    );
    image
        .as_raw()
        .chunks_exact(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect()
}

/// Writes the golden `name` whole (through a temporary file), so that the check of the
/// committed goldens running beside never reads half a file.
pub fn write_golden(name: &str, encoded: &[[u16; 3]], framing: &Framing) {
    let path = golden_path(name);
    let partial = path.with_extension("png.partial");
    let raw = encoded.iter().flatten().copied().collect();
    image::ImageBuffer::<image::Rgb<u16>, Vec<u16>>::from_raw(framing.width, framing.height, raw)
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
pub fn scaled(encoded: &[[u16; 3]], factor: f64) -> Vec<[u16; 3]> {
    encoded
        .iter()
        .map(|p| p.map(|v| exposed(v).map_or(WHITE, |x| encode(aces_filmic(factor * x)))))
        .collect()
}

/// The indices of the pixels of `framing`'s crop.
fn crop_pixels(framing: &Framing) -> impl Iterator<Item = usize> + '_ {
    let (columns, rows) = &framing.crop;
    rows.clone().flat_map(move |y| {
        columns
            .clone()
            .map(move |x| (y * framing.width + x) as usize)
    })
}

/// Writes `image` as the golden `name` when updating (`updating`); otherwise compares
/// it with the committed golden, printing the comparison or adding its failure to
/// `failures`.
pub fn check_or_update(name: &str, image: &Image, framing: &Framing, failures: &mut Vec<String>) {
    if updating() {
        write_golden(name, &image.encoded, framing);
        return;
    }
    match compare(image, &read_golden(name, framing), framing) {
        Ok(line) => println!("{name}: {line}"),
        Err(line) => failures.push(format!("{name}: {line}")),
    }
}

/// How `got` differs from `golden`, one line; `Err` with that line where the check fails.
pub fn compare(got: &Image, golden: &[[u16; 3]], framing: &Framing) -> Result<String, String> {
    let (mut worst, mut differing) = (0, 0usize);
    for (g, want) in got.display.iter().zip(golden) {
        let d = (0..3)
            .map(|c| (i32::from(g[c]) - (f64::from(want[c]) / 257.0).round() as i32).abs())
            .max()
            .unwrap();
        worst = worst.max(d);
        differing += usize::from(d > 1);
    }
    let share = differing as f64 / f64::from(framing.width * framing.height);
    let (mut sums, mut lit, mut count) = ([[0.0; 2]; 3], 0usize, 0usize);
    for i in crop_pixels(framing) {
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

/// The check on the committed golden `name`: it matches itself, and fails once its
/// radiance is 1 % higher or lower.
pub fn check_fails_shifted(name: &str, framing: &Framing) {
    let golden = read_golden(name, framing);
    let itself = compare(&Image::from_encoded(golden.clone()), &golden, framing);
    assert!(itself.is_ok(), "{name} against itself: {itself:?}");
    for factor in [1.01, 0.99] {
        let shifted = Image::from_encoded(scaled(&golden, factor));
        let result = compare(&shifted, &golden, framing);
        println!("{name} x {factor}: {result:?}");
        assert!(result.is_err(), "{name} x {factor} passed: {result:?}");
    }
}
