//! Building blocks every pass shares: bind group layout entries, uniform buffers, and a
//! compute pipeline from an embedded shader, checked inside a validation scope so a
//! broken shader is an error naming it rather than a panic.

use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::shaders;

/// Side of the square workgroup of every shader that runs one invocation per texel
/// (`@workgroup_size(8, 8)`).
pub const WORKGROUP_SIDE: u32 = 8;

/// The workgroups that cover every texel of the 2D `texture`, one invocation each.
pub fn texel_groups(texture: &wgpu::Texture) -> [u32; 3] {
    [
        texture.width().div_ceil(WORKGROUP_SIDE),
        texture.height().div_ceil(WORKGROUP_SIDE),
        1,
    ]
}

/// A uniform buffer of `size` bytes visible to compute shaders.
pub fn uniform_entry(binding: u32, size: usize) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: wgpu::BufferSize::new(size as u64),
        },
        count: None,
    }
}

/// A float texture read with `textureLoad` (not filterable: `Rgba32Float` tables).
pub fn texture_entry(
    binding: u32,
    dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    float_texture_entry(binding, dimension, false)
}

/// A float texture, sampled through a filter if `filterable`.
pub fn float_texture_entry(
    binding: u32,
    dimension: wgpu::TextureViewDimension,
    filterable: bool,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable },
            view_dimension: dimension,
            multisampled: false,
        },
        count: None,
    }
}

/// A read-only storage buffer of at least `min_size` bytes.
pub fn read_only_storage_buffer_entry(binding: u32, min_size: usize) -> wgpu::BindGroupLayoutEntry {
    buffer_entry(binding, min_size, true)
}

/// A storage buffer of at least `min_size` bytes, read-only if `read_only`.
fn buffer_entry(binding: u32, min_size: usize, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: wgpu::BufferSize::new(min_size as u64),
        },
        count: None,
    }
}

/// A write-only storage texture of `format`.
pub fn storage_texture_entry(
    binding: u32,
    format: wgpu::TextureFormat,
    dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format,
            view_dimension: dimension,
        },
        count: None,
    }
}

/// A 2D texture of one mip level and sample.
pub fn texture_2d(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// A buffer of `size` bytes for `usage`, not mapped when made.
pub fn buffer(
    device: &wgpu::Device,
    label: &str,
    size: u64,
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage,
        mapped_at_creation: false,
    })
}

/// A uniform buffer of `size` bytes that the CPU writes.
pub fn uniform_buffer(device: &wgpu::Device, label: &str, size: usize) -> wgpu::Buffer {
    let usage = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
    buffer(device, label, size as u64, usage)
}

/// The module of the embedded shader `shader` (imports resolved), made inside the
/// caller's validation scope.
pub fn shader_module(device: &wgpu::Device, shader: &str) -> Result<wgpu::ShaderModule, GpuError> {
    let source = shaders::composed(shader)?;
    Ok(device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(shader),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    }))
}

/// A bind group layout of `entries`, and a pipeline layout whose one group it is.
pub fn one_group_layout(
    device: &wgpu::Device,
    label: &str,
    entries: &[wgpu::BindGroupLayoutEntry],
) -> (wgpu::BindGroupLayout, wgpu::PipelineLayout) {
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries,
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    (layout, pipeline_layout)
}

/// `entry` (made for compute passes) seen by the `visibility` stages of a render pass.
pub fn in_stage(
    visibility: wgpu::ShaderStages,
    entry: wgpu::BindGroupLayoutEntry,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        visibility,
        ..entry
    }
}

