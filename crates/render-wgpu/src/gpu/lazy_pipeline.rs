//! A compute pipeline compiled the first time a frame asks for it: a pass that only some
//! frames take adds nothing to the start of the others (on lavapipe a compile costs tens
//! of milliseconds).

use std::sync::OnceLock;

use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::ComputePipeline;

/// Entry point `entry` of `shader` with one bind group of `entries`, compiled on first use.
#[derive(Debug)]
pub struct LazyPipeline {
    shader: &'static str,
    entry: &'static str,
    label: &'static str,
    entries: Vec<wgpu::BindGroupLayoutEntry>,
    built: OnceLock<ComputePipeline>,
}

impl LazyPipeline {
    /// The pipeline of `(shader, entry)`, not compiled yet.
    pub fn new(
        (shader, entry): (&'static str, &'static str),
        label: &'static str,
        entries: &[wgpu::BindGroupLayoutEntry],
    ) -> LazyPipeline {
        LazyPipeline {
            shader,
            entry,
            label,
            entries: entries.to_vec(),
            built: OnceLock::new(),
        }
    }

    /// The pipeline, compiled now if it was not.
    pub fn get(&self, gpu: &GpuContext) -> Result<&ComputePipeline, GpuError> {
        if let Some(pipeline) = self.built.get() {
            return Ok(pipeline);
        }
        let pipeline =
            ComputePipeline::new(gpu, self.shader, self.entry, self.label, &self.entries)?;
        Ok(self.built.get_or_init(|| pipeline))
    }
}
