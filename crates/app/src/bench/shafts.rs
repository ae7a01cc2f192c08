//! `atmos bench --shafts-scene FILE.toml`: what the terrain's light shafts add to a
//! scene with terrain (the default view: `assets/scenes/default.toml`), against the sky
//! model's pixel pass, which holds the shafts' march (docs/shafts.md, "Cost"). Each frame
//! with shafts is interleaved with the same frame without them, so that both are
//! measured under the same load; medians of `--frames` pairs after a warm-up pair.

use anyhow::{Context, bail};
use render_wgpu::Renderer;
use render_wgpu::frame::Frame;
use render_wgpu::frame::plan::FramePlan;

use super::timing::{median, step_gpu_ms, timed};
use crate::progress::Progress;
use crate::render::scene::Scene;

/// The medians of one scene with and without shafts, ms.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaftTimes {
    /// The model's pixel pass (the step named after the model), by its timestamps.
    pub pass_with_ms: Option<f64>,
    pub pass_without_ms: Option<f64>,
    /// The frames' wall-clock times.
    pub wall_with_ms: f64,
    pub wall_without_ms: f64,
}

impl ShaftTimes {
    /// The pass with shafts over the pass without, where the adapter times passes.
    pub fn pass_ratio(&self) -> Option<f64> {
        Some(self.pass_with_ms? / self.pass_without_ms?)
    }
}

/// Frames the bench renders (the warm-up pair included, two each).
pub fn frames_per_scene(frames: usize) -> usize {
    2 * (1 + frames)
}

/// The frame of the scene at `path` with the fields `overrides` sets and shafts `on`; an
/// error when the scene has no terrain.
fn scene_frame(path: &std::path::Path, overrides: &Scene, on: bool) -> anyhow::Result<Frame> {
    let scene = Scene::load(path)?
        .overridden_by(overrides.clone())
        .overridden_by(Scene {
            shafts: Some(on),
            ..Scene::default()
        })
        .resolved()
        .with_context(|| format!("--shafts-scene {}", path.display()))?;
    let frame = scene.frame()?;
    if frame.terrain.is_none() {
        bail!(
            "--shafts-scene {}: the scene has no terrain (`terrain = true`), so no shafts",
            path.display()
        );
    }
    Ok(frame)
}

/// The GPU time of the step named after the frame's model in `plan`.
fn pass_ms(plan: &FramePlan, frame: &Frame) -> Option<f64> {
    step_gpu_ms(plan, &frame.model.to_string())
}

/// Renders the scene at `path` with the fields `overrides` sets (size, model, settings),
/// `frames` pairs with and without shafts.
pub fn measure(
    renderer: &mut Renderer,
    path: &std::path::Path,
    (overrides, frames): (&Scene, usize),
    progress: &Progress,
) -> anyhow::Result<ShaftTimes> {
    let with = scene_frame(path, overrides, true)?;
    let without = scene_frame(path, overrides, false)?;
    let (mut pass_with, mut pass_without) = (Vec::new(), Vec::new());
    let (mut wall_with, mut wall_without) = (Vec::new(), Vec::new());
    for k in 0..=frames {
        let (plain, plain_ms) = timed(renderer, &without)?;
        progress.inc();
        let (shafts, shafts_ms) = timed(renderer, &with)?;
        progress.inc();
        if let Some((_, why)) = shafts.skipped.iter().find(|(name, _)| *name == "shafts") {
            bail!(
                "--shafts-scene {}: the frame has no shafts ({why})",
                path.display()
            );
        }
        // The first pair warms up: shaders compile, tables and the shadow map are built.
        if k > 0 {
            pass_without.extend(pass_ms(&plain, &without));
            pass_with.extend(pass_ms(&shafts, &with));
            wall_without.push(plain_ms);
            wall_with.push(shafts_ms);
        }
    }
    let timed_all = |v: &[f64]| (v.len() == frames).then(|| median(v)).flatten();
    Ok(ShaftTimes {
        pass_with_ms: timed_all(&pass_with),
        pass_without_ms: timed_all(&pass_without),
        wall_with_ms: median(&wall_with).unwrap_or(f64::NAN),
        wall_without_ms: median(&wall_without).unwrap_or(f64::NAN),
    })
}

/// The Markdown table of `times` for the scene at `path`.
pub fn markdown(
    path: &std::path::Path,
    adapter: &str,
    (width, height): (u32, u32),
    times: &ShaftTimes,
) -> String {
    let ms = |v: Option<f64>| v.map_or_else(|| "-".into(), |v| format!("{v:.1}"));
    let ratio = times
        .pass_ratio()
        .map_or_else(|| "-".into(), |r| format!("{r:.2}"));
    format!(
        "\n## Light shafts in {} at {width}x{height} on {adapter}\n\n\
         Each frame with shafts interleaved with the same frame without; medians.\n\n\
         | sky pass with shafts, GPU ms | without, GPU ms | with / without | frame with shafts, wall ms | without, wall ms |\n\
         |---|---|---|---|---|\n\
         | {} | {} | {ratio} | {:.1} | {:.1} |\n",
        path.display(),
        ms(times.pass_with_ms),
        ms(times.pass_without_ms),
        times.wall_with_ms,
        times.wall_without_ms,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scene_without_terrain_is_refused_by_name() {
        let dir = std::env::temp_dir().join(format!("atmos-bench-shafts-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("plain.toml");
        std::fs::write(
            &path,
            "model = \"hillaire\"\naltitude_m = 100.0\nsun_zenith_deg = 80.0\n",
        )
        .unwrap();
        let error = format!(
            "{:#}",
            scene_frame(&path, &Scene::default(), true).unwrap_err()
        );
        assert!(
            error.contains("--shafts-scene") && error.contains("no terrain"),
            "{error}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_ratio_is_the_pass_with_over_the_pass_without() {
        let times = ShaftTimes {
            pass_with_ms: Some(300.0),
            pass_without_ms: Some(200.0),
            wall_with_ms: 400.0,
            wall_without_ms: 300.0,
        };
        assert_eq!(times.pass_ratio(), Some(1.5));
        let text = markdown(std::path::Path::new("s.toml"), "lavapipe", (64, 36), &times);
        assert!(
            text.contains("| 300.0 | 200.0 | 1.50 | 400.0 | 300.0 |"),
            "{text}"
        );
        let untimed = ShaftTimes {
            pass_with_ms: None,
            ..times
        };
        assert_eq!(untimed.pass_ratio(), None);
    }
}
