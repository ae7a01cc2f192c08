//! The images of a frame's cloud spheres shaded at a reduced resolution
//! (`frame_reduced.wgsl`), one ray per `divisor` x `divisor` pixels: the spheres and
//! their spans of the layer, which the upsample (`frame_upsample.wgsl`) reads, and the
//! list of the full pixels it leaves to its listed pixels' pass.

use atmosphere_core::clouds::layer::upsample::reduced_size;

use crate::clouds::spheres::image_formats::{CLOUD_IMAGE_FORMAT, SPAN_FORMAT};
use crate::gpu::context::GpuContext;
use crate::gpu::pipeline::texture_2d;
use crate::gpu::pixel_list::PixelList;

/// The reduced images of one frame size and divisor.
#[derive(Debug)]
pub struct ReducedSphereTargets {
    pub divisor: u32,
    /// The spheres at the reduced rays (rgb radiance, a transmittance).
    pub image: wgpu::Texture,
    /// Each reduced ray's span of the layer.
    pub spans: wgpu::Texture,
    /// The full pixels the upsample cannot interpolate, or why the device cannot hold a
    /// list of this size.
    pub list: Result<PixelList, String>,
}

impl ReducedSphereTargets {
    /// The reduced images of a `width` x `height` frame shaded at `divisor`.
    pub fn new(gpu: &GpuContext, (width, height): (u32, u32), divisor: u32) -> Self {
        let size = reduced_size(width, height, divisor);
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let image = |label, format| texture_2d(&gpu.device, label, size, format, usage);
        ReducedSphereTargets {
            divisor,
            image: image("cloud spheres reduced", CLOUD_IMAGE_FORMAT),
            spans: image("cloud spheres reduced spans", SPAN_FORMAT),
            list: PixelList::new(gpu, "cloud spheres", (width, height)),
        }
    }
}
