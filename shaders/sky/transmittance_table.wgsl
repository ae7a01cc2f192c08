// Entry passes: the transmittance table T(r, mu) to the top of the atmosphere, `main`,
// and the table of columns, `columns` (render-wgpu's `sky/transmittance.rs`). CPU twin:
// atmosphere-core's `optics/transmittance_table.rs`, with the same texel centres, unit
// mapping and quadrature (64 equal panels of 5-point Gauss-Legendre), in f32. Paper: the
// transmittance table of Bruneton 2017 (its parameterization,
// `GetTransmittanceTextureUvFromRMu`), which Hillaire 2020 (section 5.1) shares; the
// columns are the table g_l of Nishita et al. 1993 (Dobashi, Yamamoto and Nishita 2002,
// section 5). Entry point `main`: rgb = transmittance in the three channels of the
// uniform, a = 1. Entry point `columns`: rgb = the columns of matter (Rayleigh, Mie,
// ozone) in metres, a = 1, as the CPU table stores them (read by
// `common/transmittance_lookup.wgsl`).

#import common/atmosphere_params.wgsl

@group(0) @binding(1) var table: texture_storage_2d<rgba32float, write>;

// Panels along each ray (`TABLE_PANELS`).
const PANELS: u32 = 64u;

// The 5-point Gauss-Legendre rule on [-1, 1] (`GAUSS_LEGENDRE_5`).
const GL5_NODES = array<f32, 5>(-0.906179845938664, -0.538469310105683, 0.0, 0.538469310105683, 0.906179845938664);
const GL5_WEIGHTS = array<f32, 5>(0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665, 0.2369268850561891);

// Value in [0, 1] of a texture coordinate whose first and last texel centres map to 0
// and 1 (Bruneton 2017 `GetUnitRangeFromTextureCoord`).
fn unit_from_coord(u: f32, size: f32) -> f32 {
    return (u - 0.5 / size) / (1.0 - 1.0 / size);
}

// Columns (Rayleigh, Mie, ozone) in metres from the point and direction of unit
// coordinates (x_mu, x_r) to the top boundary.
//
// In f32 a radius near 6.4e6 m carries 0.5 m of rounding, too much for a 1.2 km scale
// height, so neither r nor mu is formed where it would cancel. With H the horizon
// length sqrt(top^2 - bottom^2), rho = H x_r the horizon length at the ray's origin and
// d the distance to the top (Bruneton 2017 `GetRMuFromTransmittanceTextureUv`), the
// point at fraction s = t / d of the ray has
//     r(s)^2 - bottom^2 = (1 - s) rho^2 + s H^2 - s (1 - s) d^2
// (from r mu = (H^2 - rho^2 - d^2) / (2 d)), and its altitude is that over
// r(s) + bottom: a few millimetres of rounding instead of half a metre.
fn table_column(x_mu: f32, x_r: f32) -> vec3<f32> {
    let bottom = atmosphere.bottom_radius_m;
    let top = atmosphere.top_radius_m;
    let horizon_sq = (top - bottom) * (top + bottom);
    let horizon = sqrt(horizon_sq);
    let rho = horizon * x_r;
    let r = sqrt(rho * rho + bottom * bottom);
    // top - r as (H^2 - rho^2) / (top + r).
    let d_min = (horizon - rho) * (horizon + rho) / (top + r);
    let d_max = rho + horizon;
    let d = d_min + x_mu * (d_max - d_min);

    var column = vec3<f32>(0.0);
    for (var p = 0u; p < PANELS; p++) {
        var panel = vec3<f32>(0.0);
        for (var k = 0u; k < 5u; k++) {
            let s = (f32(p) + 0.5 + 0.5 * GL5_NODES[k]) / f32(PANELS);
            let q = (1.0 - s) * rho * rho + s * horizon_sq - s * (1.0 - s) * d * d;
            let altitude_m = q / (safe_sqrt(bottom * bottom + q) + bottom);
            panel += GL5_WEIGHTS[k] * densities(altitude_m);
        }
        column += panel;
    }
    // Each node's weight is half the panel length times its rule weight.
    return column * (0.5 * d / f32(PANELS));
}

// The columns (m) along the ray of texel `id`'s centre.
fn texel_column(id: vec2<u32>) -> vec3<f32> {
    let size = textureDimensions(table);
    let uv = (vec2<f32>(id) + 0.5) / vec2<f32>(size);
    return table_column(unit_from_coord(uv.x, f32(size.x)), unit_from_coord(uv.y, f32(size.y)));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(table)) {
        return;
    }
    textureStore(table, id.xy, vec4<f32>(exp(-optical_depth(texel_column(id.xy))), 1.0));
}

@compute @workgroup_size(8, 8)
fn columns(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(table)) {
        return;
    }
    textureStore(table, id.xy, vec4<f32>(texel_column(id.xy), 1.0));
}
