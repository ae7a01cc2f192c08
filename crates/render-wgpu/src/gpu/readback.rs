//! Copying GPU results back to the CPU, waiting for the GPU: the texels of a 2D texture,
//! row-major, and mapped buffers.

use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::buffer;

/// A buffer of `size` bytes that the GPU copies results into and the CPU then maps
/// ([`map_and_read`]).
pub fn readable_buffer(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    let usage = wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ;
    buffer(device, label, size, usage)
}

/// The raw bytes of `texture`'s texels, row-major without row padding (a 3D texture
/// slice after slice); `texel_bytes` is the size of one texel of its format.
pub fn read_texture(
    gpu: &GpuContext,
    texture: &wgpu::Texture,
    texel_bytes: u32,
) -> Result<Vec<u8>, GpuError> {
    let (width, height) = (texture.width(), texture.height());
    let rows = height * texture.depth_or_array_layers();
    let row_bytes = width * texel_bytes;
    let padded_row_bytes = row_bytes.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let size = u64::from(padded_row_bytes) * u64::from(rows);
    let buffer = readable_buffer(&gpu.device, "read-back", size);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row_bytes),
                rows_per_image: Some(height),
            },
        },
        texture.size(),
    );
    gpu.queue.submit([encoder.finish()]);
    let bytes = map_and_read(gpu, &buffer)?;
    Ok(bytes
        .chunks_exact(padded_row_bytes as usize)
        .flat_map(|row| &row[..row_bytes as usize])
        .copied()
        .collect())
}

/// The contents of a `MAP_READ` buffer once the GPU has finished the work submitted so
/// far.
pub fn map_and_read(gpu: &GpuContext, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    let (sender, receiver) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |result| {
        // The receiver lives until the poll below has returned.
        let _ = sender.send(result);
    });
    gpu.device.poll(wgpu::PollType::wait_indefinitely())?;
    receiver
        .recv()
        .expect("map_async calls back during a waiting poll")?;
    let bytes = buffer.get_mapped_range(..)?.to_vec();
    buffer.unmap();
    Ok(bytes)
}
