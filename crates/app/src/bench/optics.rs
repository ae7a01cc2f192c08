//! `atmos bench --optics-scene FILE.toml`: what a scene's rain and ice volumes cost
//! against its sky model's frame, at --width x --height: frames with the volumes
//! interleaved with the same frames without them, timed by the wall clock around each
//! render. Each pair, rendered one after the other under the same load, gives the
//! volumes' cost as a share of the frame without them (the sky pass, the tone map and
//! the frame's own work); the median of the pairs' shares is the figure. The sky pass's
//! own GPU timestamps are shown beside it but not divided by: lavapipe's timestamps
//! around compute passes often read a fraction of a millisecond (docs/optics-rendering.md,
//! "Cost"). At the scene's `resolution_divisor` above 1 the row also gives how far that
//! frame is from the frame with every pixel marched: the RMS of the relative difference
//! per channel over the pixels the volumes change by more than 1 %.

use anyhow::Context;
use render_wgpu::Renderer;

use super::timing::{median, timed};
use crate::render::scene::Scene;

/// The medians of one optics scene, ms.
#[derive(Clone, Debug, PartialEq)]
pub struct OpticsTimes {
    pub without_ms: f64,
    pub with_ms: f64,
    /// The model's pixel pass (the step named after the model), by its timestamps.
    pub sky_pass_ms: Option<f64>,
    /// The median over the pairs of (with - without) / without.
    pub pair_ratio: f64,
    /// The one-minute load average before and after, where the system tells it.
    pub load: Option<(f64, f64)>,
    /// The scene's divisor, and above 1 the RMS relative difference of its frame from
    /// the frame marched at every pixel.
    pub divisor: (u32, Option<f64>),
}

/// The RMS of (reduced - exact) / exact per channel over the pixels where `exact`
/// differs from `without` (the frame without volumes) by more than 1 %.
pub fn divisor_difference(exact: &[[f32; 4]], reduced: &[[f32; 4]], without: &[[f32; 4]]) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for ((e, r), w) in exact.iter().zip(reduced).zip(without) {
        for c in 0..3 {
            let (e, r, w) = (f64::from(e[c]), f64::from(r[c]), f64::from(w[c]));
            if e > 0.0 && (e - w).abs() > 0.01 * e {
                sum += ((r - e) / e).powi(2);
                n += 1;
            }
        }
    }
    if n == 0 { 0.0 } else { (sum / n as f64).sqrt() }
}

/// The one-minute load average (`/proc/loadavg`); `None` where there is none.
fn load_average() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// Renders the scene at `path` resized to `size`, `frames` times with and without its
/// volumes.
pub fn measure(
    renderer: &mut Renderer,
    path: &std::path::Path,
    size: (u32, u32),
    frames: usize,
) -> anyhow::Result<OpticsTimes> {
    let scene = Scene::load(path)?
        .overridden_by(Scene {
            width: Some(size.0),
            height: Some(size.1),
            ..Scene::default()
        })
        .resolved()
        .with_context(|| format!("--optics-scene {}", path.display()))?;
    let frame = scene.frame()?;
    let divisor = scene.volumes.divisor()?;
    let volumes = scene.volumes.lit_volumes(&frame)?;
    renderer.set_volumes_divisor(divisor)?;
    if volumes.is_empty() {
        anyhow::bail!(
            "--optics-scene {}: the scene has no rain or cirrus",
            path.display()
        );
    }
    let model = frame.model.to_string();
    // A first frame of each builds the tables and pipelines.
    renderer.set_volumes(Vec::new())?;
    timed(renderer, &frame)?;
    renderer.set_volumes(volumes.clone())?;
    timed(renderer, &frame)?;
    let load_before = load_average();
    let (mut without, mut with, mut sky) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..frames {
        renderer.set_volumes(Vec::new())?;
        let (plan, ms) = timed(renderer, &frame)?;
        without.push(ms);
        sky.extend(
            plan.steps
                .iter()
                .filter(|s| s.name == model)
                .filter_map(|s| s.gpu_ms),
        );
        renderer.set_volumes(volumes.clone())?;
        with.push(timed(renderer, &frame)?.1);
    }
    let difference = if divisor > 1 {
        let mut image = |volumes: Vec<_>, divisor| -> anyhow::Result<Vec<[f32; 4]>> {
            renderer.set_volumes(volumes)?;
            renderer.set_volumes_divisor(divisor)?;
            renderer.render(&frame)?;
            Ok(renderer.read_hdr()?)
        };
        let without_image = image(Vec::new(), divisor)?;
        let exact = image(volumes.clone(), 1)?;
        let reduced = image(volumes, divisor)?;
        Some(divisor_difference(&exact, &reduced, &without_image))
    } else {
        None
    };
    let ratios: Vec<f64> = with
        .iter()
        .zip(&without)
        .map(|(w, o)| (w - o) / o)
        .collect();
    Ok(OpticsTimes {
        without_ms: median(&without).unwrap_or(f64::NAN),
        with_ms: median(&with).unwrap_or(f64::NAN),
        sky_pass_ms: median(&sky),
        pair_ratio: median(&ratios).unwrap_or(f64::NAN),
        load: load_before.zip(load_average()),
        divisor: (divisor, difference),
    })
}

