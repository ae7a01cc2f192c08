//! The bindings every bruneton shader shares (`sky/bruneton/bindings.wgsl`): atmosphere,
//! frame, parameters, the columns table, the store, the transmittance table and the
//! density table's texture; each step's own resources follow from
//! [`FIRST_STEP_BINDING`] on.

use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::pipeline::{ComputePipeline, storage_buffer_entry, texture_entry, uniform_entry};
use crate::sky::bruneton::store_chunks::STORE_BINDINGS as STORE_CHUNK_BINDINGS;
use crate::sky::bruneton::tables::Tables;
use crate::sky::bruneton::uniform::BrunetonUniform;
use crate::sky::model_pass::PassIo;

/// `AtmosphereUniform` (`common/atmosphere_params.wgsl`).
const ATMOSPHERE_BINDING: u32 = 0;
/// `FrameUniform` (`common/frame_params.wgsl`).
const FRAME_BINDING: u32 = 1;
/// [`BrunetonUniform`].
const PARAMS_BINDING: u32 = 2;
/// The columns table T(r, mu) (`sky/transmittance_table.wgsl`, `columns`).
pub const COLUMNS_BINDING: u32 = 3;
/// The store's chunks (`store.rs`, `store_chunks.rs`): `store0` to `store3`.
const STORE_BINDINGS: [u32; STORE_CHUNK_BINDINGS] = [4, 13, 14, 15];
/// The transmittance table.
const TRANSMITTANCE_BINDING: u32 = 5;
/// The density table's texture.
const DENSITY_BINDING: u32 = 12;
/// The first binding of a step's own resources.
pub const FIRST_STEP_BINDING: u32 = 6;

/// The layout entries of the shared bindings, with each chunk of the store at least
/// `store_bytes`.
pub fn shared_entries(store_bytes: usize) -> Vec<wgpu::BindGroupLayoutEntry> {
    use wgpu::TextureViewDimension::{D1, D2};
    let mut entries = vec![
        texture_entry(DENSITY_BINDING, D1),
        uniform_entry(ATMOSPHERE_BINDING, size_of::<AtmosphereUniform>()),
        uniform_entry(FRAME_BINDING, size_of::<FrameUniform>()),
        uniform_entry(PARAMS_BINDING, size_of::<BrunetonUniform>()),
        texture_entry(COLUMNS_BINDING, D2),
        texture_entry(TRANSMITTANCE_BINDING, D2),
    ];
    entries.extend(
        STORE_BINDINGS
            .iter()
            .map(|&binding| storage_buffer_entry(binding, store_bytes)),
    );
    entries
}

/// The bind group of `pipeline`: the shared bindings with `params`, then `extra` from
/// [`FIRST_STEP_BINDING`] on, and `more` (binding, resource) pairs elsewhere.
pub fn bind_group(
    gpu: &GpuContext,
    io: &PassIo<'_>,
    tables: &Tables,
    pipeline: &ComputePipeline,
    params: &wgpu::Buffer,
    extra: &[wgpu::BindingResource<'_>],
    more: &[(u32, wgpu::BindingResource<'_>)],
) -> wgpu::BindGroup {
    let columns = tables.columns.texture().create_view(&Default::default());
    let transmittance = tables
        .transmittance
        .texture()
        .create_view(&Default::default());
    let density = tables.density.create_view(&Default::default());
    let mut resources = vec![
        (ATMOSPHERE_BINDING, io.atmosphere.as_entire_binding()),
        (FRAME_BINDING, io.frame.as_entire_binding()),
        (PARAMS_BINDING, params.as_entire_binding()),
        (
            COLUMNS_BINDING,
            wgpu::BindingResource::TextureView(&columns),
        ),
        (
            TRANSMITTANCE_BINDING,
            wgpu::BindingResource::TextureView(&transmittance),
        ),
        (
            DENSITY_BINDING,
            wgpu::BindingResource::TextureView(&density),
        ),
    ];
    let chunks = tables.chunks.ranges().map(|(offset, size)| {
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: &tables.store,
            offset,
            size: Some(size),
        })
    });
    resources.extend(STORE_BINDINGS.into_iter().zip(chunks));
    resources.extend((FIRST_STEP_BINDING..).zip(extra.iter().cloned()));
    resources.extend_from_slice(more);
    pipeline.bind_group_numbered(gpu, &resources)
}
