//! The chunks' normal maps (`normal_map.rs`) on the GPU: two `Rgba16Float` textures per
//! chunk (xyz the normal, w unused), its own map and its parent's over it
//! (`detail_morph.rs`), bound with a clamped bilinear sampler as the terrain shader's
//! group 1, set per draw.

use crate::gpu::context::GpuContext;
use crate::gpu::pipeline::{float_texture_entry, in_stage, ordered_bind_group, texture_2d};
use crate::terrain::detail_morph::ParentNormalMap;
use crate::terrain::normal_map::NormalMap;

/// The bind group layout and sampler of the chunks' normal maps.
#[derive(Debug)]
pub struct NormalTextures {
    pub layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
}

impl NormalTextures {
    pub fn new(device: &wgpu::Device) -> NormalTextures {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("terrain normal map"),
            entries: &[
                in_stage(
                    wgpu::ShaderStages::FRAGMENT,
                    float_texture_entry(0, wgpu::TextureViewDimension::D2, true),
                ),
                in_stage(
                    wgpu::ShaderStages::FRAGMENT,
                    float_texture_entry(2, wgpu::TextureViewDimension::D2, true),
                ),
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("terrain normal map"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        NormalTextures { layout, sampler }
    }

    /// Uploads a chunk's map `own` and its parent's over it, `parent`; returns their
    /// bind group.
    pub fn upload(
        &self,
        gpu: &GpuContext,
        own: &NormalMap,
        parent: &ParentNormalMap,
    ) -> wgpu::BindGroup {
        let (own, parent) = (texture_view(gpu, own), texture_view(gpu, &parent.map));
        ordered_bind_group(
            &gpu.device,
            Some("terrain normal map"),
            &self.layout,
            &[
                wgpu::BindingResource::TextureView(&own),
                wgpu::BindingResource::Sampler(&self.sampler),
                wgpu::BindingResource::TextureView(&parent),
            ],
        )
    }
}

/// `map` as an `Rgba16Float` texture.
fn texture_view(gpu: &GpuContext, map: &NormalMap) -> wgpu::TextureView {
    let side = map.texels;
    let texture = texture_2d(
        &gpu.device,
        "terrain normal map",
        (side, side),
        wgpu::TextureFormat::Rgba16Float,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    let texels: Vec<u16> = map
        .normals
        .iter()
        .flat_map(|n| [n[0], n[1], n[2], 0.0])
        .map(|c| half::f16::from_f32(c).to_bits())
        .collect();
    gpu.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture: &texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        bytemuck::cast_slice(&texels),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(side * 8),
            rows_per_image: Some(side),
        },
        wgpu::Extent3d {
            width: side,
            height: side,
            depth_or_array_layers: 1,
        },
    );
    texture.create_view(&Default::default())
}
