//! The formats of the cloud spheres' images in frames: the cloud (rgb radiance, a
//! transmittance), which the layer's march writes too and the composite reads, and the
//! reduced rays' spans of the layer.

/// The format of the cloud images the spheres' passes read (the layer's) and write.
pub const CLOUD_IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The reduced rays' spans of the layer, (t0, t1) per ray.
pub const SPAN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Float;
