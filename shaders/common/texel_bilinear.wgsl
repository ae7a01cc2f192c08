// Library: the bilinear read of a 2D table by hand, four texel loads (Rgba32Float need
// not be filterable). CPU twin: the bilinear lookups of atmosphere-core's tables
// (`optics/transmittance_table.rs`, `models/hillaire/multiple_scattering.rs`): the cell
// below the position, clamped to the last full cell. No paper: numerics.

// Bilinear interpolation (rgb) of `table` at texel coordinates `f` (texel centres on
// whole numbers, already within the table).
fn texel_bilinear(table: texture_2d<f32>, f: vec2<f32>) -> vec3<f32> {
    let size = textureDimensions(table);
    let i0 = min(vec2<u32>(f), size - 2u);
    let a = f - vec2<f32>(i0);
    let c00 = textureLoad(table, i0, 0).xyz;
    let c10 = textureLoad(table, i0 + vec2<u32>(1u, 0u), 0).xyz;
    let c01 = textureLoad(table, i0 + vec2<u32>(0u, 1u), 0).xyz;
    let c11 = textureLoad(table, i0 + vec2<u32>(1u, 1u), 0).xyz;
    let low = c00 + a.x * (c10 - c00);
    let high = c01 + a.x * (c11 - c01);
    return low + a.y * (high - low);
}
