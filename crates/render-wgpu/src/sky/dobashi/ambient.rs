//! The dobashi model's ambient term on the GPU: the table psi per sun cosine that
//! `shaders/sky/dobashi/ambient.wgsl` builds (the CPU's `AmbientTable::build`), the table
//! of ones its own rays read, and what it depends on.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::dobashi::DobashiSettings;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::texture_2d;
use crate::sky::table_limits::table_extent;
use crate::sky::transmittance::TABLE_FORMAT;

/// The settings the ambient table depends on besides the tables'.
pub fn ambient_key(s: &DobashiSettings) -> [usize; 2] {
    [s.ambient_directions, s.ambient_sun_angles]
}

/// What the ambient table was built from: the atmosphere, the table settings, the
/// ambient settings and the orders.
pub type AmbientKey = (Atmosphere, [usize; 5], [usize; 2], Option<u32>);

/// A table of ones in the ambient table's place: psi = 1 at every sun angle.
pub fn unit_ambient_texture(gpu: &GpuContext) -> wgpu::Texture {
    let texture = texture_2d(
        &gpu.device,
        "dobashi unit ambient",
        (2, 1),
        TABLE_FORMAT,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    gpu.queue.write_texture(
        texture.as_image_copy(),
        bytemuck::cast_slice(&[[1.0f32; 4]; 2]),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(32),
            rows_per_image: None,
        },
        texture.size(),
    );
    texture
}

/// The ambient table's texture of `sun_angles` x 1 texels, or why this GPU cannot hold it.
pub fn ambient_texture(gpu: &GpuContext, sun_angles: usize) -> Result<wgpu::Texture, RenderError> {
    let extent = table_extent(
        gpu,
        "dobashi ambient table",
        "ambient_sun_angles",
        wgpu::TextureDimension::D2,
        (sun_angles, 1, 1),
    )?;
    Ok(texture_2d(
        &gpu.device,
        "dobashi ambient",
        (extent.width, 1),
        TABLE_FORMAT,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
    ))
}
