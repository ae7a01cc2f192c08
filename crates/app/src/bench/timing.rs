//! Timing a frame and the median of repeated timings.

use std::time::Instant;

use anyhow::Context;
use render_wgpu::Renderer;
use render_wgpu::frame::Frame;
use render_wgpu::frame::plan::FramePlan;

/// The median of `values` (the lower middle one for an even count); `None` when empty.
pub fn median(values: &[f64]) -> Option<f64> {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted.get((sorted.len().max(1) - 1) / 2).copied()
}

/// Renders `frame`; returns the plan and the wall-clock time, ms.
pub fn timed(renderer: &mut Renderer, frame: &Frame) -> anyhow::Result<(FramePlan, f64)> {
    let start = Instant::now();
    let plan = renderer
        .render(frame)
        .with_context(|| format!("rendering {}", frame.model))?;
    Ok((plan, start.elapsed().as_secs_f64() * 1e3))
}

/// The GPU time, ms, of the step named `name` in `plan`; `None` where it did not run or
/// the adapter gives no timestamps.
pub fn step_gpu_ms(plan: &FramePlan, name: &str) -> Option<f64> {
    plan.steps
        .iter()
        .find(|s| s.name == name)
        .and_then(|s| s.gpu_ms)
}
