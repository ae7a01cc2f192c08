// Library: f_l, the smooth factor of one plane interval of a view ray (Dobashi et al.
// 2002 Eq. 7), from the pre-integrated table q(u, v) of their Eq. 8-9 for a point light
// or spot, in closed form for a parallel light. CPU twins: atmosphere-core's
// `beams/methods/qtable2002/q_table.rs` (`QTable::q`, `QTable::segment`: nodes even in
// asinh(u / dt) and ln v, bilinear between them, the nearest edge outside) and
// `qtable2002/interval.rs` (`f_l`, `light_frame_uv`).

#import shafts/beams/bindings.wgsl
#import shafts/beams/qtable_bindings.wgsl
#import shafts/beams/phase.wgsl

fn q_node(i: u32, j: u32) -> vec3<f32> {
    return textureLoad(q_table, vec2<u32>(i, j), 0).xyz;
}

// The node index below `value` on a grid of `n` nodes over `range`, and the fraction.
fn grid_cell(value: f32, range: vec2<f32>, n: u32) -> vec2<f32> {
    let last = f32(n - 1u);
    let f = clamp((value - range.x) / (range.y - range.x) * last, 0.0, last);
    let i = min(floor(f), last - 1.0);
    return vec2<f32>(i, f - i);
}

// q(u, v) at the three wavelengths, m^-2 sr^-1.
fn q_at(u: f32, v: f32) -> vec3<f32> {
    let x = grid_cell(asinh(u / qtable.interval_m.x), qtable.ranges.xy, qtable.nodes.x);
    let y = grid_cell(log(max(v, exp(qtable.ranges.z))), qtable.ranges.zw, qtable.nodes.y);
    let i = u32(x.x);
    let j = u32(y.x);
    let top = q_node(i, j) * (1.0 - x.y) + q_node(i + 1u, j) * x.y;
    let bottom = q_node(i, j + 1u) * (1.0 - x.y) + q_node(i + 1u, j + 1u) * x.y;
    return top * (1.0 - y.y) + bottom * y.y;
}

// f_l over `span_m` of the ray from the point `t` from the camera at (u, v): Eq. 9's
// c_k q, the intervals past the first each attenuated by those before it, a part of one
// counting its share.
fn q_segment(t: f32, u: f32, v: f32, span_m: f32) -> vec3<f32> {
    let dt = qtable.interval_m.x;
    let sigma_t = params.extinction_per_m.xyz;
    var sum = vec3<f32>(0.0);
    var start = 0.0;
    while start < span_m {
        let share = min((span_m - start) / dt, 1.0);
        sum += exp(-sigma_t * start) * q_at(u + start, v) * share;
        start += dt;
    }
    return exp(-sigma_t * t) * sum;
}

// f_l of `light` over [t, t + span_m] of the camera's ray along the unit `dir`.
fn f_l(light: BeamLight, dir: vec3<f32>, t: f32, span_m: f32) -> vec3<f32> {
    if light.kind == 2u {
        let along = dot(light.frame_z.xyz, dir);
        let s0 = max(dot(light.frame_z.xyz, dir * t - light.position.xyz), 0.0);
        let sigma_t = params.extinction_per_m.xyz;
        let k = sigma_t * (1.0 + along);
        let kl = k * span_m;
        // (1 - exp(-k L)) / k, by its series where k L is small (f32 loses it there).
        let series = span_m * (1.0 - 0.5 * kl);
        let integral = select((1.0 - exp(-kl)) / k, series, kl < vec3<f32>(1e-3));
        return params.scattering_per_m.xyz * beams_phase(-along) * exp(-sigma_t * (s0 + t))
            * integral;
    }
    // The frame of Fig. 2: u along the ray from the foot of the light's perpendicular,
    // v the light's distance from the ray (the camera at the origin).
    let rel = -light.position.xyz;
    let along = dot(rel, dir);
    let v = length(rel - dir * along);
    return q_segment(t, along + t, v, span_m);
}
