//! The dispatch list of the loop over orders (Bruneton and Neyret 2008, Algorithm 4.1):
//! per order Delta J (moments per (r, mu_s), then every texel), Delta E, Delta S in
//! slices, their sums, the GPU's decision whether the order is added and whether the
//! loop goes on (`sky/bruneton/orders.wgsl`), S += Delta S and E += Delta E. Every order
//! up to the limit is recorded; those after the loop's end dispatch no workgroups (the
//! indirect dispatch sizes are written by the GPU), so nothing is read back.

use crate::gpu::context::GpuContext;
use crate::gpu::pipeline::ComputePipeline;
use crate::sky::bruneton::bindings::bind_group;
use crate::sky::bruneton::order_state::IndirectStep;
use crate::sky::bruneton::pipelines::Pipelines;
use crate::sky::bruneton::progressive::{Recording, Share};
use crate::sky::bruneton::store::{SUM_GROUPS, StoreTable};
use crate::sky::bruneton::tables::Tables;
use crate::sky::model_pass::PassIo;

/// A dispatch's size: workgroups along x, or the indirect arguments of a step in the
/// loop's state.
#[derive(Debug)]
enum DispatchSize<'a> {
    Direct(u32),
    Indirect(&'a wgpu::Buffer, IndirectStep),
}

/// One dispatch of the loop over orders.
#[derive(Debug)]
pub struct OrderDispatch<'a> {
    /// The step's name (`moments`, `scattering`, `decide`...).
    pub name: &'static str,
    /// The share of a progressive build it belongs to.
    pub share: Share,
    pipeline: &'a wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    size: DispatchSize<'a>,
}

impl<'a> OrderDispatch<'a> {
    fn new(
        name: &'static str,
        share: Share,
        pipeline: &'a ComputePipeline,
        bind_group: wgpu::BindGroup,
        size: DispatchSize<'a>,
    ) -> Self {
        OrderDispatch {
            name,
            share,
            pipeline: &pipeline.pipeline,
            bind_group,
            size,
        }
    }

    /// Records the dispatch into `pass`.
    pub fn record(&self, pass: &mut wgpu::ComputePass<'_>) {
        pass.set_pipeline(self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        match self.size {
            DispatchSize::Direct(x) => pass.dispatch_workgroups(x, 1, 1),
            DispatchSize::Indirect(buffer, step) => {
                pass.dispatch_workgroups_indirect(buffer, step.args_offset())
            }
        }
    }
}

/// The dispatches of the loop over orders, in order: each with its step's name and the
/// share of a progressive build it belongs to (order 1 for the sums of single
/// scattering). The loop starts by clearing S's multiple part and E ([`clear_orders`]).
pub fn order_dispatches<'a>(
    gpu: &GpuContext,
    io: &PassIo<'_>,
    tables: &'a Tables,
    p: &'a Pipelines,
) -> Vec<OrderDispatch<'a>> {
    let state = [tables.state.as_entire_binding()];
    let delta_j = tables.delta_j.create_view(&Default::default());
    let slice = |k: u32| {
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: &tables.slice_starts,
            offset: tables.slice_stride * u64::from(k),
            size: wgpu::BufferSize::new(16),
        })
    };
    let with_delta_j = [wgpu::BindingResource::TextureView(&delta_j)];
    let bind = |pipeline, params, extra: &[wgpu::BindingResource<'_>]| {
        bind_group(gpu, io, tables, pipeline, params, extra, &[])
    };
    // Bind groups of order 2 (`params_first`) and of later orders.
    let both = |pipeline, extra: &[wgpu::BindingResource<'_>]| {
        [
            bind(pipeline, &tables.params_first, extra),
            bind(pipeline, &tables.params, extra),
        ]
    };
    let first_steps = [
        (
            "moments",
            IndirectStep::Moments,
            &p.moments,
            both(&p.moments, &[]),
        ),
        (
            "scattering_density",
            IndirectStep::ScatteringDensity,
            &p.scattering_density,
            both(&p.scattering_density, &with_delta_j),
        ),
        (
            "irradiance",
            IndirectStep::Irradiance,
            &p.irradiance,
            both(&p.irradiance, &[]),
        ),
    ];
    let slice_groups: Vec<_> = (0..tables.slices)
        .map(|k| both(&p.scattering, &[with_delta_j[0].clone(), slice(k)]))
        .collect();
    // The state is bound to `decide` only: the other steps are dispatched from it.
    let sum_single = bind(&p.sum_single, &tables.params, &[]);
    let sum_order = bind(&p.sum_order, &tables.params, &[]);
    let decide = bind(&p.decide, &tables.params, &state);
    let accumulate = bind(&p.accumulate, &tables.params, &[]);
    let dispatch = OrderDispatch::new;
    let indirect = |step| DispatchSize::Indirect(&tables.state, step);
    let single = Share::FIRST;
    let mut out = vec![
        dispatch(
            "sum_single",
            single,
            &p.sum_single,
            sum_single,
            DispatchSize::Direct(SUM_GROUPS),
        ),
        dispatch(
            "decide",
            single,
            &p.decide,
            decide.clone(),
            DispatchSize::Direct(1),
        ),
    ];
    for order in 2..=tables.max_orders {
        let later = usize::from(order > 2);
        let part = |part| Share { order, part };
        for (name, step, pipeline, groups) in &first_steps {
            out.push(dispatch(
                name,
                part(0),
                pipeline,
                groups[later].clone(),
                indirect(*step),
            ));
        }
        for (k, groups) in (1..).zip(&slice_groups) {
            out.push(dispatch(
                "scattering",
                part(k),
                &p.scattering,
                groups[later].clone(),
                indirect(IndirectStep::Scattering),
            ));
        }
        let last = part(tables.slices);
        out.push(dispatch(
            "sum_order",
            last,
            &p.sum_order,
            sum_order.clone(),
            indirect(IndirectStep::SumOrder),
        ));
        out.push(dispatch(
            "decide",
            last,
            &p.decide,
            decide.clone(),
            DispatchSize::Direct(1),
        ));
        out.push(dispatch(
            "accumulate",
            last,
            &p.accumulate,
            accumulate.clone(),
            indirect(IndirectStep::Accumulate),
        ));
    }
    out
}

/// Clears S's multiple part and E, where the loop over orders adds its orders.
pub fn clear_orders(tables: &Tables, encoder: &mut wgpu::CommandEncoder) {
    for table in [StoreTable::Multiple, StoreTable::Irradiance] {
        let (offset, size) = tables.layout.range(table);
        encoder.clear_buffer(&tables.store, offset, Some(size));
    }
}

/// Records the loop over orders into one compute pass: all of it, or the share of this
/// progressive frame.
pub fn encode_orders(
    gpu: &GpuContext,
    io: &PassIo<'_>,
    tables: &Tables,
    pipelines: &Pipelines,
    recording: Recording,
    encoder: &mut wgpu::CommandEncoder,
    timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
) {
    if recording.starts() {
        clear_orders(tables, encoder);
    }
    let dispatches = order_dispatches(gpu, io, tables, pipelines);
    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some("bruneton scattering orders"),
        timestamp_writes: timestamps,
    });
    for d in &dispatches {
        if recording.includes(d.share) {
            d.record(&mut pass);
        }
    }
}
