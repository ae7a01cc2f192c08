//! GPU time of each pass, from timestamp queries written at the start and end of passes.
//! Available where the adapter has `TIMESTAMP_QUERY` (lavapipe has, with a 1 ns period);
//! elsewhere frames carry no GPU times.

use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::buffer;
use crate::gpu::readback::{map_and_read, readable_buffer};

/// A query set of two timestamps per pass and the buffers that bring them back.
#[derive(Debug)]
pub struct GpuTimer {
    queries: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    readable: wgpu::Buffer,
    passes: u32,
}

impl GpuTimer {
    /// A timer for up to `passes` passes a frame; `None` without `TIMESTAMP_QUERY`.
    pub fn new(gpu: &GpuContext, passes: u32) -> Option<GpuTimer> {
        if !gpu
            .device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
        {
            return None;
        }
        let count = 2 * passes;
        let bytes = u64::from(count) * size_of::<u64>() as u64;
        let queries = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count,
        });
        let resolve_usage = wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC;
        Some(GpuTimer {
            queries,
            resolved: buffer(&gpu.device, "timestamps", bytes, resolve_usage),
            readable: readable_buffer(&gpu.device, "timestamps read-back", bytes),
            passes,
        })
    }

    /// The timestamps of compute pass number `pass`.
    pub fn compute_writes(&self, pass: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * pass),
            end_of_pass_write_index: Some(2 * pass + 1),
        }
    }

    /// The timestamps of render pass number `pass`.
    pub fn render_writes(&self, pass: u32) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * pass),
            end_of_pass_write_index: Some(2 * pass + 1),
        }
    }

    /// Records the copy of the first `passes` passes' timestamps for [`GpuTimer::read`].
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder, passes: u32) {
        let count = 2 * passes.min(self.passes);
        encoder.resolve_query_set(&self.queries, 0..count, &self.resolved, 0);
        encoder.copy_buffer_to_buffer(
            &self.resolved,
            0,
            &self.readable,
            0,
            u64::from(count) * size_of::<u64>() as u64,
        );
    }

    /// Milliseconds of each of the first `passes` passes, waiting for the GPU.
    pub fn read(&self, gpu: &GpuContext, passes: u32) -> Result<Vec<f64>, GpuError> {
        let bytes = map_and_read(gpu, &self.readable)?;
        let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
        let period_ns = f64::from(gpu.queue.get_timestamp_period());
        Ok(ticks
            .chunks_exact(2)
            .take(passes as usize)
            .map(|t| t[1].saturating_sub(t[0]) as f64 * period_ns * 1e-6)
            .collect())
    }
}
