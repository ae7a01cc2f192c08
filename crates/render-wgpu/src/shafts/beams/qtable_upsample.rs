//! The q(u, v) table's walk at reduced resolution brought to the frame's size
//! (`shaders/shafts/beams/qtable_upsample.wgsl`; the setting `resolution_divisor` above
//! 1): `qtable_pass.rs` renders the planes at the reduced size first, then one triangle
//! over the frame interpolates the reduced walk where its four taps agree and marks the
//! pixels where they do not in a depth image, and a second triangle, depth-tested
//! against it, walks every light at the marked pixels alone. (One pass that chose per
//! pixel took most of the walk's time on lavapipe even where it chose no walk at all:
//! the walk's code in a fragment costs there whether it runs or not.) CPU twin:
//! atmosphere-core's `beams/methods/qtable2002/upsample.rs`.

use atmosphere_core::beams::methods::qtable2002::upsample::Upsample;
use atmosphere_core::beams::scene::MAX_LIGHTS;
use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::{in_stage, texture_entry, uniform_entry};
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::shader_module;
use crate::shafts::beams::blended_planes::{BlendedPlanes, PipelineStages, additive_pipeline};
use crate::shafts::beams::qtable_walk::WalkedPlanes;

/// One light's walk as the upsample reads it (WGSL `WalkEntry`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct WalkEntry {
    /// Light, plane intervals, the index of its first interval's m_k, 0.
    pub walk: [u32; 4],
    /// The light's part of the screen, normalised device coordinates [x0, y0, x1, y1].
    pub bounds: [f32; 4],
    /// x: the light's first plane's depth along the view, m.
    pub first_depth_m: [f32; 4],
}

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

    /// The lights' walks as the uniform holds them: one per light with planes, then
    /// zeroed walks (which visit nothing) up to [`MAX_LIGHTS`].
    pub fn entries(&self) -> [WalkEntry; MAX_LIGHTS] {
        let mut entries = [WalkEntry::default(); MAX_LIGHTS];
        for (entry, l) in entries.iter_mut().zip(&self.walked.lights) {
            *entry = WalkEntry {
                walk: l.walk,
                bounds: l.bounds,
                first_depth_m: [l.first_depth_m, 0.0, 0.0, 0.0],
            };
        }
        entries
    }

    /// The walks uploaded (the scene's eight storage buffers are as many as a fragment
    /// stage may read, so the walks are a uniform).
    pub fn walks_buffer(&self, gpu: &GpuContext) -> wgpu::Buffer {
        gpu.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("beams qtable2002 walks"),
                contents: bytemuck::cast_slice(&self.entries()),
                usage: wgpu::BufferUsages::UNIFORM,
            })
    }
}

/// The depth image's format: 1 where a pixel is to be walked, 0 where interpolated.
pub const MARK_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The upsample's two pipelines: `interpolate` (the entry points `vertex` and
/// `fragment`), which writes the interpolated pixels and marks the others, and `walk`
/// (`walk_fragment`), drawn at depth 0.5 where the mark is 1, with the same layouts.
#[derive(Debug)]
pub struct UpsamplePipelines {
    pub interpolate: BlendedPlanes,
    pub walk: wgpu::RenderPipeline,
}

impl UpsamplePipelines {
    /// Group 1 laid out by `table_entries` (the uniform, ray ends, table and sample
    /// counts of the walk) and the reduced radiance (binding 4) and walks (binding 5);
    /// one triangle, no vertex buffer.
    pub fn new(
        gpu: &GpuContext,
        table_entries: &[wgpu::BindGroupLayoutEntry],
    ) -> Result<UpsamplePipelines, RenderError> {
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let mut entries = table_entries.to_vec();
        entries.push(in_stage(
            fragment,
            texture_entry(4, wgpu::TextureViewDimension::D2),
        ));
        let walks = size_of::<WalkEntry>() * MAX_LIGHTS;
        entries.push(in_stage(fragment, uniform_entry(5, walks)));
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
            fragment: "walk_fragment",
            buffers: &[],
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
