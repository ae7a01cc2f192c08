//! How a pass reads its `Rgba32Float` tables: with the texture unit's linear filter where
//! the device filters that format (`Features::FLOAT32_FILTERABLE`), else texel by texel
//! with the interpolation written out in WGSL. One filtered read replaces the 4 texel
//! reads of a bilinear look-up, or the 8 of a trilinear one; a texel read costs about as
//! much as a filtered one on a software rasteriser, so table reads are most of a
//! table-driven pass's cost (docs/rendering.md).
//!
//! The two ways give the same interpolation (weights from the same coordinates), up to
//! the filter's precision: lavapipe computes the weights in f32; real GPUs quantise them
//! (8 fractional bits on NVIDIA), an error of at most 1/512 of the difference of two
//! neighbouring texels. A shader imports `shaders/common/table_sampling.wgsl`, whose
//! override constant [`TableSampling::CONSTANT`] is set at pipeline creation, so the
//! other way is compiled out, and whose sampler is at [`TableSampling::SAMPLER_BINDING`].

use crate::gpu::context::GpuContext;
use crate::gpu::pipeline::{ComputePipeline, float_texture_entry};

/// The sampler and the layout entries of a pass's table reads on one device.
#[derive(Clone, Debug)]
pub struct TableSampling {
    filtered: bool,
    sampler: wgpu::Sampler,
}

impl TableSampling {
    /// The WGSL override constant (bool) that says whether tables are read filtered.
    pub const CONSTANT: &'static str = "FILTERED_TABLES";

    /// The sampler's binding in `common/table_sampling.wgsl`.
    pub const SAMPLER_BINDING: u32 = 29;

    /// Filtered reads where `gpu`'s device has `FLOAT32_FILTERABLE`.
    pub fn new(gpu: &GpuContext) -> TableSampling {
        let filtered = TableSampling::device_filters(gpu);
        let filter = if filtered {
            wgpu::FilterMode::Linear
        } else {
            wgpu::FilterMode::Nearest
        };
        let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("tables"),
            mag_filter: filter,
            min_filter: filter,
            ..Default::default()
        });
        TableSampling { filtered, sampler }
    }

    /// Whether `gpu`'s device filters `Rgba32Float`, so that tables are read filtered.
    pub fn device_filters(gpu: &GpuContext) -> bool {
        gpu.device
            .features()
            .contains(wgpu::Features::FLOAT32_FILTERABLE)
    }

    /// The pipeline constant for [`TableSampling::CONSTANT`].
    pub fn constant(&self) -> (&'static str, f64) {
        (TableSampling::CONSTANT, f64::from(u8::from(self.filtered)))
    }

    /// A table texture that the shader may sample (filterable when filtered).
    pub fn texture_entry(
        &self,
        binding: u32,
        dimension: wgpu::TextureViewDimension,
    ) -> wgpu::BindGroupLayoutEntry {
        float_texture_entry(binding, dimension, self.filtered)
    }

    /// The sampler's entry (bound in both ways; unused by the texel reads).
    pub fn sampler_entry(&self) -> wgpu::BindGroupLayoutEntry {
        let kind = if self.filtered {
            wgpu::SamplerBindingType::Filtering
        } else {
            wgpu::SamplerBindingType::NonFiltering
        };
        wgpu::BindGroupLayoutEntry {
            binding: TableSampling::SAMPLER_BINDING,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Sampler(kind),
            count: None,
        }
    }

    /// The sampler at its binding, for a bind group.
    pub fn sampler_binding(&self) -> (u32, wgpu::BindingResource<'_>) {
        (
            TableSampling::SAMPLER_BINDING,
            wgpu::BindingResource::Sampler(&self.sampler),
        )
    }

    /// The bind group of a table build's `pipeline`: `resources` in order from binding 0,
    /// and the sampler (a model's pixel pass binds it through `pixel_pass`).
    pub fn bind_group(
        &self,
        gpu: &GpuContext,
        pipeline: &ComputePipeline,
        resources: &[wgpu::BindingResource<'_>],
    ) -> wgpu::BindGroup {
        let mut numbered: Vec<_> = (0..).zip(resources.iter().cloned()).collect();
        numbered.push(self.sampler_binding());
        pipeline.bind_group_numbered(gpu, &numbered)
    }
}
