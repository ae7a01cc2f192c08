// Entry passes: the sampling planes of Dobashi et al. 2002 section 4.2 with the q(u, v)
// table, `vertex` and `fragment` (render-wgpu's `shafts/beams/qtable_pass.rs`). CPU
// twin: atmosphere-core's `beams/methods/qtable2002/mod.rs` (`radiance`).
//
// One instance per light, plane interval k and sample j < m_k (the main plane, j = 0,
// and its sub-planes, chosen on the CPU from f_l on the centre ray and epsilon) draws a
// plane at depth d_k + j dt / m_k over the rectangle of the screen that the light's
// bounding volume projects to (section 4.2.1's pyramid to d0). Each fragment adds its share of the
// interval's f_h f_l (Eq. 6): I_l H at its sample (Eq. 10's term: the light's
// distribution, light map and shadow map) over the samples in front of the ray's end,
// times f_l of the interval from the table (`q_table.wgsl`). Additive blending sums
// them. The interval on an oblique ray is dt / cos long; a plane within a thousandth of
// the ray's length of its end is left out, as on the CPU. With `weighted_samples` (not
// the paper's) a fragment's share is g at its sample over the sum of g at the visible
// samples (`sample_weights.wgsl`) instead of one over their count. Drawn planes are the
// same for every pixel, so `subplanes_per_ray` is refused here (`qtable_pass.rs`).

#import shafts/beams/bindings.wgsl
#import shafts/beams/qtable_bindings.wgsl
#import shafts/beams/plane_light.wgsl
#import shafts/beams/q_table.wgsl
#import shafts/beams/sample_weights.wgsl
#import shafts/beams/screen_rectangle.wgsl

struct PlaneSample {
    @builtin(position) position: vec4<f32>,
    // Light, interval k, sample j, samples m_k.
    @location(0) @interpolate(flat) plane: vec4<u32>,
    // The light's first plane's depth, m.
    @location(1) @interpolate(flat) first_depth_m: f32,
}

@vertex
fn vertex(
    @builtin(vertex_index) v: u32,
    @location(0) plane: vec4<u32>,
    @location(1) first_depth_m: f32,
    @location(2) bounds: vec4<f32>,
) -> PlaneSample {
    var out: PlaneSample;
    out.position = screen_rectangle_position(bounds, v);
    out.plane = plane;
    out.first_depth_m = first_depth_m;
    return out;
}

@fragment
fn fragment(in: PlaneSample) -> @location(0) vec4<f32> {
    let pixel = in.position.xy;
    let dir = pixel_direction(pixel);
    let cos_forward = dot(dir, params.camera_forward.xyz);
    let dt = qtable.interval_m.x;
    let dt_ray = dt / cos_forward;
    let t_k = (in.first_depth_m + f32(in.plane.y) * dt) / cos_forward;
    let t_end = textureLoad(ray_end, vec2<i32>(pixel), 0).x;
    if t_k >= t_end * (1.0 - 1e-3) {
        discard;
    }
    let span = min(dt_ray, t_end - t_k);
    let m = in.plane.w;
    let spacing = dt_ray / f32(m);
    // The sliver by the end's surface is left out for sub-planes as for planes.
    let visible = clamp(u32(ceil((t_end * (1.0 - 1e-3) - t_k) / spacing)), 1u, m);
    if in.plane.z >= visible {
        discard;
    }
    let point = dir * (t_k + f32(in.plane.z) * spacing);
    let light = lights[in.plane.x];
    let lit = plane_light(light, point);
    if !lit.lit {
        discard;
    }
    var share = vec3<f32>(1.0 / f32(visible));
    if qtable.interval_m.y > 0.5 {
        var base = -1.0;
        var own = vec3<f32>(0.0);
        var weight_sum = vec3<f32>(0.0);
        for (var j = 0u; j < visible; j++) {
            let g = smooth_factor(light, dir, t_k + f32(j) * spacing, base);
            base = select(base, g.w, base < 0.0);
            weight_sum += g.xyz;
            if j == in.plane.z {
                own = g.xyz;
            }
        }
        share = select(vec3<f32>(0.0), own / weight_sum, weight_sum > vec3<f32>(0.0));
    }
    return vec4<f32>(lit.light * share * f_l(light, dir, t_k, span), 0.0);
}
