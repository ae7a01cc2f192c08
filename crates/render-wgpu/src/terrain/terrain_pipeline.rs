//! The terrain shader's interface (`shaders/terrain/terrain.wgsl`): its uniforms as Rust
//! structs, its bind group layouts (group 0: the frame's parameters, the chunks' offsets
//! and the colour map; group 1: a chunk's normal map, `normal_texture.rs`) and the
//! render pipeline that writes the surface buffer with reversed depth.

use bytemuck::{Pod, Zeroable};

use crate::frame::surface_buffer::{ALBEDO_FORMAT, GEOMETRY_FORMAT};
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::{
    float_texture_entry, in_stage, read_only_storage_buffer_entry, shader_module, uniform_entry,
};
use crate::terrain::chunk_cache::Vertex;

/// The depth buffer's format: reversed depth, f32.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// WGSL `TerrainParams`, 128 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct TerrainUniform {
    pub right: [f32; 4],
    pub up: [f32; 4],
    pub forward: [f32; 4],
    /// x: the near plane, m; y: where a morph begins (`geomorph::MORPH_START`); z: pixels
    /// per radian (`LodView`), for the normal maps' fade.
    pub near: [f32; 4],
    /// rgb: the water's albedo (`sea_colour.rs`).
    pub sea_albedo: [f32; 4],
    /// The season's snow line (atmosphere-core's `geo::land_cover::SnowLine`): x its
    /// height at the thermal equator, m; y its fall to the pole, m; z the thermal
    /// equator's latitude, rad; w the band over which snow sets in, m.
    pub snow_line: [f32; 4],
    /// rgb: rock's albedo; w: the slope cosine where rock sets in.
    pub rock: [f32; 4],
    /// rgb: snow's albedo; w: the slope cosine past which all is rock.
    pub snow: [f32; 4],
}

/// WGSL `Chunk`, 48 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ChunkUniform {
    pub offset: [f32; 4],
    /// xyz: the origin, planet-centred, m; w: a normal-map texel's side, m
    /// (`normal_map::texel_size_m`).
    pub origin: [f32; 4],
    /// x, y: where the chunk's own and its coarser neighbours' morphs end, m
    /// (`geomorph::MorphEnds`); z: the coarser edges as bits (`1 << Edge`); w: cells.
    pub morph: [f32; 4],
}

/// The group 0 layout and the pipeline, with `normal_layout` as group 1.
pub fn terrain_pipeline(
    device: &wgpu::Device,
    normal_layout: &wgpu::BindGroupLayout,
) -> Result<(wgpu::BindGroupLayout, wgpu::RenderPipeline), GpuError> {
    let module = shader_module(device, "terrain/terrain.wgsl")?;
    use wgpu::ShaderStages as S;
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("terrain"),
        entries: &[
            in_stage(
                S::VERTEX | S::FRAGMENT,
                uniform_entry(0, size_of::<TerrainUniform>()),
            ),
            in_stage(
                S::VERTEX,
                read_only_storage_buffer_entry(1, size_of::<ChunkUniform>()),
            ),
            in_stage(
                S::FRAGMENT,
                float_texture_entry(2, wgpu::TextureViewDimension::D2, true),
            ),
            wgpu::BindGroupLayoutEntry {
                binding: 3,
                visibility: S::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
        ],
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("terrain"),
        bind_group_layouts: &[Some(&layout), Some(normal_layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("terrain"),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vertex_main"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![
                    0 => Float32x3, 1 => Float32x3, 2 => Float32, 3 => Float32x3, 4 => Float32,
                    5 => Float32x3
                ],
            })],
        },
        primitive: wgpu::PrimitiveState {
            front_face: wgpu::FrontFace::Ccw,
            cull_mode: Some(wgpu::Face::Back),
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Greater),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fragment_main"),
            compilation_options: Default::default(),
            targets: &[Some(GEOMETRY_FORMAT.into()), Some(ALBEDO_FORMAT.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    Ok((layout, pipeline))
}