/// A bind group of `layout` with `resources` bound in order from binding 0.
pub fn ordered_bind_group(
    device: &wgpu::Device,
    label: Option<&str>,
    layout: &wgpu::BindGroupLayout,
    resources: &[wgpu::BindingResource<'_>],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
        .iter()
        .enumerate()
        .map(|(binding, resource)| wgpu::BindGroupEntry {
            binding: binding as u32,
            resource: resource.clone(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label,
        layout,
        entries: &entries,
    })
}

/// A compute pipeline and its one bind group layout.
#[derive(Debug)]
pub struct ComputePipeline {
    pub pipeline: wgpu::ComputePipeline,
    pub layout: wgpu::BindGroupLayout,
}

impl ComputePipeline {
    /// Compiles entry point `entry` of the embedded shader `shader` (imports resolved)
    /// with one bind group of `entries`; `label` names it in errors and GPU captures.
    pub fn new(
        gpu: &GpuContext,
        shader: &str,
        entry: &str,
        label: &'static str,
        entries: &[wgpu::BindGroupLayoutEntry],
    ) -> Result<ComputePipeline, GpuError> {
        ComputePipeline::with_constants(gpu, shader, entry, label, entries, &[])
    }

    /// As [`ComputePipeline::new`], with the shader's pipeline-overridable constants set
    /// to `constants` (name, value).
    pub fn with_constants(
        gpu: &GpuContext,
        shader: &str,
        entry: &str,
        label: &'static str,
        entries: &[wgpu::BindGroupLayoutEntry],
        constants: &[(&str, f64)],
    ) -> Result<ComputePipeline, GpuError> {
        let device = &gpu.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = shader_module(device, shader)?;
        let (layout, pipeline_layout) = one_group_layout(device, label, entries);
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                ..Default::default()
            },
            cache: None,
        });
        if let Some(source) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation {
                what: label,
                source,
            });
        }
        Ok(ComputePipeline { pipeline, layout })
    }

    /// A bind group of `resources`, bound in order from binding 0.
    pub fn bind_group(
        &self,
        gpu: &GpuContext,
        resources: &[wgpu::BindingResource<'_>],
    ) -> wgpu::BindGroup {
        ordered_bind_group(&gpu.device, None, &self.layout, resources)
    }

    /// A bind group of (binding, resource) pairs.
    pub fn bind_group_numbered(
        &self,
        gpu: &GpuContext,
        resources: &[(u32, wgpu::BindingResource<'_>)],
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
            .iter()
            .map(|(binding, resource)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: resource.clone(),
            })
            .collect();
        gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &self.layout,
            entries: &entries,
        })
    }

    /// Records one dispatch of `groups` workgroups with `bind_group`, timed by
    /// `timestamps` when given.
    pub fn dispatch(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        label: &str,
        bind_group: &wgpu::BindGroup,
        groups: [u32; 3],
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(label),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(groups[0], groups[1], groups[2]);
    }

    /// Records one dispatch whose workgroup counts the GPU reads from `indirect` (three
    /// u32 at offset 0), timed by `timestamps` when given.
    pub fn dispatch_indirect(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        label: &str,
        bind_group: &wgpu::BindGroup,
        indirect: &wgpu::Buffer,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(label),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups_indirect(indirect, 0);
    }
}

/// `timestamps` split over two passes recorded one after the other: the first writes the
/// beginning, the second the end, so the two are timed as one.
pub fn split_timestamps(
    timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
) -> (
    Option<wgpu::ComputePassTimestampWrites<'_>>,
    Option<wgpu::ComputePassTimestampWrites<'_>>,
) {
    match timestamps {
        Some(t) => (
            Some(wgpu::ComputePassTimestampWrites {
                query_set: t.query_set,
                beginning_of_pass_write_index: t.beginning_of_pass_write_index,
                end_of_pass_write_index: None,
            }),
            Some(wgpu::ComputePassTimestampWrites {
                query_set: t.query_set,
                beginning_of_pass_write_index: None,
                end_of_pass_write_index: t.end_of_pass_write_index,
            }),
        ),
        None => (None, None),
    }
}

/// A model's pixel pass in two variants: one that reads the frame's surface buffer and
/// one with `common/surface.wgsl`'s `SURFACE` constant false, which compiles every branch
/// of the surface out. A software rasteriser (lavapipe) runs both sides of every branch,
/// even one that no pixel takes, so a frame without a surface would otherwise pay for it.
#[derive(Debug)]
pub struct PixelPipeline {
    with_sea: ComputePipeline,
    with_surface: ComputePipeline,
    without_surface: ComputePipeline,
}

impl PixelPipeline {
    /// The three variants of entry point `entry` of `shader` (see
    /// [`ComputePipeline::new`]): with a surface and the sea, with a surface on land only
    /// (`SEA` false: the sea's mirror ray compiled out, as a software rasteriser pays for
    /// every branch), and without a surface; the shader's other pipeline-overridable
    /// constants set to `constants` (name, value) in all.
    pub fn with_constants(
        gpu: &GpuContext,
        shader: &str,
        entry: &str,
        label: &'static str,
        entries: &[wgpu::BindGroupLayoutEntry],
        constants: &[(&str, f64)],
    ) -> Result<PixelPipeline, GpuError> {
        let variant = |surface: f64, sea: f64| {
            let mut all = vec![("SURFACE", surface), ("SEA", sea)];
            all.extend_from_slice(constants);
            ComputePipeline::with_constants(gpu, shader, entry, label, entries, &all)
        };
        Ok(PixelPipeline {
            with_sea: variant(1.0, 1.0)?,
            with_surface: variant(1.0, 0.0)?,
            without_surface: variant(0.0, 0.0)?,
        })
    }

    /// The variant for a frame with (`surface`) or without a surface, and with sea
    /// (`sea`, only with a surface) or without.
    pub fn variant(&self, surface: bool, sea: bool) -> &ComputePipeline {
        match (surface, sea) {
            (true, true) => &self.with_sea,
            (true, false) => &self.with_surface,
            (false, _) => &self.without_surface,
        }
    }
}

/// A read-write storage buffer of at least `min_size` bytes.
pub fn storage_buffer_entry(binding: u32, min_size: usize) -> wgpu::BindGroupLayoutEntry {
    buffer_entry(binding, min_size, false)
}
