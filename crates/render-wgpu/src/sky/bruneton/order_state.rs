//! The state of the loop over orders on the GPU (`OrderState` of
//! `sky/bruneton/orders.wgsl`): its sums and decisions, and the indirect dispatch sizes
//! it writes for the next order's steps.

use atmosphere_core::models::bruneton::parameterization::ScatteringSize;
use bytemuck::{Pod, Zeroable};

use crate::sky::bruneton::store::SUM_GROUPS;
use crate::sky::bruneton::workgroups::{FLAT, delta_s_slices, flat_groups};

/// The most orders the GPU loop records (`OrderState::shares` holds 64).
pub const MAX_ORDERS: u32 = 63;

/// The steps of an order dispatched from [`OrderState::args`], in its order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IndirectStep {
    Moments,
    ScatteringDensity,
    Irradiance,
    Scattering,
    SumOrder,
    Accumulate,
}

impl IndirectStep {
    /// The byte offset of the step's dispatch size in the state buffer.
    pub fn args_offset(self) -> u64 {
        (std::mem::offset_of!(OrderState, args) + 16 * self as usize) as u64
    }
}

/// WGSL `OrderState` (`sky/bruneton/orders.wgsl`), 496 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct OrderState {
    /// Per channel: the sum of all accepted orders' radiance.
    pub totals: [f32; 4],
    /// Per channel: the radiance of the last accepted order.
    pub previous_added: [f32; 4],
    /// The order the next decision judges (1: single scattering).
    pub order: u32,
    /// 1 while the loop goes on.
    pub running: u32,
    /// The highest order added to the tables.
    pub last_order: u32,
    /// 1 once an order of two or more has been added.
    pub has_previous: u32,
    /// Indirect dispatch sizes of the [`IndirectStep`]s (x, y, z, unused).
    pub args: [[u32; 4]; 6],
    /// The same when they run.
    pub full: [[u32; 4]; 6],
    /// The share of each order (index = order; -1: left out as diverging).
    pub shares: [f32; 64],
}

impl OrderState {
    /// The loop's state before its first decision for S of size `s` and E of
    /// `irradiance_texels`: dispatch sizes of every order's steps.
    pub fn initial(s: ScatteringSize, irradiance_texels: u32) -> OrderState {
        let n = s.texels() as u32;
        let e = irradiance_texels;
        let groups = |x: u32| [x, 1, 1, 0];
        let flat = |texels: u32| {
            let [x, y, z] = flat_groups(texels);
            [x, y, z, 0]
        };
        let full = [
            groups(((s.r * s.mu_s) as u32).div_ceil(FLAT)),
            flat(n),
            groups(e.div_ceil(FLAT)),
            groups(delta_s_slices(n).1 / FLAT),
            groups(SUM_GROUPS),
            flat(n.max(e)),
        ];
        OrderState {
            totals: [0.0; 4],
            previous_added: [0.0; 4],
            order: 1,
            running: 1,
            last_order: 1,
            has_previous: 0,
            args: full,
            full,
            shares: [0.0; 64],
        }
    }
}
