//! The optics section's GPU column: each row that the GPU pass renders (its march's
//! own steps) as its view's scene at [`FRAME_SIZE`] with the row's volume, interleaved
//! with the same frame without it as `atmos bench --optics-scene` does
//! (`bench/optics.rs`), so that both see the same load of a shared machine: a warm-up
//! pair (pipelines, the volume's buffers), then [`FRAMES`] pairs, medians of the
//! wall-clock times from `render` until the GPU has finished.

use anyhow::{Context, ensure};
use render_wgpu::Renderer;

use crate::bench::timing::{median, timed};
use crate::progress::Progress;
use crate::report::optics_rows::OpticsRow;
use crate::report::optics_scene::OpticsScene;
use crate::report::paired_frames::{GpuTimes, PairedFrame};

/// Measured pairs after the warm-up pair.
pub const FRAMES: usize = 3;

/// Every GPU row on every view.
pub fn measure_all(rows: &[OpticsRow], scenes: &[OpticsScene]) -> anyhow::Result<GpuTimes> {
    let mut renderer = Renderer::headless().context("the GPU frame times need an adapter")?;
    let adapter = renderer.gpu().adapter_summary();
    let total = rows.iter().filter(|r| r.on_gpu()).count() * scenes.len();
    let progress = Progress::new("gpu optics frames", "frames", total as u64);
    let mut per_row = vec![vec![None; scenes.len()]; rows.len()];
    for (v, scene) in scenes.iter().enumerate() {
        for (r, row) in rows.iter().enumerate() {
            if row.on_gpu() {
                per_row[r][v] = Some(
                    measure(&mut renderer, row, scene)
                        .with_context(|| format!("{row} on view {}", scene.view.id))?,
                );
                progress.inc();
            }
        }
    }
    renderer.set_volumes(Vec::new())?;
    progress.finish();
    Ok(GpuTimes { adapter, per_row })
}

fn measure(
    renderer: &mut Renderer,
    row: &OpticsRow,
    scene: &OpticsScene,
) -> anyhow::Result<PairedFrame> {
    let lit = scene.lit(row.tables, row.march())?;
    let (mut with, mut without) = (Vec::new(), Vec::new());
    for k in 0..=FRAMES {
        renderer.set_volumes(Vec::new())?;
        let (_, without_ms) = timed(renderer, &scene.frame)?;
        renderer.set_volumes(vec![lit.clone()])?;
        let (plan, with_ms) = timed(renderer, &scene.frame)?;
        ensure!(
            plan.runs("volumes"),
            "the frame's plan has no volumes: {plan}"
        );
        if k > 0 {
            with.push(with_ms);
            without.push(without_ms);
        }
    }
    Ok(PairedFrame {
        with_ms: median(&with).unwrap_or(f64::NAN),
        without_ms: median(&without).unwrap_or(f64::NAN),
    })
}
