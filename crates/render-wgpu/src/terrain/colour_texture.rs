//! The colour map on the GPU: an sRGB texture with its mip chain (`colour_mips.rs`).

use crate::gpu::context::GpuContext;
use crate::terrain::colour_map::ColourMap;
use crate::terrain::colour_mips::colour_mips;

/// The colour map as an sRGB texture with its mip chain.
pub fn upload_colour(gpu: &GpuContext, map: &ColourMap) -> wgpu::TextureView {
    let levels = colour_mips(map);
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("colour map"),
        size: wgpu::Extent3d {
            width: map.width as u32,
            height: map.height as u32,
            depth_or_array_layers: 1,
        },
        mip_level_count: levels.len() as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (level, mip) in levels.iter().enumerate() {
        gpu.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: level as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(&mip.texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(mip.width as u32 * 4),
                rows_per_image: Some(mip.height as u32),
            },
            wgpu::Extent3d {
                width: mip.width as u32,
                height: mip.height as u32,
                depth_or_array_layers: 1,
            },
        );
    }
    texture.create_view(&Default::default())
}
