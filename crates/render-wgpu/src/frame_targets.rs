//! The renderer's images of one size: the HDR and display targets, the surface buffer
//! the rays end on, and the cloud steps' images once a frame of that size has clouds.

use crate::clouds::cloud_targets::CloudTargets;
use crate::frame::surface_buffer::SurfaceBuffer;
use crate::gpu::context::GpuContext;
use crate::gpu::formats::{HDR_FORMAT, LDR_FORMAT};
use crate::gpu::pipeline::texture_2d;

/// The HDR and display targets of one image size, and the surface the rays end on.
#[derive(Debug)]
pub struct Targets {
    pub hdr: wgpu::Texture,
    pub ldr: wgpu::Texture,
    pub surface: SurfaceBuffer,
    /// The cloud steps' images, made when a frame of this size first has clouds.
    pub clouds: Option<CloudTargets>,
}

impl Targets {
    /// The targets of a `width` x `height` image, without cloud images.
    pub fn new(gpu: &GpuContext, width: u32, height: u32) -> Targets {
        Targets {
            hdr: target(gpu, "hdr", HDR_FORMAT, (width, height)),
            ldr: target(gpu, "ldr", LDR_FORMAT, (width, height)),
            surface: SurfaceBuffer::new(gpu, width, height),
            clouds: None,
        }
    }
}

/// A colour target: storage for the HDR image the passes write, a render attachment for
/// the display image; both sampled and copied out.
fn target(
    gpu: &GpuContext,
    label: &str,
    format: wgpu::TextureFormat,
    size: (u32, u32),
) -> wgpu::Texture {
    let usage = if format == HDR_FORMAT {
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING
    } else {
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING
    };
    texture_2d(
        &gpu.device,
        label,
        size,
        format,
        usage | wgpu::TextureUsages::COPY_SRC,
    )
}
