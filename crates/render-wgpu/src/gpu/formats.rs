//! The formats of the frame's targets, shared by every pass that writes or reads them.

/// Format of the HDR target: spectral radiance (W m^-2 sr^-1 nm^-1) at 680, 550 and
/// 440 nm in rgb, a = 1.
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Format of the display target.
pub const LDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
