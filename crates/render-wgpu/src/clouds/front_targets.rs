//! The images of the sky model's reduced run in front of the cloud from above the layer
//! (`frame_front.rs`), one ray per `divisor` x `divisor` pixels (`layer/upsample.rs`'s
//! map): where each ray enters the sphere of the layer's top (the surface the run ends
//! on, with its black albedo), the atmosphere's transmittance to there
//! (`clouds/front_rays.wgsl` writes both), the run's radiance, and the uniforms of the
//! run (the frame's, with the reduced image's size) and of the rays (the top's radius).

use atmosphere_core::clouds::layer::upsample::reduced_size;

use crate::frame::surface_buffer::{GEOMETRY_FORMAT, black_albedo};
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{texture_2d, uniform_buffer};

/// The reduced rays' transmittance in front of the cloud: f32, as the composite takes
/// its logarithm and 1 - T, which are small from orbit.
pub const TRANSMITTANCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The reduced run's images of one frame size and divisor; see the module documentation.
#[derive(Debug)]
pub struct ReducedFrontTargets {
    pub divisor: u32,
    /// Where each ray enters the layer (`surface_buffer.rs`'s geometry layout; w = 0
    /// where it does not).
    pub entries: wgpu::Texture,
    /// Their albedo: 0, Lambertian.
    pub albedo: wgpu::Texture,
    /// The atmosphere's transmittance along each ray to its entry.
    pub transmittance: wgpu::Texture,
    /// The sky model's radiance along each ray ended at its entry.
    pub radiance: wgpu::Texture,
    /// The frame's `FrameUniform` with the reduced image's size.
    pub frame: wgpu::Buffer,
    /// x: the radius of the layer's top, m.
    pub layer: wgpu::Buffer,
}

impl ReducedFrontTargets {
    /// The reduced run's images of a `width` x `height` frame at `divisor`.
    pub fn new(gpu: &GpuContext, (width, height): (u32, u32), divisor: u32) -> Self {
        let size = reduced_size(width, height, divisor);
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let image = |label, format| texture_2d(&gpu.device, label, size, format, usage);
        ReducedFrontTargets {
            divisor,
            entries: image("cloud front reduced entries", GEOMETRY_FORMAT),
            albedo: black_albedo(gpu, "cloud front reduced albedo", size),
            transmittance: image("cloud front reduced transmittance", TRANSMITTANCE_FORMAT),
            radiance: image("cloud front reduced radiance", HDR_FORMAT),
            frame: uniform_buffer(
                &gpu.device,
                "cloud front reduced frame",
                size_of::<FrameUniform>(),
            ),
            layer: uniform_buffer(&gpu.device, "cloud front reduced layer", 16),
        }
    }

    /// The reduced image's size.
    pub fn size(&self) -> (u32, u32) {
        (self.radiance.width(), self.radiance.height())
    }

    /// Views of the run's surface, for its `PassIo`.
    pub fn surface(&self) -> [wgpu::TextureView; 2] {
        [
            self.entries.create_view(&Default::default()),
            self.albedo.create_view(&Default::default()),
        ]
    }
}
