//! `atmos bench --optics-scene FILE.toml`: what a scene's rain and ice volumes cost
//! against its sky model's pixel pass, at --width x --height: frames with the volumes
//! interleaved with the same frames without them, timed by the wall clock around each
//! render (lavapipe's timestamps around a lone compute pass do not measure it); the
//! volumes' cost is the difference of the medians, the sky pass's the median of its own
//! GPU timestamps (docs/optics-rendering.md, "Cost").

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
    let volumes = scene.volumes.lit_volumes(&frame)?;
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
    Ok(OpticsTimes {
        without_ms: median(&without).unwrap_or(f64::NAN),
        with_ms: median(&with).unwrap_or(f64::NAN),
        sky_pass_ms: median(&sky),
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
    let (sky, ratio) = match times.sky_pass_ms {
        Some(s) => (format!("{s:.1}"), format!("{:.2}", volumes / s)),
        None => ("-".into(), "-".into()),
    };
    format!(
        "## Optics scene {} at {}x{} on {adapter}\n\n\
         | frame without volumes (ms) | frame with volumes (ms) | volumes (ms) | sky pass (ms) | volumes / sky pass |\n\
         |---|---|---|---|---|\n\
         | {:.1} | {:.1} | {volumes:.1} | {sky} | {ratio} |\n",
        path.display(),
        size.0,
        size.1,
        times.without_ms,
        times.with_ms,
    )
}
