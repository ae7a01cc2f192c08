// Library: reading Rgba32Float tables through the texture unit's linear filter where the
// device filters that format, else texel by texel. render-wgpu's
// `sky/table_sampling.rs` sets `FILTERED_TABLES` when it makes the pipeline (so the other
// way is compiled out) and binds `table_sampler` at 29. CPU twin: the bilinear lookups of
// atmosphere-core's tables, which the unfiltered way repeats. No paper: numerics. Texel i
// of n lies at coordinate (i + 0.5) / n, so a fractional texel position f reads at
// (f + 0.5) / n: the same weights as interpolating by hand, up to the filter's precision.

#import common/transmittance_lookup.wgsl

override FILTERED_TABLES: bool = true;

@group(0) @binding(29) var table_sampler: sampler;

// The 2D table's bilinear value (rgb) at fractional texel position `f`, filtered.
fn sample_2d(table: texture_2d<f32>, f: vec2<f32>) -> vec3<f32> {
    return sample_2d_rgba(table, f).xyz;
}

// As `sample_2d`, all four channels.
fn sample_2d_rgba(table: texture_2d<f32>, f: vec2<f32>) -> vec4<f32> {
    let size = vec2<f32>(textureDimensions(table));
    return textureSampleLevel(table, table_sampler, (f + 0.5) / size, 0.0);
}

// The 3D table's trilinear value at fractional texel position `f`, filtered.
fn sample_3d(table: texture_3d<f32>, f: vec3<f32>) -> vec3<f32> {
    let size = vec3<f32>(textureDimensions(table));
    return textureSampleLevel(table, table_sampler, (f + 0.5) / size, 0.0).xyz;
}

// `table_columns`, filtered or not: one read instead of four.
fn read_table_columns(table: texture_2d<f32>, q: f32, mu: f32) -> vec3<f32> {
    if !FILTERED_TABLES {
        return table_columns(table, q, mu);
    }
    let bottom = atmosphere.bottom_radius_m;
    let unit = table_unit_from_q_mu(q, sqrt(bottom * bottom + q), mu);
    return sample_2d(table, unit * (vec2<f32>(textureDimensions(table)) - 1.0));
}

// `ground_columns`, filtered or not: one read instead of two.
fn read_ground_columns(table: texture_2d<f32>, mu: f32) -> vec3<f32> {
    if !FILTERED_TABLES {
        return ground_columns(table, mu);
    }
    let x = table_unit_from_q_mu(0.0, atmosphere.bottom_radius_m, mu).x;
    return sample_2d(table, vec2<f32>(x * f32(textureDimensions(table).x - 1u), 0.0));
}
