// Library: a light's visibility from its shadow map (Williams 1978; the shadow maps of
// Dobashi, Yamamoto and Nishita 2000 section 5.2): the point's distance from the light
// against the stored depth plus a bias of two texels' width there, four texels compared
// and blended bilinearly (percentage-closer filtering). Points outside every view are
// lit but for the infinite planes, tested exactly. CPU twin: atmosphere-core's
// `beams/shadow_map.rs` (`ShadowMap::visibility`, `View::lookup`, `Projection::project`).

#import shafts/beams/bindings.wgsl
#import shafts/beams/occluders.wgsl

struct Projected {
    inside: bool,
    uv: vec2<f32>,
    depth_m: f32,
    texel_m: f32,
}

fn project(view: ShadowView, point: vec3<f32>) -> Projected {
    var out: Projected;
    out.inside = false;
    let rel = point - view.origin.xyz;
    let l = vec3<f32>(dot(rel, view.frame_x.xyz), dot(rel, view.frame_y.xyz), dot(rel, view.frame_z.xyz));
    if view.kind == 0u {
        let tan_half = view.origin.w;
        if l.z <= 0.0 {
            return out;
        }
        let distance = length(l);
        out.uv = vec2<f32>(0.5 + 0.5 * l.x / (l.z * tan_half), 0.5 - 0.5 * l.y / (l.z * tan_half));
        out.depth_m = distance;
        out.texel_m = distance * 2.0 * tan_half / f32(view.size);
    } else {
        out.uv = vec2<f32>(0.5 + 0.5 * l.x / view.half.x, 0.5 - 0.5 * l.y / view.half.y);
        out.depth_m = l.z;
        out.texel_m = 2.0 * max(view.half.x, view.half.y) / f32(view.size);
    }
    out.inside = all(out.uv >= vec2<f32>(0.0)) && all(out.uv <= vec2<f32>(1.0));
    return out;
}

fn texel_lit(view: ShadowView, i: f32, j: f32, depth: f32, bias: f32) -> f32 {
    let n = f32(view.size);
    let column = u32(clamp(i, 0.0, n - 1.0));
    let row = u32(clamp(j, 0.0, n - 1.0));
    let stored = shadow_depths[view.offset + row * view.size + column];
    return select(0.0, 1.0, depth <= stored + bias);
}

// The lit fraction in [0, 1] of `point` on the way `to_light` (`distance_m` long).
fn shadow_visibility(light: BeamLight, point: vec3<f32>, to_light: vec3<f32>, distance_m: f32) -> f32 {
    if light.view_count == 0u {
        return 1.0;
    }
    for (var k = 0u; k < light.view_count; k++) {
        let view = shadow_views[light.first_view + k];
        let p = project(view, point);
        if !p.inside {
            continue;
        }
        let n = f32(view.size);
        let x = p.uv.x * n - 0.5;
        let y = p.uv.y * n - 0.5;
        let x0 = floor(x);
        let y0 = floor(y);
        let fx = x - x0;
        let fy = y - y0;
        let bias = 2.0 * p.texel_m;
        let top = texel_lit(view, x0, y0, p.depth_m, bias) * (1.0 - fx)
            + texel_lit(view, x0 + 1.0, y0, p.depth_m, bias) * fx;
        let bottom = texel_lit(view, x0, y0 + 1.0, p.depth_m, bias) * (1.0 - fx)
            + texel_lit(view, x0 + 1.0, y0 + 1.0, p.depth_m, bias) * fx;
        return top * (1.0 - fy) + bottom * fy;
    }
    return select(1.0, 0.0, planes_block(point, to_light, distance_m));
}
