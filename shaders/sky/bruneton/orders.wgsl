// The bookkeeping of Algorithm 4.1 (Bruneton and Neyret 2008, section 4) on the GPU,
// without reading anything back: the GPU twin of the loop of `Builder::multiple_orders`
// (atmosphere-core `bruneton/precompute.rs`).
//
// `sum_single` and `sum_order` sum the radiance of all texels per channel (single
// scattering with its phase functions, or an order's Delta S) into 256 partial sums;
// `decide` (one workgroup) adds them up and judges the order as the CPU does: an order
// holding more light than the one before is left out and ends the loop (the iteration
// would diverge); otherwise it is added, and the loop ends once its share of all the
// table's radiance (worst channel) is below the threshold or the most orders are done.
// It then writes the indirect dispatch sizes of the next order's steps (zero once the
// loop has ended) and of `accumulate`, which adds Delta S to S and Delta E to E (zero
// when the order is left out). Every order up to the limit is recorded; those after the
// end dispatch no workgroups.

#import sky/bruneton/parameterization.wgsl
#import common/phase.wgsl

struct OrderState {
    // Per channel: the sum of all accepted orders' radiance, and of the last one.
    totals: vec4<f32>,
    previous_added: vec4<f32>,
    // The order the next `decide` judges (1: single scattering).
    order: u32,
    // 1 while the loop goes on.
    running: u32,
    // The highest order added to the tables.
    last_order: u32,
    // 1 once an order of two or more has been added.
    has_previous: u32,
    // Indirect dispatch sizes (x, y, z, unused): moments, scattering density,
    // irradiance, scattering, sum_order, accumulate.
    args: array<vec4<u32>, 6>,
    // The same when they run.
    full: array<vec4<u32>, 6>,
    // The share of each order (index = order; -1: left out as diverging).
    shares: array<f32, 64>,
}

@group(0) @binding(6) var<storage, read_write> state: OrderState;

// Workgroups of the partial sums, and their size.
const SUM_GROUPS: u32 = 256u;
const SUM_SIZE: u32 = 256u;

var<workgroup> partial: array<vec3<f32>, SUM_SIZE>;

// Sums `partial` over the workgroup into partial[0].
fn reduce(lid: u32) {
    for (var stride = SUM_SIZE / 2u; stride > 0u; stride /= 2u) {
        workgroupBarrier();
        if lid < stride {
            partial[lid] += partial[lid + stride];
        }
    }
    workgroupBarrier();
}

// The radiance of texel `index`: single scattering with its phase functions (`single`),
// else the order's Delta S.
fn texel_radiance(index: u32, single: bool) -> vec3<f32> {
    if !single {
        return store_read(bruneton.delta_s_offset + index).xyz;
    }
    let nu = texel_of_index(index).nu;
    var l = rayleigh_phase(nu) * store_read(bruneton.single_rayleigh_offset + index).xyz;
    if bruneton.mie_on == 1u {
        l += mie_phase(nu) * store_read(bruneton.single_mie_offset + index).xyz;
    }
    return l;
}

fn sum(group: u32, lid: u32, single: bool) {
    let n = bruneton.scattering_texels;
    var s = vec3<f32>(0.0);
    for (var i = group * SUM_SIZE + lid; i < n; i += SUM_GROUPS * SUM_SIZE) {
        s += texel_radiance(i, single);
    }
    partial[lid] = s;
    reduce(lid);
    if lid == 0u {
        store_write(bruneton.partials_offset + group, vec4<f32>(partial[0], 0.0));
    }
}

@compute @workgroup_size(256)
fn sum_single(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    sum(group.x, lid, true);
}

@compute @workgroup_size(256)
fn sum_order(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    sum(group.x, lid, false);
}

@compute @workgroup_size(256)
fn decide(@builtin(local_invocation_index) lid: u32) {
    partial[lid] = store_read(bruneton.partials_offset + lid).xyz;
    reduce(lid);
    if lid != 0u {
        return;
    }
    if state.running == 0u {
        state.args[5] = vec4<u32>(0u, 1u, 1u, 0u);
        return;
    }
    let added = partial[0];
    let order = state.order;
    state.order = order + 1u;
    if order == 1u {
        state.totals = vec4<f32>(added, 0.0);
        state.shares[1] = 1.0;
        return;
    }
    var accepted = true;
    if state.has_previous == 1u && any(added > state.previous_added.xyz) {
        accepted = false;
        state.running = 0u;
        state.shares[order] = -1.0;
    } else {
        state.previous_added = vec4<f32>(added, 0.0);
        state.has_previous = 1u;
        let totals = state.totals.xyz + added;
        state.totals = vec4<f32>(totals, 0.0);
        let shares = select(vec3<f32>(0.0), added / totals, totals > vec3<f32>(0.0));
        let share = max(shares.x, max(shares.y, shares.z));
        state.shares[order] = share;
        state.last_order = order;
        if share < bruneton.order_threshold {
            state.running = 0u;
        }
    }
    if order >= bruneton.max_orders {
        state.running = 0u;
    }
    for (var k = 0u; k < 5u; k++) {
        state.args[k] = select(vec4<u32>(0u, 1u, 1u, 0u), state.full[k], state.running == 1u);
    }
    state.args[5] = select(vec4<u32>(0u, 1u, 1u, 0u), state.full[5], accepted);
}

// S += Delta S and E += Delta E, one invocation per texel.
@compute @workgroup_size(64)
fn accumulate(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = flat_index(id);
    if index < bruneton.scattering_texels {
        let at = bruneton.multiple_offset + index;
        store_write(at, store_read(at) + store_read(bruneton.delta_s_offset + index));
    }
    if index < bruneton.irradiance_texels {
        let at = bruneton.irradiance_offset + index;
        store_write(at, store_read(at) + store_read(bruneton.delta_e_offset + index));
    }
}
