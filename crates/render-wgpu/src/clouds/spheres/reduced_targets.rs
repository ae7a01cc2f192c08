//! The images of a frame's cloud spheres shaded at a reduced resolution
//! (`frame_reduced.wgsl`), one ray per `divisor` x `divisor` pixels: the spheres and
//! their spans of the layer, which the upsample reads, and the air in front of the cloud
//! at the same rays, which the composite reads from orbit (`clouds/frame_front.rs`):
//! where each reduced ray enters the layer (the surface the sky model's reduced run ends
//! on, with its black albedo), that run's radiance, the atmosphere's transmittance to the
//! entry, and the frame's uniform with the reduced image's size.

use atmosphere_core::clouds::layer::upsample::reduced_size;

use crate::clouds::spheres::frame_spheres::CLOUD_IMAGE_FORMAT;
use crate::frame::surface_buffer::{GEOMETRY_FORMAT, black_albedo};
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{texture_2d, uniform_buffer};

/// The reduced rays' spans of the layer, (t0, t1) per ray.
pub const SPAN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Float;

/// The reduced rays' transmittance in front of the cloud: f32, as 1 - T is what the
/// composite divides by and is small from orbit.
pub const TRANSMITTANCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The reduced images of one frame size and divisor; see the module documentation.
#[derive(Debug)]
pub struct ReducedSphereTargets {
    pub divisor: u32,
    /// The spheres at the reduced rays (rgb radiance, a transmittance).
    pub image: wgpu::Texture,
    /// Each reduced ray's span of the layer.
    pub spans: wgpu::Texture,
    /// Where each reduced ray enters the layer (`surface_buffer.rs`'s geometry layout;
    /// w = 0 where it has no span).
    pub front_geometry: wgpu::Texture,
    /// Its albedo: 0, Lambertian.
    pub front_albedo: wgpu::Texture,
    /// The sky model's radiance at the reduced rays ended where they enter the layer.
    pub front: wgpu::Texture,
    /// The atmosphere's transmittance along each reduced ray to that entry.
    pub front_transmittance: wgpu::Texture,
    /// The frame's `FrameUniform` with the reduced image's size, which the model's
    /// reduced run reads.
    pub frame: wgpu::Buffer,
}

impl ReducedSphereTargets {
    /// The reduced images of a `width` x `height` frame shaded at `divisor`.
    pub fn new(gpu: &GpuContext, (width, height): (u32, u32), divisor: u32) -> Self {
        let size = reduced_size(width, height, divisor);
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let image = |label, format| texture_2d(&gpu.device, label, size, format, usage);
        let front_albedo = black_albedo(gpu, "cloud spheres reduced front albedo", size);
        ReducedSphereTargets {
            divisor,
            image: image("cloud spheres reduced", CLOUD_IMAGE_FORMAT),
            spans: image("cloud spheres reduced spans", SPAN_FORMAT),
            front_geometry: image("cloud spheres reduced front geometry", GEOMETRY_FORMAT),
            front_albedo,
            front: image("cloud spheres reduced front", HDR_FORMAT),
            front_transmittance: image(
                "cloud spheres reduced front transmittance",
                TRANSMITTANCE_FORMAT,
            ),
            frame: uniform_buffer(
                &gpu.device,
                "cloud spheres reduced frame",
                size_of::<FrameUniform>(),
            ),
        }
    }

    /// Views of the reduced run's surface, for its `PassIo`.
    pub fn front_surface(&self) -> [wgpu::TextureView; 2] {
        [
            self.front_geometry.create_view(&Default::default()),
            self.front_albedo.create_view(&Default::default()),
        ]
    }
}
