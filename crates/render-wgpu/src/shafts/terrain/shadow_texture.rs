//! The shadow map on the GPU: its levels' tops stacked in one R32Float texture, finest
//! on top (read texel by texel), and its parameters in a uniform buffer; a 2 x 2
//! placeholder with shafts off.

use atmosphere_core::shafts::ShadowMap;

use crate::gpu::context::GpuContext;
use crate::gpu::pipeline::uniform_buffer;
use crate::shafts::terrain::uniform::ShadowMapUniform;

/// The shadow map's texture and parameters, as the sky passes bind them.
#[derive(Debug)]
pub struct ShadowTexture {
    texture: wgpu::Texture,
    params: wgpu::Buffer,
}

impl ShadowTexture {
    /// The placeholder of a frame without shafts.
    pub fn new(gpu: &GpuContext) -> ShadowTexture {
        let texture = tops_texture(gpu, (2, 2));
        let params = uniform_buffer(&gpu.device, "shadow map", size_of::<ShadowMapUniform>());
        gpu.write_uniform(&params, &ShadowMapUniform::default());
        ShadowTexture { texture, params }
    }

    /// Uploads `map` (`None`: shafts off) for the frames that follow, at most `samples.0`
    /// and at least `samples.1` samples per view segment.
    pub fn upload(&mut self, gpu: &GpuContext, map: Option<&ShadowMap>, samples: (u32, u32)) {
        let Some(map) = map else {
            // No levels; the sample counts still bound the cloud's shafts.
            let none = ShadowMapUniform {
                size: [0, 0, samples.0, samples.1],
                ..ShadowMapUniform::default()
            };
            gpu.write_uniform(&self.params, &none);
            return;
        };
        let n = map.grid.size as u32;
        let tops: Vec<f32> = map
            .levels()
            .flat_map(|m| m.tops_m.iter().copied())
            .collect();
        let rows = (tops.len() / n as usize) as u32;
        if (self.texture.width(), self.texture.height()) != (n, rows) {
            self.texture = tops_texture(gpu, (n, rows));
        }
        gpu.queue.write_texture(
            self.texture.as_image_copy(),
            bytemuck::cast_slice(&tops),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * n),
                rows_per_image: Some(rows),
            },
            wgpu::Extent3d {
                width: n,
                height: rows,
                depth_or_array_layers: 1,
            },
        );
        gpu.write_uniform(&self.params, &ShadowMapUniform::new(map, samples));
    }

    /// The tops' view (binding 9 of a pass that reads it).
    pub fn view(&self) -> wgpu::TextureView {
        self.texture.create_view(&Default::default())
    }

    /// The parameters' buffer (binding 10).
    pub fn params(&self) -> &wgpu::Buffer {
        &self.params
    }
}

fn tops_texture(gpu: &GpuContext, (width, height): (u32, u32)) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("shadow map tops"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::R32Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}
