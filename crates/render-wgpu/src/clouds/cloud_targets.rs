//! The images a renderer frame's cloud steps write and read (`frame_pass.rs`,
//! `frame_front.rs`, `spheres/frame_spheres.rs`), made for one frame size and the layer's
//! and the spheres' resolution divisors, and kept for the frames that follow.

use atmosphere_core::clouds::layer::upsample::reduced_size;

use crate::clouds::composite_inputs::CompositeTextures;
use crate::clouds::frame_clouds::FRONT_GRID_SCALE;
use crate::clouds::front_targets::ReducedFrontTargets;
use crate::clouds::spheres::reduced_targets::ReducedSphereTargets;
use crate::frame::surface_buffer::{GEOMETRY_FORMAT, black_albedo};
use crate::gpu::context::GpuContext;
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::texture_2d;
use crate::gpu::pixel_list::PixelList;

/// The cloud images' format: rgb radiance, a transmittance.
pub const CLOUD_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// The reduced march's segments, (t0, t1) per ray.
pub const SEGMENT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Float;

/// The images (and the list of pixels to march) of one frame size the cloud steps write
/// and read.
#[derive(Debug)]
pub struct CloudTargets {
    /// The model's pixels, whole (L_full).
    pub full: wgpu::Texture,
    /// The model's pixels ended at the cloud (L_front).
    pub front: wgpu::Texture,
    /// The cloud's radiance (rgb) and transmittance (a) of the layer's march.
    pub cloud: wgpu::Texture,
    /// The same of the spheres (blended with the march in the hand-over band).
    pub spheres: wgpu::Texture,
    /// The second run's surface: the cloud's entry (`surface_buffer.rs`'s layout).
    pub front_geometry: wgpu::Texture,
    /// Its albedo: 0, Lambertian.
    pub front_albedo: wgpu::Texture,
    /// The pixels a reduced march's upsample leaves to the listed march, or why the
    /// device cannot hold a list of this size.
    pub march_list: Result<PixelList, String>,
    /// The pixels the composite cannot read from the reduced run's taps (where the
    /// device cannot hold the list, the composite takes every pixel by the whole rule).
    pub composite_list: Result<PixelList, String>,
    /// The resolution divisor these were made for, and above 1 the reduced march's
    /// image and segments.
    pub divisor: u32,
    pub reduced: Option<[wgpu::Texture; 2]>,
    /// The spheres' reduced images, where their resolution divisor is above 1.
    pub spheres_reduced: Option<ReducedSphereTargets>,
    /// The model's reduced runs in front of the cloud (`frame_front.rs`), one for each
    /// of the layer's and the spheres' divisors above 1.
    pub front_reduced: Vec<ReducedFrontTargets>,
}

impl CloudTargets {
    /// The targets of a frame of `width` x `height` whose layer is marched at one pixel
    /// in `divisor` x `divisor` and whose spheres are shaded at one in
    /// `spheres_divisor` x `spheres_divisor`.
    pub fn new(
        gpu: &GpuContext,
        (width, height): (u32, u32),
        (divisor, spheres_divisor): (u32, u32),
    ) -> CloudTargets {
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let image = |label, format| texture_2d(&gpu.device, label, (width, height), format, usage);
        let front_albedo = black_albedo(gpu, "cloud front albedo", (width, height));
        let mut targets = CloudTargets {
            full: image("cloud full", HDR_FORMAT),
            front: image("cloud front", HDR_FORMAT),
            cloud: image("cloud image", CLOUD_FORMAT),
            spheres: image("cloud spheres image", CLOUD_FORMAT),
            front_geometry: image("cloud front geometry", GEOMETRY_FORMAT),
            front_albedo,
            march_list: PixelList::new(gpu, "cloud frame", (width, height)),
            composite_list: PixelList::new(gpu, "cloud composite", (width, height)),
            divisor,
            reduced: (divisor > 1).then(|| {
                let size = reduced_size(width, height, divisor);
                [
                    texture_2d(
                        &gpu.device,
                        "cloud reduced image",
                        size,
                        CLOUD_FORMAT,
                        usage,
                    ),
                    texture_2d(
                        &gpu.device,
                        "cloud reduced segments",
                        size,
                        SEGMENT_FORMAT,
                        usage,
                    ),
                ]
            }),
            spheres_reduced: (spheres_divisor > 1)
                .then(|| ReducedSphereTargets::new(gpu, (width, height), spheres_divisor)),
            front_reduced: Vec::new(),
        };
        for cloud_divisor in [divisor, spheres_divisor] {
            let d = FRONT_GRID_SCALE * cloud_divisor;
            if cloud_divisor > 1 && targets.front_reduced(d).is_none() {
                let run = ReducedFrontTargets::new(gpu, (width, height), d);
                targets.front_reduced.push(run);
            }
        }
        targets
    }

    /// The model's reduced run in front of the cloud at `divisor`, if these hold one.
    pub fn front_reduced(&self, divisor: u32) -> Option<&ReducedFrontTargets> {
        self.front_reduced.iter().find(|r| r.divisor == divisor)
    }

    /// Whether these were made for a layer's `divisor` and the spheres'
    /// `spheres_divisor`.
    pub fn made_for(&self, divisor: u32, spheres_divisor: u32) -> bool {
        let spheres = self.spheres_reduced.as_ref().map_or(1, |r| r.divisor);
        self.divisor == divisor && spheres == spheres_divisor.max(1)
    }

    /// Views of the second run's surface, for its `PassIo`.
    pub fn front_surface(&self) -> [wgpu::TextureView; 2] {
        [
            self.front_geometry.create_view(&Default::default()),
            self.front_albedo.create_view(&Default::default()),
        ]
    }

    /// What the composite of a frame whose run in front of the cloud has `front_divisor`
    /// reads, writing `hdr`: the reduced run's images where it ran reduced.
    pub fn composite_textures<'a>(
        &'a self,
        front_divisor: u32,
        hdr: &'a wgpu::Texture,
    ) -> CompositeTextures<'a> {
        let reduced = self.front_reduced(front_divisor);
        CompositeTextures {
            full: &self.full,
            front: reduced.map_or(&self.front, |r| &r.radiance),
            hdr,
            entries: reduced.map_or(&self.front_geometry, |r| &r.entries),
            transmittance: reduced.map_or(&self.front_geometry, |r| &r.transmittance),
        }
    }
}
