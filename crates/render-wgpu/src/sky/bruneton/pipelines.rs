//! The pipelines of every bruneton step, with their bind group layouts: the shared
//! bindings (`bindings.rs`) and each step's own.

use wgpu::TextureFormat::Rgba32Float;
use wgpu::TextureViewDimension::{D2, D3};

use crate::clouds::sun_map_texture::SunMapTexture;
use crate::frame::surface_buffer::SurfaceBuffer;
use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{
    ComputePipeline, PixelPipeline, storage_buffer_entry, storage_texture_entry, texture_entry,
    uniform_entry,
};
use crate::shafts::terrain::uniform::ShadowMapUniform;
use crate::sky::bruneton::bindings::{COLUMNS_BINDING, shared_entries};
use crate::sky::bruneton::order_state::OrderState;
use crate::sky::table_sampling::TableSampling;

/// The per-pixel pass's bindings of the terrain's shadow map for light shafts: its tops
/// and its parameters (`sky/bruneton/pixel.wgsl`).
pub const SHADOW_TOPS_BINDING: u32 = 16;
pub const SHADOW_MAP_BINDING: u32 = 17;

/// The pipelines of every step.
#[derive(Debug)]
pub struct Pipelines {
    pub density: ComputePipeline,
    pub single: ComputePipeline,
    pub moments: ComputePipeline,
    pub scattering_density: ComputePipeline,
    pub irradiance: ComputePipeline,
    pub scattering: ComputePipeline,
    pub sum_single: ComputePipeline,
    pub sum_order: ComputePipeline,
    pub decide: ComputePipeline,
    pub accumulate: ComputePipeline,
    pub texture: ComputePipeline,
    pub view_slice: ComputePipeline,
    /// The pass for a camera above the atmosphere, and for one inside (after the view
    /// slice).
    pub render: PixelPipeline,
    pub render_inside: PixelPipeline,
}

impl Pipelines {
    /// Compiles every step; the per-pixel pass reads its tables as `sampling` says.
    pub fn new(gpu: &GpuContext, sampling: &TableSampling) -> Result<Pipelines, GpuError> {
        let shared = shared_entries(16);
        let with = |own: &[wgpu::BindGroupLayoutEntry]| {
            let mut entries = shared.clone();
            entries.extend_from_slice(own);
            entries
        };
        let make = |shader, entry, label, entries: &[wgpu::BindGroupLayoutEntry]| {
            ComputePipeline::new(gpu, shader, entry, label, entries)
        };
        let order_entries = with(&[storage_buffer_entry(6, size_of::<OrderState>())]);
        let delta_j_out = with(&[storage_texture_entry(6, Rgba32Float, D3)]);
        let delta_j_in = with(&[texture_entry(6, D3), uniform_entry(7, 16)]);
        let texture_entries = with(&[
            storage_texture_entry(6, Rgba32Float, D3),
            storage_texture_entry(7, Rgba32Float, D3),
            storage_texture_entry(8, Rgba32Float, D3),
            storage_texture_entry(9, Rgba32Float, D2),
        ]);
        let scattering_textures = [
            texture_entry(6, D3),
            texture_entry(7, D3),
            texture_entry(8, D3),
        ];
        let view_slice_entries = with(
            &[
                &scattering_textures[..],
                &[storage_texture_entry(9, Rgba32Float, D2)],
            ]
            .concat(),
        );
        // The pass may sample the columns table, the view slice and E.
        let surface_entries = SurfaceBuffer::layout_entries();
        let sun_map_entries = SunMapTexture::layout_entries();
        let mut render_entries = with(
            &[
                &scattering_textures[..],
                &[
                    storage_texture_entry(9, HDR_FORMAT, D2),
                    surface_entries[0],
                    surface_entries[1],
                    sun_map_entries[0],
                    sun_map_entries[1],
                    sampling.texture_entry(10, D2),
                    sampling.texture_entry(11, D2),
                    sampling.sampler_entry(),
                    texture_entry(SHADOW_TOPS_BINDING, D2),
                    uniform_entry(SHADOW_MAP_BINDING, size_of::<ShadowMapUniform>()),
                ],
            ]
            .concat(),
        );
        for entry in &mut render_entries {
            if entry.binding == COLUMNS_BINDING {
                *entry = sampling.texture_entry(COLUMNS_BINDING, D2);
            }
        }
        let render = |entry| {
            PixelPipeline::with_constants(
                gpu,
                "sky/bruneton/pixel.wgsl",
                entry,
                "the bruneton pass",
                &render_entries,
                &[sampling.constant()],
            )
        };
        let orders = "sky/bruneton/orders.wgsl";
        Ok(Pipelines {
            density: make(
                "sky/bruneton/density.wgsl",
                "main",
                "bruneton density",
                &shared,
            )?,
            single: make(
                "sky/bruneton/single_scattering.wgsl",
                "main",
                "bruneton single scattering",
                &shared,
            )?,
            moments: make(
                "sky/bruneton/scattering_density.wgsl",
                "moments",
                "bruneton Delta J moments",
                &shared,
            )?,
            scattering_density: make(
                "sky/bruneton/scattering_density.wgsl",
                "main",
                "bruneton Delta J",
                &delta_j_out,
            )?,
            irradiance: make(
                "sky/bruneton/irradiance.wgsl",
                "main",
                "bruneton Delta E",
                &shared,
            )?,
            scattering: make(
                "sky/bruneton/scattering.wgsl",
                "main",
                "bruneton Delta S",
                &delta_j_in,
            )?,
            sum_single: make(orders, "sum_single", "bruneton sums", &shared)?,
            sum_order: make(orders, "sum_order", "bruneton sums", &shared)?,
            decide: make(orders, "decide", "bruneton order decision", &order_entries)?,
            accumulate: make(orders, "accumulate", "bruneton accumulation", &shared)?,
            texture: make(
                "sky/bruneton/scattering_texture.wgsl",
                "main",
                "bruneton scattering texture",
                &texture_entries,
            )?,
            view_slice: make(
                "sky/bruneton/view_slice.wgsl",
                "main",
                "bruneton view slice",
                &view_slice_entries,
            )?,
            render: render("main")?,
            render_inside: render("inside")?,
        })
    }
}
