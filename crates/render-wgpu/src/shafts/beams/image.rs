//! A rendered beams image: radiance at the three wavelengths per pixel (W m^-2 sr^-1
//! nm^-1), read back as it is or tone-mapped to display pixels by the planet frame's
//! tone map (`post/`), so that both kinds of scene come out of `atmos render` alike.

use crate::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::formats::LDR_FORMAT;
use crate::gpu::pipeline::texture_2d;
use crate::gpu::readback::read_texture;
use crate::post::tone_map::ToneMap;
use crate::post::tone_map_pass::ToneMapPass;

/// The format of the radiance image: f32, so that the parity test sees the passes' own
/// rounding and nothing else.
pub const RADIANCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The radiance image of a beams pass.
#[derive(Debug)]
pub struct BeamImage {
    pub radiance: wgpu::Texture,
}

impl BeamImage {
    /// An image of `width` x `height` pixels for a pass to write or draw into.
    pub fn new(gpu: &GpuContext, width: u32, height: u32) -> BeamImage {
        let usage = wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC;
        BeamImage {
            radiance: texture_2d(
                &gpu.device,
                "beams radiance",
                (width, height),
                RADIANCE_FORMAT,
                usage,
            ),
        }
    }

    /// Radiance at 680, 550 and 440 nm (xyz; w = 1) per pixel, row by row from the top.
    pub fn read_radiance(&self, gpu: &GpuContext) -> Result<Vec<[f32; 4]>, RenderError> {
        let bytes = read_texture(gpu, &self.radiance, 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// The display pixels (sRGB, alpha 255) at exposure `ev100`, by the tone-map pass.
    pub fn tone_mapped(&self, gpu: &GpuContext, ev100: f64) -> Result<Vec<[u8; 4]>, RenderError> {
        let tone_map = ToneMap::new(RGB_WAVELENGTHS_NM, ev100)?;
        let pass = ToneMapPass::new(gpu)?;
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let size = (self.radiance.width(), self.radiance.height());
        let ldr = texture_2d(&gpu.device, "beams display", size, LDR_FORMAT, usage);
        let target = ldr.create_view(&Default::default());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        pass.encode(
            gpu,
            &tone_map.uniform(),
            &self.radiance,
            &target,
            &mut encoder,
            None,
        );
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_texture(gpu, &ldr, 4)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}
