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

// The cell and fraction of the table's rows at the light's distance `v` from the ray.
fn q_row(v: f32) -> vec2<f32> {
    return grid_cell(log(max(v, exp(qtable.ranges.z))), qtable.ranges.zw, qtable.nodes.y);
}

// q(u, v) at the three wavelengths, m^-2 sr^-1, v given by its rows (`q_row`).
fn q_at(u: f32, row: vec2<f32>) -> vec3<f32> {
    let x = grid_cell(asinh(u / qtable.interval_m.x), qtable.ranges.xy, qtable.nodes.x);
    let i = u32(x.x);
    let j = u32(row.x);
    let top = q_node(i, j) * (1.0 - x.y) + q_node(i + 1u, j) * x.y;
    let bottom = q_node(i, j + 1u) * (1.0 - x.y) + q_node(i + 1u, j + 1u) * x.y;
    return top * (1.0 - row.y) + bottom * row.y;
}

// What f_l shares along one view ray of one light, found once per ray: for a point light
// or spot, u of the camera in the frame of Fig. 2 (u along the ray from the foot of the
// light's perpendicular, v the light's distance from the ray) and the table's rows at v;
// the attenuation exp(-sigma_t dt) over one interval.
struct RayTable {
    u_camera: f32,
    row: vec2<f32>,
    attenuation_dt: vec3<f32>,
}

fn ray_table(light: BeamLight, dir: vec3<f32>) -> RayTable {
    var out: RayTable;
    let rel = -light.position.xyz;
    let along = dot(rel, dir);
    out.u_camera = along;
    out.row = q_row(length(rel - dir * along));
    out.attenuation_dt = exp(-params.extinction_per_m.xyz * qtable.interval_m.x);
    return out;
}

// f_l over `span_m` of the ray from the point `t` from the camera: Eq. 9's c_k q, the
// intervals past the first each attenuated by those before it, a part of one counting
// its share.
fn q_segment(ray: RayTable, t: f32, span_m: f32) -> vec3<f32> {
    let dt = qtable.interval_m.x;
    let u = ray.u_camera + t;
    var sum = vec3<f32>(0.0);
    var attenuation = vec3<f32>(1.0);
    var start = 0.0;
    while start < span_m {
        let share = min((span_m - start) / dt, 1.0);
        sum += attenuation * q_at(u + start, ray.row) * share;
        attenuation *= ray.attenuation_dt;
        start += dt;
    }
    return exp(-params.extinction_per_m.xyz * t) * sum;
}

// f_l of `light` over [t, t + span_m] of the camera's ray along the unit `dir`, what the
// ray shares (`ray_table`) found before.
fn f_l_on_ray(light: BeamLight, ray: RayTable, dir: vec3<f32>, t: f32, span_m: f32) -> vec3<f32> {
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
    return q_segment(ray, t, span_m);
}

// f_l of `light` over [t, t + span_m] of the camera's ray along the unit `dir`.
fn f_l(light: BeamLight, dir: vec3<f32>, t: f32, span_m: f32) -> vec3<f32> {
    return f_l_on_ray(light, ray_table(light, dir), dir, t, span_m);
}
