//! What the cloud layer pass reads besides its parameters: the cover grid as an
//! `R32Float` texture (read texel by texel, bilinear in the shader as on the CPU) and
//! Riley et al. 2004's A_n and F_n tables as one storage buffer, in the order
//! `shaders/clouds/layer_params.wgsl` documents; and the cover and tables on the CPU,
//! from which a frame's cloud spheres are made (`spheres/sphere_cache.rs`).

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::orders::{ANGLES, ORDERS, ScatteringOrders};
use wgpu::util::DeviceExt;

use crate::clouds::spheres::sphere_cache::SphereCache;
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::texture_2d;

/// The cover texture and the tables on the GPU.
#[derive(Debug)]
pub struct LayerInputs {
    pub cover: wgpu::Texture,
    pub cover_size: (usize, usize),
    pub orders: wgpu::Buffer,
    /// The cloud spheres of the same cover and tables, made when a frame needs them.
    pub spheres: SphereCache,
}

impl LayerInputs {
    /// Uploads `cover` and `orders` (three wavelengths: 680, 550, 440 nm).
    pub fn new(
        gpu: &GpuContext,
        cover: &CoverGrid,
        orders: &ScatteringOrders,
    ) -> Result<LayerInputs, RenderError> {
        if orders.wavelengths() != 3 {
            return Err(RenderError::Frame(format!(
                "cloud phase tables for {} wavelengths; the GPU renders 3 (680, 550, 440 nm)",
                orders.wavelengths()
            )));
        }
        let limit = gpu.device.limits().max_texture_dimension_2d as usize;
        if cover.width() > limit || cover.height() > limit {
            return Err(RenderError::Frame(format!(
                "cloud cover grid {} x {} exceeds this GPU's {limit} texels a side",
                cover.width(),
                cover.height()
            )));
        }
        let (width, height) = (cover.width() as u32, cover.height() as u32);
        let texture = texture_2d(
            &gpu.device,
            "cloud cover",
            (width, height),
            wgpu::TextureFormat::R32Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        );
        gpu.queue.write_texture(
            texture.as_image_copy(),
            bytemuck::cast_slice(cover.values()),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(width * 4),
                rows_per_image: Some(height),
            },
            texture.size(),
        );
        let mut values: Vec<f32> = Vec::with_capacity(3 * ORDERS * (ANGLES + 1) + 15);
        for w in 0..3 {
            values.extend(orders.table(w).iter().map(|&a| a as f32));
        }
        for w in 0..3 {
            values.extend((1..=ORDERS).map(|n| orders.forward_fraction(w, n) as f32));
        }
        values.extend((0..3).map(|w| orders.asymmetry(w) as f32));
        for w in 0..3 {
            values.extend(orders.moments(w)[1..].iter().map(|&chi| chi as f32));
        }
        let buffer = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("cloud scattering orders"),
                contents: bytemuck::cast_slice(&values),
                usage: wgpu::BufferUsages::STORAGE,
            });
        Ok(LayerInputs {
            cover: texture,
            cover_size: (cover.width(), cover.height()),
            orders: buffer,
            spheres: SphereCache::new(cover.clone(), orders.clone()),
        })
    }
}
