//! The shaders' workgroup sizes, and the slices an order's Delta S is dispatched in.

/// Invocations of the flat shaders' workgroups (one invocation per texel).
pub const FLAT: u32 = 64;
/// Workgroups along x of a flat dispatch over the texels of S; more go along y, so that
/// a table of any size the device holds stays within the dispatch's per-dimension limit
/// (`FLAT_ROW_INVOCATIONS` = this times [`FLAT`] in `sky/bruneton/parameterization.wgsl`).
pub const FLAT_ROW_GROUPS: u32 = 1024;
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

/// The workgroups of a flat dispatch over `texels` texels (x, y, z): rows of
/// [`FLAT_ROW_GROUPS`], the invocation of texel `x + y FLAT_ROW_GROUPS FLAT`.
pub fn flat_groups(texels: u32) -> [u32; 3] {
    let groups = texels.div_ceil(FLAT);
    if groups <= FLAT_ROW_GROUPS {
        [groups, 1, 1]
    } else {
        [FLAT_ROW_GROUPS, groups.div_ceil(FLAT_ROW_GROUPS), 1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_dispatches_cover_every_texel_within_one_row_of_groups_along_x() {
        assert_eq!(flat_groups(100), [2, 1, 1]);
        let texels = 32 * 128 * 64 * 16;
        let [x, y, _] = flat_groups(texels);
        assert_eq!(x, FLAT_ROW_GROUPS);
        assert!(x * y * FLAT >= texels && (x * (y - 1)) * FLAT < texels);
    }
}
