//! A table's size checked against the device before its texture is made: every side
//! within the device's largest texture side and the texels within a memory budget, so
//! that table settings too large for the GPU are errors naming the settings rather than
//! a validation panic or a failed allocation.

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;

/// The most GPU memory one table texture may take: 1 GiB.
pub const GPU_TABLE_BUDGET_BYTES: u64 = 1 << 30;

/// Bytes of one texel of every table texture (`Rgba32Float`).
const TEXEL_BYTES: u64 = 16;

/// The extent of `table` (e.g. "hillaire aerial radiance") of `size` texels, made from
/// `settings` (e.g. "ap_width x ap_height x ap_slices"), or why this GPU cannot hold it.
pub fn table_extent(
    gpu: &GpuContext,
    table: &str,
    settings: &str,
    dimension: wgpu::TextureDimension,
    (width, height, depth): (usize, usize, usize),
) -> Result<wgpu::Extent3d, RenderError> {
    let limits = gpu.device.limits();
    let largest = match dimension {
        wgpu::TextureDimension::D1 => limits.max_texture_dimension_1d,
        wgpu::TextureDimension::D2 => limits.max_texture_dimension_2d,
        wgpu::TextureDimension::D3 => limits.max_texture_dimension_3d,
    };
    let depth_limit = match dimension {
        wgpu::TextureDimension::D3 => largest,
        _ => limits.max_texture_array_layers,
    };
    let refuse = |why: String| {
        RenderError::Unsupported(format!(
            "{table} of {width} x {height} x {depth} texels ({settings}): {why}"
        ))
    };
    let side = |n: usize, most: u32| u32::try_from(n).ok().filter(|&n| (1..=most).contains(&n));
    let (Some(w), Some(h), Some(d)) = (
        side(width, largest),
        side(height, largest),
        side(depth, depth_limit),
    ) else {
        return Err(refuse(format!(
            "a side is over this GPU's largest, {largest} texels"
        )));
    };
    let bytes = u64::from(w) * u64::from(h) * u64::from(d) * TEXEL_BYTES;
    if bytes > GPU_TABLE_BUDGET_BYTES {
        return Err(refuse(format!(
            "{bytes} bytes, over the GPU table budget of {GPU_TABLE_BUDGET_BYTES} bytes (1 GiB)"
        )));
    }
    Ok(wgpu::Extent3d {
        width: w,
        height: h,
        depth_or_array_layers: d,
    })
}
