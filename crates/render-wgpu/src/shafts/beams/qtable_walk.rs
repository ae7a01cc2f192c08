//! The planes and sub-planes of Dobashi et al. 2002 section 4.2 walked per pixel, the
//! default way `qtable_pass.rs` draws them (`shaders/shafts/beams/qtable_walk.wgsl`):
//! one instance per light over the part of the screen its bounding volume projects to,
//! each fragment summing the light's plane intervals and their m_k samples where its ray
//! is in the beam. The terms are those of the planes drawn one by one; the intervals a
//! ray does not cross in the beam add nothing there and are not visited.

use atmosphere_core::beams::methods::qtable2002::Qtable2002;
use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;

/// The widest row of the sample-count texture.
const SAMPLES_ROW: usize = 4096;

/// One light's walk: an instance's vertex attributes (WGSL `qtable_walk.wgsl`'s
/// `vertex`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LightWalk {
    /// Light, plane intervals, the index of its first interval's m_k in the sample
    /// counts, and the f_l one sample stands for on a ray counting its own sub-planes
    /// (`LightPlanes::sample_unit`, f32 bits; 0 where rays take the centre ray's m_k).
    pub walk: [u32; 4],
    /// The light's first plane's depth along the view, m.
    pub first_depth_m: f32,
    /// The part of the screen drawn, normalised device coordinates [x0, y0, x1, y1]:
    /// the light's bounding volume (`Qtable2002::screen_bounds`).
    pub bounds: [f32; 4],
}

/// Every light's walk and the sample counts m_k of its intervals, the lights one after
/// another.
#[derive(Clone, Debug, PartialEq)]
pub struct WalkedPlanes {
    pub lights: Vec<LightWalk>,
    pub samples: Vec<u32>,
}

impl WalkedPlanes {
    /// The walks of `method`'s lights (those with planes).
    pub fn new(method: &Qtable2002) -> WalkedPlanes {
        let mut lights = Vec::new();
        let mut samples = Vec::new();
        for (l, planes) in method.planes().iter().enumerate() {
            if planes.samples.is_empty() {
                continue;
            }
            lights.push(LightWalk {
                walk: [
                    l as u32,
                    planes.samples.len() as u32,
                    samples.len() as u32,
                    method
                        .subplanes_per_ray()
                        .map_or(0.0, |rule| planes.sample_unit(&rule) as f32)
                        .to_bits(),
                ],
                first_depth_m: planes.first_depth_m as f32,
                bounds: method.screen_bounds()[l].map(|v| v as f32),
            });
            samples.extend(planes.samples.iter().map(|&m| m as u32));
        }
        WalkedPlanes { lights, samples }
    }

    /// The sub-planes every pixel in a beam visits where its ray crosses their
    /// interval: m_k - 1 of each interval.
    pub fn subplane_count(&self) -> usize {
        self.samples.iter().map(|&m| m as usize - 1).sum()
    }

    /// The sample counts as an `R32Uint` texture, rows of at most 4096 (one texel where
    /// there are none, as a binding needs a texture); an error where the device cannot
    /// hold it.
    pub fn texture(&self, gpu: &GpuContext) -> Result<wgpu::Texture, RenderError> {
        let count = self.samples.len().max(1);
        let width = count.min(SAMPLES_ROW);
        let height = count.div_ceil(width);
        let side = gpu.device.limits().max_texture_dimension_2d as usize;
        if height > side {
            return Err(RenderError::BeamsTooLarge(format!(
                "qtable2002's {count} plane intervals need {height} rows of {width}; the \
                 device's largest texture side is {side} (raise delta_min_m or lower d0_m)"
            )));
        }
        let mut texels = self.samples.clone();
        texels.resize(width * height, 1);
        Ok(gpu.device.create_texture_with_data(
            &gpu.queue,
            &wgpu::TextureDescriptor {
                label: Some("beams qtable2002 interval samples"),
                size: wgpu::Extent3d {
                    width: width as u32,
                    height: height as u32,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::R32Uint,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            bytemuck::cast_slice(&texels),
        ))
    }
}

/// The layout entry of the sample counts (binding 3 of the walk's group 1).
pub fn samples_entry() -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding: 3,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Uint,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}
