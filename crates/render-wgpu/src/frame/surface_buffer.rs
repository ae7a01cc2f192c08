//! The surface a frame's rays end on, per pixel: what the terrain pass draws (or a
//! caller gives, [`crate::Renderer::render_with_surface`]) and every model's pixel pass
//! reads at bindings 30 and 31 (`shaders/common/surface.wgsl`) to end its rays there and light
//! the surface with its own irradiance: the depth and position input of aerial
//! perspective. Its CPU twin is atmosphere-core's `surface_lighting::radiance_with_surface`.

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::texture_2d;

/// Per pixel: xyz the outward unit normal, w the distance from the camera along the
/// pixel's ray, m (0: no surface).
pub const GEOMETRY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// Per pixel: the surface's albedo, linear, in rgb; alpha 1 for a Lambertian surface, 0
/// for the sea (`shaders/common/sea_surface.wgsl`), whose rgb is the water body's albedo.
pub const ALBEDO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// The bindings of the two textures in every model's pixel pass.
pub const GEOMETRY_BINDING: u32 = 30;
pub const ALBEDO_BINDING: u32 = 31;

/// One pixel's surface, as a caller gives it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceTexel {
    /// Outward unit normal, planet axes.
    pub normal: [f32; 3],
    /// Distance from the camera along the pixel's ray, m; 0 for no surface.
    pub distance_m: f32,
    /// Linear albedo at the three wavelengths, stored in 8 bits each.
    pub albedo: [f32; 3],
    /// The sea: a specular interface over a water body of albedo `albedo`
    /// (atmosphere-core's `optics::sea_surface`), not a Lambertian surface.
    pub water: bool,
}

impl SurfaceTexel {
    /// The albedo as the GPU reads it back from 8 bits.
    pub fn stored_albedo(&self) -> [f32; 3] {
        self.albedo.map(|a| unorm8(a) as f32 / 255.0)
    }
}

/// Checks a caller's `surface` for a frame of `pixels` pixels: one texel each, every
/// distance finite and >= 0, every normal of a surface non-zero.
pub fn check_surface(surface: &[SurfaceTexel], pixels: usize) -> Result<(), RenderError> {
    if surface.len() != pixels {
        return Err(RenderError::Frame(format!(
            "the surface has {} texels for {pixels} pixels",
            surface.len()
        )));
    }
    match surface.iter().position(|t| {
        !(t.distance_m.is_finite() && t.distance_m >= 0.0)
            || t.distance_m > 0.0 && glam::Vec3::from_array(t.normal).try_normalize().is_none()
    }) {
        Some(bad) => Err(RenderError::Frame(format!(
            "surface texel {bad}: the distance must be finite and >= 0 and the normal non-zero"
        ))),
        None => Ok(()),
    }
}

/// An albedo texture of `size`, 0 and Lambertian everywhere: the surface of a model's run
/// ended where its rays enter a cloud, which reflects nothing.
pub fn black_albedo(gpu: &GpuContext, label: &str, (width, height): (u32, u32)) -> wgpu::Texture {
    let albedo = texture_2d(
        &gpu.device,
        label,
        (width, height),
        ALBEDO_FORMAT,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    let black = vec![[0u8, 0, 0, 255]; width as usize * height as usize];
    gpu.queue.write_texture(
        albedo.as_image_copy(),
        bytemuck::cast_slice(&black),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(width * 4),
            rows_per_image: Some(height),
        },
        albedo.size(),
    );
    albedo
}

fn unorm8(a: f32) -> u8 {
    (a.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The two textures of one image size.
#[derive(Debug)]
pub struct SurfaceBuffer {
    pub geometry: wgpu::Texture,
    pub albedo: wgpu::Texture,
}

impl SurfaceBuffer {
    /// Textures of `width` x `height`, drawable by a render pass and readable by the
    /// model passes; their content is undefined until drawn or uploaded.
    pub fn new(gpu: &GpuContext, width: u32, height: u32) -> SurfaceBuffer {
        let texture = |label, format| {
            texture_2d(
                &gpu.device,
                label,
                (width, height),
                format,
                wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_DST
                    | wgpu::TextureUsages::COPY_SRC,
            )
        };
        SurfaceBuffer {
            geometry: texture("surface geometry", GEOMETRY_FORMAT),
            albedo: texture("surface albedo", ALBEDO_FORMAT),
        }
    }

    /// (width, height) in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.geometry.width(), self.geometry.height())
    }

    /// Writes `texels` (row-major, one per pixel; the caller checks the count).
    pub fn upload(&self, gpu: &GpuContext, texels: &[SurfaceTexel]) {
        let (width, height) = self.size();
        let geometry: Vec<[f32; 4]> = texels
            .iter()
            .map(|t| [t.normal[0], t.normal[1], t.normal[2], t.distance_m])
            .collect();
        let albedo: Vec<[u8; 4]> = texels
            .iter()
            .map(|t| {
                let [r, g, b] = t.albedo.map(unorm8);
                [r, g, b, if t.water { 0 } else { 255 }]
            })
            .collect();
        let write = |texture: &wgpu::Texture, bytes: &[u8], texel_bytes: u32| {
            gpu.queue.write_texture(
                texture.as_image_copy(),
                bytes,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(width * texel_bytes),
                    rows_per_image: Some(height),
                },
                texture.size(),
            );
        };
        write(&self.geometry, bytemuck::cast_slice(&geometry), 16);
        write(&self.albedo, bytemuck::cast_slice(&albedo), 4);
    }

    /// The layout entries of bindings 30 and 31 (`shaders/common/surface.wgsl`).
    pub fn layout_entries() -> [wgpu::BindGroupLayoutEntry; 2] {
        use crate::gpu::pipeline::texture_entry;
        use wgpu::TextureViewDimension::D2;
        [
            texture_entry(GEOMETRY_BINDING, D2),
            texture_entry(ALBEDO_BINDING, D2),
        ]
    }

    /// Views of the two textures, for a model's pixel pass (`crate::sky::pixel_pass`).
    pub fn views(&self) -> [wgpu::TextureView; 2] {
        [
            self.geometry.create_view(&Default::default()),
            self.albedo.create_view(&Default::default()),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn albedo_is_stored_in_eight_bits() {
        let t = SurfaceTexel {
            albedo: [0.0, 0.5, 1.5],
            ..Default::default()
        };
        assert_eq!(t.stored_albedo(), [0.0, 128.0 / 255.0, 1.0]);
    }
}
