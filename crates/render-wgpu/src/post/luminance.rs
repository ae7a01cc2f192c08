//! The log-average luminance of an HDR image, for automatic exposure
//! (`shaders/post/luminance.wgsl`): one compute dispatch of [`GRID`] x [`GRID`] workgroups
//! that each sum `ln L` and a count over a strided share of the pixels, then a read-back
//! of those few pairs (2 KiB), added on the CPU. Pixels whose luminance is at most
//! [`FLOOR_CD_M2`] (space, the night side) are left out, so the mean is that of what is
//! lit; with none lit the result is the floor.
//!
//! Luminance is CIE Y in cd/m^2 of the spectral radiance at the image's three
//! wavelengths, with atmosphere-core's [`SpectrumToColor`] weights (the tone map's).
//! [`log_average_luminance`] is the CPU twin, the specification of the pass.

use atmosphere_core::color::SpectrumToColor;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::{
    ComputePipeline, buffer, storage_buffer_entry, texture_entry, uniform_buffer, uniform_entry,
};
use crate::gpu::readback::{map_and_read, readable_buffer};

/// Workgroups along each side of the dispatch (`GRID` in the shader).
pub const GRID: u32 = 16;

/// Luminances at or below this (cd/m^2, darker than a moonless night sky) are left out.
pub const FLOOR_CD_M2: f64 = 1e-4;

/// Bytes of the per-workgroup sums.
const SUMS_BYTES: u64 = (GRID * GRID) as u64 * 8;

/// CIE Y (cd/m^2) per unit of spectral radiance at each of `wavelengths_nm`.
pub fn luminance_weights(wavelengths_nm: [f64; 3]) -> Result<[f64; 3], RenderError> {
    let colour = SpectrumToColor::new(&wavelengths_nm)?;
    Ok(std::array::from_fn(|w| colour.xyz_weights()[w][1]))
}

/// The CPU twin: `exp(mean ln L)` over the pixels brighter than [`FLOOR_CD_M2`] of an
/// image of spectral radiance at the wavelengths of `weights` ([`luminance_weights`]);
/// the floor when none is.
pub fn log_average_luminance(weights: [f64; 3], pixels: &[[f32; 4]]) -> f64 {
    let (sum, count) = pixels
        .iter()
        .map(|p| (0..3).map(|c| weights[c] * f64::from(p[c])).sum::<f64>())
        .filter(|&l| l > FLOOR_CD_M2)
        .fold((0.0, 0u64), |(s, n), l| (s + l.ln(), n + 1));
    mean_or_floor(sum, count as f64)
}

/// exp(sum / count), the log-average of `count` luminances whose logarithms add up to
/// `sum`, or the floor when no pixel was above it.
fn mean_or_floor(sum: f64, count: f64) -> f64 {
    if count == 0.0 {
        FLOOR_CD_M2
    } else {
        (sum / count).exp()
    }
}

/// Pipeline and buffers, made once.
#[derive(Debug)]
pub struct LuminancePass {
    pipeline: ComputePipeline,
    params: wgpu::Buffer,
    sums: wgpu::Buffer,
    read_back: wgpu::Buffer,
}

impl LuminancePass {
    /// The pipeline and buffers, with the weights of radiance at `wavelengths_nm`.
    pub fn new(gpu: &GpuContext, wavelengths_nm: [f64; 3]) -> Result<LuminancePass, RenderError> {
        let pipeline = ComputePipeline::new(
            gpu,
            "post/luminance.wgsl",
            "main",
            "luminance",
            &[
                uniform_entry(0, 16),
                texture_entry(1, wgpu::TextureViewDimension::D2),
                storage_buffer_entry(2, SUMS_BYTES as usize),
            ],
        )?;
        let params = uniform_buffer(&gpu.device, "luminance", 16);
        let [r, g, b] = luminance_weights(wavelengths_nm)?;
        let uniform = [r as f32, g as f32, b as f32, FLOOR_CD_M2 as f32];
        gpu.write_uniform(&params, &uniform);
        use wgpu::BufferUsages as U;
        Ok(LuminancePass {
            pipeline,
            params,
            sums: buffer(
                &gpu.device,
                "luminance sums",
                SUMS_BYTES,
                U::STORAGE | U::COPY_SRC,
            ),
            read_back: readable_buffer(&gpu.device, "luminance read-back", SUMS_BYTES),
        })
    }

    /// The log-average luminance (cd/m^2) of `hdr`, a texture of spectral radiance
    /// sampleable as float; waits for the GPU.
    pub fn measure(&self, gpu: &GpuContext, hdr: &wgpu::Texture) -> Result<f64, RenderError> {
        let view = hdr.create_view(&Default::default());
        let bind_group = self.pipeline.bind_group(
            gpu,
            &[
                self.params.as_entire_binding(),
                wgpu::BindingResource::TextureView(&view),
                self.sums.as_entire_binding(),
            ],
        );
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.pipeline.dispatch(
            &mut encoder,
            "luminance",
            &bind_group,
            [GRID, GRID, 1],
            None,
        );
        encoder.copy_buffer_to_buffer(&self.sums, 0, &self.read_back, 0, SUMS_BYTES);
        gpu.queue.submit([encoder.finish()]);
        let bytes = map_and_read(gpu, &self.read_back)?;
        let sums: Vec<[f32; 2]> = bytemuck::pod_collect_to_vec(&bytes);
        let (sum, count) = sums.iter().fold((0.0, 0.0), |(s, n), p| {
            (s + f64::from(p[0]), n + f64::from(p[1]))
        });
        Ok(mean_or_floor(sum, count))
    }
}
