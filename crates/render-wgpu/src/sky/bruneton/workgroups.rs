//! The shaders' workgroup sizes, and the slices an order's Delta S is dispatched in.

/// Texels of a row of S (mu_s x nu) at most: the workgroup of the row shaders
/// (`sky/bruneton/single_scattering.wgsl`).
pub const ROW_TEXELS: usize = 256;
/// Invocations of the flat shaders' workgroups (one invocation per texel).
pub const FLAT: u32 = 64;
/// Texels of S per Delta S dispatch at most: an order's Delta S is dispatched in slices of
/// this many texels, so that a progressive build can spread it over frames (a multiple of
/// [`FLAT`]).
pub const SLICE_TEXELS: u32 = 65536;

/// The Delta S slices of an order over `texels` texels of S: how many, and the texels of
/// each (a multiple of [`FLAT`]; the last slice may hold fewer).
pub fn delta_s_slices(texels: u32) -> (u32, u32) {
    let slices = texels.div_ceil(SLICE_TEXELS);
    (slices, texels.div_ceil(slices).next_multiple_of(FLAT))
}
