// Library: reading the columns table that `sky/transmittance_table.wgsl` builds with its
// `columns` entry point: the columns of matter (Rayleigh, Mie, ozone) from (r, mu) to the
// top of the atmosphere, bilinearly interpolated by hand (Rgba32Float need not be
// filterable), in the accurate variables of `common/frame_params.wgsl`: q = r^2 - bottom^2
// and mu. CPU twin: atmosphere-core's `optics/transmittance_table.rs`
// (`TransmittanceTable::column`) and `models/nishita.rs` (`sun_column`). Paper: the
// table g_l of Nishita et al. 1993 (Dobashi, Yamamoto and Nishita 2002, section 5,
// Eq. 11), in the parameterization of Bruneton 2017 (`GetTransmittanceTextureUvFromRMu`).

#import common/atmosphere_params.wgsl
#import common/texel_bilinear.wgsl

// Unit coordinates (x_mu, x_r) of the ray from r (with r^2 - bottom^2 = q) with cosine
// mu (`TransmittanceMapping::unit_from_r_mu`).
fn table_unit_from_q_mu(q: f32, r: f32, mu: f32) -> vec2<f32> {
    let top = atmosphere.top_radius_m;
    let bottom = atmosphere.bottom_radius_m;
    let horizon_sq = (top - bottom) * (top + bottom);
    let horizon = sqrt(horizon_sq);
    let rho = safe_sqrt(q);
    // distance_to_exit(r, mu, top) with r^2 - top^2 = q - H^2.
    let r_mu = r * mu;
    let root = safe_sqrt(r_mu * r_mu - q + horizon_sq);
    var d = max(-r_mu + root, 0.0);
    if mu > 0.0 {
        let s = r_mu + root;
        d = select(0.0, max((horizon_sq - q) / s, 0.0), s > 0.0);
    }
    let d_min = (horizon_sq - q) / (top + r);
    let d_max = rho + horizon;
    let x_mu = select(0.0, (d - d_min) / (d_max - d_min), d_max > d_min);
    return clamp(vec2<f32>(x_mu, rho / horizon), vec2<f32>(0.0), vec2<f32>(1.0));
}

// Columns (m) from (q, mu) to the top, for a ray that does not meet the ground.
fn table_columns(table: texture_2d<f32>, q: f32, mu: f32) -> vec3<f32> {
    let bottom = atmosphere.bottom_radius_m;
    let r = sqrt(bottom * bottom + q);
    let unit = table_unit_from_q_mu(q, r, mu);
    let size = vec2<f32>(textureDimensions(table));
    return texel_bilinear(table, unit * (size - 1.0));
}

// `table_columns` on the ground (q = 0, mu >= 0): the table's first row, the only one
// with weight there, interpolated along mu alone (two texel reads instead of four, the
// same value).
fn ground_columns(table: texture_2d<f32>, mu: f32) -> vec3<f32> {
    let bottom = atmosphere.bottom_radius_m;
    let width = textureDimensions(table).x;
    let f = table_unit_from_q_mu(0.0, bottom, mu).x * f32(width - 1u);
    let i = min(u32(f), width - 2u);
    let low = textureLoad(table, vec2<u32>(i, 0u), 0).xyz;
    let high = textureLoad(table, vec2<u32>(i + 1u, 0u), 0).xyz;
    return low + (f - f32(i)) * (high - low);
}

