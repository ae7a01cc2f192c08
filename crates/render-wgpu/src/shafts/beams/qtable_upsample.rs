//! The q(u, v) table's walk at reduced resolution brought to the frame's size
//! (`shaders/shafts/beams/qtable_upsample.wgsl`; the setting `resolution_divisor` above
//! 1): `qtable_pass.rs` renders the planes at the reduced size first, then one triangle
//! over the frame interpolates the reduced walk where its four taps agree and marks the
//! pixels where they do not in a depth image, and each light's rectangle of the walk,
//! depth-tested against it, walks that light at the marked pixels alone, one light per
//! fragment as the walk does, each marked pixel's ray ended where it meets an occluder:
//! traced there, or, in a scene with glTF meshes, read from the frame's own ray ends
//! traced for every pixel first. (One pass that chose per pixel took most of the walk's
//! time on lavapipe even where it chose no walk at all: the walk's code in a fragment
//! costs there whether it runs or not.) CPU twin: atmosphere-core's
//! `beams/methods/qtable2002/upsample.rs`.

use atmosphere_core::beams::methods::qtable2002::upsample::Upsample;

use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{in_stage, shader_module, texture_entry};
use crate::shafts::beams::blended_planes::{BlendedPlanes, PipelineStages, additive_pipeline};
use crate::shafts::beams::qtable_walk::WalkedPlanes;

/// The reduced walk of a frame and what the pixels walked at full size need.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuUpsample {
    /// The reduced image's width and height, px.
    pub reduced: (u32, u32),
    /// Every light's walk and the sample counts of its intervals.
    pub walked: WalkedPlanes,
}

impl GpuUpsample {
    /// The reduced walk of `upsample` for a `width` x `height` frame of `walked`.
    pub fn new(upsample: &Upsample, (width, height): (u32, u32), walked: WalkedPlanes) -> Self {
        GpuUpsample {
            reduced: upsample.reduced_size(width, height),
            walked,
        }
    }
}

/// The depth image's format: 1 where a pixel is to be walked, 0 where interpolated.
pub const MARK_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The upsample's two pipelines: `interpolate` (the entry points `vertex` and
/// `fragment`), which writes the interpolated pixels and marks the others, and `walk`
/// (`walk_vertex`, `walk_fragment`: the walk's light rectangles), drawn at depth 0.5
/// where the mark is 1, with the same layouts.
#[derive(Debug)]
pub struct UpsamplePipelines {
    pub interpolate: BlendedPlanes,
    pub walk: wgpu::RenderPipeline,
}

impl UpsamplePipelines {
    /// Group 1 laid out by `table_entries` (the uniform, ray ends, table and sample
    /// counts of the walk), the reduced radiance (binding 4) and the reduced ray ends
    /// (binding 5); `interpolate` draws one
    /// triangle without vertex buffers, `walk` the walk's instances of `walk_buffers`.
    pub fn new(
        gpu: &GpuContext,
        table_entries: &[wgpu::BindGroupLayoutEntry],
        walk_buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
    ) -> Result<UpsamplePipelines, RenderError> {
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let mut entries = table_entries.to_vec();
        for binding in [4, 5] {
            entries.push(in_stage(
                fragment,
                texture_entry(binding, wgpu::TextureViewDimension::D2),
            ));
        }
        let shader = "shafts/beams/qtable_upsample.wgsl";
        let depth = |write: bool, compare: wgpu::CompareFunction| wgpu::DepthStencilState {
            format: MARK_FORMAT,
            depth_write_enabled: Some(write),
            depth_compare: Some(compare),
            stencil: Default::default(),
            bias: Default::default(),
        };
        let label = "beams qtable2002 upsample";
        let interpolate = BlendedPlanes::with_depth(
            gpu,
            shader,
            label,
            &entries,
            &[],
            Some(depth(true, wgpu::CompareFunction::Always)),
        )?;
        let device = &gpu.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[
                Some(&interpolate.scene_layout),
                Some(&interpolate.own_layout),
            ],
            immediate_size: 0,
        });
        let module = shader_module(device, shader)?;
        let stages = PipelineStages {
            module: &module,
            vertex: "walk_vertex",
            fragment: "walk_fragment",
            buffers: walk_buffers,
            depth: Some(depth(false, wgpu::CompareFunction::Less)),
        };
        let walk = additive_pipeline(device, label, &layout, &stages);
        if let Some(source) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation {
                what: label,
                source,
            }
            .into());
        }
        Ok(UpsamplePipelines { interpolate, walk })
    }
}
