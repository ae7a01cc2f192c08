//! Reading the tables back, for tests: a table of the store, a scattering texture, and
//! the state of the loop over orders.

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::readback::{map_and_read, read_texture, readable_buffer};
use crate::sky::bruneton::order_state::OrderState;
use crate::sky::bruneton::pass::BrunetonPass;
use crate::sky::bruneton::store::StoreTable;
use crate::sky::bruneton::tables::Tables;

/// `size` bytes of `source` from `offset`, copied into a mappable buffer and read.
fn read_buffer(
    gpu: &GpuContext,
    source: &wgpu::Buffer,
    offset: u64,
    size: u64,
) -> Result<Vec<u8>, RenderError> {
    let buffer = readable_buffer(&gpu.device, "bruneton read-back", size);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(source, offset, &buffer, 0, size);
    gpu.queue.submit([encoder.finish()]);
    Ok(map_and_read(gpu, &buffer)?)
}

impl Tables {
    /// The state of the last loop over orders.
    pub fn read_state(&self, gpu: &GpuContext) -> Result<OrderState, RenderError> {
        let size = size_of::<OrderState>() as u64;
        let bytes = read_buffer(gpu, &self.state, 0, size)?;
        Ok(bytemuck::pod_read_unaligned(&bytes))
    }
}

impl BrunetonPass {
    /// A table of the store as last built, vec4 per texel (rgb = the three channels), in
    /// the CPU's order (`ScatteringSize::index`, `IrradianceMapping::index`).
    pub fn read_table(
        &self,
        gpu: &GpuContext,
        table: StoreTable,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        let tables = &self.tables;
        let (offset, size) = tables.layout.range(table);
        let bytes = read_buffer(gpu, &tables.store, offset, size)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// Scattering texture `k` (0 single Rayleigh, 1 single Mie, 2 orders two and up),
    /// texels in x, y, z order.
    pub fn read_scattering_texture(
        &self,
        gpu: &GpuContext,
        k: usize,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        let bytes = read_texture(gpu, &self.tables.textures[k], 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// The state of the last loop over orders: the highest order added and each order's
    /// share.
    pub fn read_orders(&self, gpu: &GpuContext) -> Result<OrderState, RenderError> {
        self.tables.read_state(gpu)
    }
}
