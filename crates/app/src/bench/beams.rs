//! `atmos bench --beams-scene FILE.toml`: the GPU frame time of beam methods on a beams
//! scene at the bench's size, each frame interleaved with a frame of the cost baseline
//! (nishita with 16 samples, the ground view) so that the ratio of the two is measured
//! under the same load. Times are medians of `--frames` pairs after a warm-up pair.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, bail};
use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::Renderer;
use render_wgpu::frame::Frame;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::shafts::beams::gpu_methods::PreparedBeams;

use crate::bench::timing::{median, timed};
use crate::progress::Progress;
use crate::render::beams::gpu_method;

/// A beam method with its settings, as `--beams-variant "march steps=32"` gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamVariant {
    pub label: String,
    pub method: BeamMethodId,
    pub options: Vec<String>,
}

impl BeamVariant {
    /// "METHOD key=value ..."; the method must be on the GPU.
    pub fn parse(text: &str) -> anyhow::Result<BeamVariant> {
        let mut words = text.split_whitespace();
        let Some(method) = words.next() else {
            bail!("--beams-variant '{text}': give a beam method, e.g. \"march steps=32\"");
        };
        let method = gpu_method("--beams-variant", Some(method))?;
        Ok(BeamVariant {
            label: text.split_whitespace().collect::<Vec<_>>().join(" "),
            method,
            options: words.map(str::to_string).collect(),
        })
    }
}

/// What one beam variant measured, ms.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamTimes {
    pub label: String,
    /// Median GPU time of the beam pass, where the adapter has timestamps.
    pub gpu_ms: Option<f64>,
    /// Median wall-clock time from the pass's start to its radiance read back.
    pub wall_ms: f64,
    /// The baseline's medians over the frames interleaved with this variant's.
    pub baseline_gpu_ms: Option<f64>,
    pub baseline_wall_ms: f64,
    /// The medians of the march at its defaults (128 steps) over the frames
    /// interleaved with this variant's, where the adapter has timestamps.
    pub march_gpu_ms: Option<f64>,
}

/// Frames the bench renders per beam variant (the warm-up triple included: the
/// baseline, the variant and the default march each).
pub fn frames_per_variant(frames: usize) -> usize {
    3 * (1 + frames)
}

/// Measures each of `variants` on the scene at `path` rendered at `size`, interleaved
/// with `baseline` frames on `renderer` and with frames of the march at its defaults
/// (the beams' own baseline).
pub fn measure(
    renderer: &mut Renderer,
    baseline: &Frame,
    path: &Path,
    variants: &[BeamVariant],
    (size, frames): ((u32, u32), usize),
    progress: &Progress,
) -> anyhow::Result<Vec<BeamTimes>> {
    let mut scene =
        BeamScene::load(path).with_context(|| format!("--beams-scene {}", path.display()))?;
    (scene.camera.width_px, scene.camera.height_px) = size;
    let march_settings = BeamSettings {
        wavelengths_nm: RGB_WAVELENGTHS_NM.to_vec(),
        options: ModelOptions::default(),
    };
    let march = PreparedBeams::new(BeamMethodId::March, &scene, &march_settings)?
        .renderer(renderer.gpu())?;
    let mut out = Vec::new();
    for variant in variants {
        let settings = BeamSettings {
            wavelengths_nm: RGB_WAVELENGTHS_NM.to_vec(),
            options: ModelOptions::parse(&variant.options)?,
        };
        let pass =
            PreparedBeams::new(variant.method, &scene, &settings)?.renderer(renderer.gpu())?;
        let (mut gpu, mut wall, mut base_gpu, mut base_wall, mut march_gpu) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for k in 0..=frames {
            let (plan, base_ms) = timed(renderer, baseline)?;
            progress.inc();
            let start = Instant::now();
            let (image, gpu_ms) = pass.render(renderer.gpu())?;
            image.read_radiance(renderer.gpu())?;
            let ms = start.elapsed().as_secs_f64() * 1e3;
            progress.inc();
            let (march_image, march_ms) = march.render(renderer.gpu())?;
            march_image.read_radiance(renderer.gpu())?;
            progress.inc();
            // The first triple warms up: shaders compile, buffers are first made.
            if k > 0 {
                march_gpu.extend(march_ms);
                gpu.extend(gpu_ms);
                wall.push(ms);
                base_gpu.extend(plan.total_gpu_ms());
                base_wall.push(base_ms);
            }
        }
        let timed_all = |t: &[f64]| (t.len() == frames).then(|| median(t)).flatten();
        out.push(BeamTimes {
            label: variant.label.clone(),
            gpu_ms: timed_all(&gpu),
            wall_ms: median(&wall).unwrap_or(f64::NAN),
            baseline_gpu_ms: timed_all(&base_gpu),
            baseline_wall_ms: median(&base_wall).unwrap_or(f64::NAN),
            march_gpu_ms: timed_all(&march_gpu),
        });
    }
    Ok(out)
}

fn ms(value: Option<f64>) -> String {
    value.map_or_else(|| "-".to_string(), |v| format!("{v:.1}"))
}

/// The Markdown table of `results` for the scene at `path`, under `baseline` (its label).
pub fn markdown(path: &Path, baseline: &str, results: &[BeamTimes]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "\nBeams scene {}: each frame interleaved with a {baseline} frame (ground view) \
         and with a frame of the march at its defaults (128 steps); ratios of medians \
         measured in the same run.\n",
        path.display()
    );
    let _ = writeln!(
        out,
        "| beam method | GPU ms | wall ms | {baseline} GPU ms | {baseline} wall ms | GPU / {baseline} | wall / {baseline} | march GPU ms | GPU / march |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|");
    for r in results {
        let gpu_ratio = r.gpu_ms.zip(r.baseline_gpu_ms).map(|(a, b)| a / b);
        let march_ratio = r.gpu_ms.zip(r.march_gpu_ms).map(|(a, b)| a / b);
        let _ = writeln!(
            out,
            "| {} | {} | {:.1} | {} | {:.1} | {} | {:.2} | {} | {} |",
            r.label,
            ms(r.gpu_ms),
            r.wall_ms,
            ms(r.baseline_gpu_ms),
            r.baseline_wall_ms,
            gpu_ratio.map_or_else(|| "-".to_string(), |x| format!("{x:.2}")),
            r.wall_ms / r.baseline_wall_ms,
            ms(r.march_gpu_ms),
            march_ratio.map_or_else(|| "-".to_string(), |x| format!("{x:.2}"))
        );
    }
    out
}
