//! `atmos bench --terrain-scene FILE.toml`: the terrain pass of a scene's view against
//! its model's sky pass, both timed in the same frames (the terrain pass then the sky
//! pass, one after the other, so each frame's two times share the machine's load), at
//! `--width` x `--height`; medians of `--frames` frames after a warm-up frame (which
//! compiles the shaders, builds the tables, loads the maps and builds the chunk meshes),
//! and their ratio (docs/terrain.md, "Cost of the refinement").

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, bail};
use render_wgpu::Renderer;
use render_wgpu::frame::Frame;

use crate::render::scene::Scene;

use super::timing::{median, step_gpu_ms, timed};

/// What the scene's frames measured, ms.
#[derive(Clone, Debug, PartialEq)]
pub struct TerrainTimes {
    /// The model whose sky pass the terrain is set against.
    pub model: String,
    /// Medians of the terrain pass's and the sky pass's GPU times.
    pub terrain_ms: f64,
    pub sky_ms: f64,
    /// Median of each frame's terrain time over its sky time.
    pub frame_ratio: f64,
    /// Median wall-clock time of the frame, from `render` to the GPU's end.
    pub frame_wall_ms: f64,
}

/// The frame of the scene file at `path` at `width` x `height`, checked before any GPU
/// work: it must draw terrain.
pub fn scene_frame(path: &Path, (width, height): (u32, u32)) -> anyhow::Result<Frame> {
    let scene = Scene::load(path)?
        .resolved()
        .with_context(|| format!("--terrain-scene {}", path.display()))?;
    let mut frame = scene
        .frame()
        .with_context(|| format!("--terrain-scene {}", path.display()))?;
    if frame.terrain.is_none() {
        bail!(
            "--terrain-scene {}: the scene has no terrain (terrain = true)",
            path.display()
        );
    }
    frame.width = width;
    frame.height = height;
    Ok(frame)
}

/// Renders `frame` once to warm up, then `frames` times, timing both passes in each.
pub fn measure(
    renderer: &mut Renderer,
    frame: &Frame,
    frames: usize,
) -> anyhow::Result<TerrainTimes> {
    let model = frame.model.to_string();
    timed(renderer, frame)?;
    let (mut terrain, mut sky, mut ratios, mut walls) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for _ in 0..frames {
        let (plan, wall_ms) = timed(renderer, frame)?;
        let gpu_ms = |name: &str| {
            step_gpu_ms(&plan, name).with_context(|| {
                format!("the frame has no GPU time for its {name} pass (plan: {plan})")
            })
        };
        let (t, s) = (gpu_ms("terrain")?, gpu_ms(&model)?);
        terrain.push(t);
        sky.push(s);
        ratios.push(t / s);
        walls.push(wall_ms);
    }
    let med = |v: &[f64]| median(v).unwrap_or(f64::NAN);
    Ok(TerrainTimes {
        terrain_ms: med(&terrain),
        sky_ms: med(&sky),
        frame_ratio: med(&ratios),
        frame_wall_ms: med(&walls),
        model,
    })
}

/// The Markdown row of `times`, with its heading.
pub fn markdown(
    path: &Path,
    adapter: &str,
    (width, height): (u32, u32),
    times: &TerrainTimes,
) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "\nTerrain of {} on {adapter}, {width}x{height} px: the terrain pass and the {} \
         pass timed in the same frames; medians after a warm-up frame.\n",
        path.display(),
        times.model
    );
    let _ = writeln!(
        out,
        "| terrain pass, GPU ms | {} pass, GPU ms | terrain / {} (medians) | median of each frame's ratio | frame wall ms |",
        times.model, times.model
    );
    let _ = writeln!(out, "|---|---|---|---|---|");
    let _ = writeln!(
        out,
        "| {:.1} | {:.1} | {:.2} | {:.2} | {:.1} |",
        times.terrain_ms,
        times.sky_ms,
        times.terrain_ms / times.sky_ms,
        times.frame_ratio,
        times.frame_wall_ms
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scene_without_terrain_is_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sky.toml");
        std::fs::write(
            &path,
            "model = \"hillaire\"\naltitude_m = 10.0\nsun_zenith_deg = 40.0\n",
        )
        .unwrap();
        let e = format!("{:#}", scene_frame(&path, (64, 36)).unwrap_err());
        assert!(
            e.contains("--terrain-scene") && e.contains("no terrain"),
            "{e}"
        );
    }

    #[test]
    fn the_default_scene_is_taken_at_the_bench_size() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes/default.toml");
        let frame = scene_frame(&path, (320, 180)).unwrap();
        assert_eq!((frame.width, frame.height), (320, 180));
        assert!(frame.terrain.is_some());
        assert_eq!(frame.model.to_string(), "hillaire");
    }
}
