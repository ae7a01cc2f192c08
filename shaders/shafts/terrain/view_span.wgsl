// Library: the part of a view segment the terrain's shadow can reach and the samples
// that read the shadow map along it. CPU twin: atmosphere-core's `shafts/view_span.rs`
// (`shaft_span_m`, `shaft_samples`, `shadowed_length_m`); method: docs/shafts.md.

#import common/atmosphere_params.wgsl
#import common/frame_params.wgsl
#import shafts/terrain/shadow_map.wgsl

// `shaft_span_m`: x, y the distances from the segment's start where it enters and
// leaves the sphere of the shadow volume's top (x = 0 from inside it), at most the
// outermost level's width and the segment; y <= x when it never dips below it. (r - top)(r + top) is
// written as q - h (2 bottom + h) for f32.
fn shaft_span(m: ShadowMapParams, s: Segment) -> vec2<f32> {
    return span_below(s, m.up_top.w, shadow_map_width(m));
}

// `shaft_span_m` under the sphere `h` (m) above the ground, at most `width` (m) long.
fn span_below(s: Segment, h: f32, width: f32) -> vec2<f32> {
    let above = s.q - h * (2.0 * atmosphere.bottom_radius_m + h);
    let disc = s.r_mu * s.r_mu - above;
    if disc < 0.0 {
        return vec2<f32>(0.0);
    }
    let exit = -s.r_mu + sqrt(disc);
    var entry = 0.0;
    if above > 0.0 && exit > 0.0 {
        entry = above / exit;
    }
    return vec2<f32>(entry, min(exit, min(s.length, width)));
}

// `shaft_samples`: two per cell of the outermost level (`ShadowMap::sample_cell_m`),
// within the fewest (w) and the most (z).
fn shaft_samples(m: ShadowMapParams, span: f32) -> u32 {
    let per_cell = u32(ceil(2.0 * span * f32(m.size.x) / shadow_map_width(m)));
    return min(max(per_cell, m.size.w), m.size.z);
}

// `shaft_samples` over `span` (m) in cells `cell` (m) wide, within the fewest (w) and
// the most (z) of `m`.
fn samples_per_cell(m: ShadowMapParams, span: f32, cell: f32) -> u32 {
    let per_cell = u32(ceil(2.0 * span / cell));
    return min(max(per_cell, m.size.w), m.size.z);
}

// `shadowed_length_m`: the midpoint rule of 1 - V over the span, m; 0 without shafts.
fn shadowed_length(tops: texture_2d<f32>, m: ShadowMapParams, s: Segment, direction: vec3<f32>) -> f32 {
    if m.size.y == 0u {
        return 0.0;
    }
    let span = shaft_span(m, s);
    if span.y <= span.x {
        return 0.0;
    }
    let samples = shaft_samples(m, span.y - span.x);
    let dt = (span.y - span.x) / f32(samples);
    let bottom = atmosphere.bottom_radius_m;
    var shadowed = 0.0;
    for (var k = 0u; k < samples; k++) {
        let t = span.x + (f32(k) + 0.5) * dt;
        let q = s.q + t * (t + 2.0 * s.r_mu);
        let altitude = q / (sqrt(bottom * bottom + q) + bottom);
        let position = s.start + t * direction;
        shadowed += (1.0 - shadow_map_visible(tops, m, bottom, position, altitude)) * dt;
    }
    return shadowed;
}