/// The Markdown table of `times` for the scene at `path`.
pub fn markdown(
    path: &std::path::Path,
    adapter: &str,
    size: (u32, u32),
    times: &OpticsTimes,
) -> String {
    let volumes = times.with_ms - times.without_ms;
    let sky = times
        .sky_pass_ms
        .map_or_else(|| "-".into(), |s| format!("{s:.1}"));
    let load = times
        .load
        .map_or_else(|| "-".into(), |(a, b)| format!("{a:.2}, {b:.2}"));
    let (divisor, difference) = times.divisor;
    let difference = difference.map_or_else(|| "-".into(), |d| format!("{:.2} %", 100.0 * d));
    format!(
        "## Optics scene {} at {}x{} on {adapter}\n\n\
         | frame without volumes (ms) | frame with volumes (ms) | volumes (ms) | sky pass timestamps (ms) | volumes / frame without (median of pairs) | load before, after | divisor | RMS difference from divisor 1 |\n\
         |---|---|---|---|---|---|---|---|\n\
         | {:.1} | {:.1} | {volumes:.1} | {sky} | {:.2} | {load} | {divisor} | {difference} |\n",
        path.display(),
        size.0,
        size.1,
        times.without_ms,
        times.with_ms,
        times.pair_ratio,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_row_shows_the_median_of_the_pairs_and_the_load() {
        let times = OpticsTimes {
            without_ms: 400.0,
            with_ms: 700.0,
            sky_pass_ms: None,
            pair_ratio: 0.8,
            load: Some((3.5, 4.25)),
            divisor: (2, Some(0.0123)),
        };
        let text = markdown(std::path::Path::new("r.toml"), "cpu", (64, 36), &times);
        assert!(
            text.contains("| 400.0 | 700.0 | 300.0 | - | 0.80 | 3.50, 4.25 | 2 | 1.23 % |"),
            "{text}"
        );
    }

    #[test]
    fn the_difference_counts_only_the_volumes_pixels() {
        let without = [[1.0, 1.0, 1.0, 1.0], [1.0, 1.0, 1.0, 1.0]];
        let exact = [[2.0, 2.0, 2.0, 1.0], [1.0, 1.0, 1.0, 1.0]];
        let reduced = [[2.2, 2.0, 1.8, 1.0], [5.0, 5.0, 5.0, 1.0]];
        let d = divisor_difference(&exact, &reduced, &without);
        assert!((d - (0.02f64 / 3.0).sqrt()).abs() < 1e-6, "{d}");
    }
}
